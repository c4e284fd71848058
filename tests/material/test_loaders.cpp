// refractiveindex.info YAML and CSV loaders on every shared data file, and on malformed input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "spectrum/test_data.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/refractive_index.hpp"
#include "surfscatter/material/refractiveindex_info.hpp"
#include "surfscatter/material/tabulated_index.hpp"

namespace sm = surfscatter::material;
using surfscatter::test::read_shared_csv;
using surfscatter::test::shared_data;
using surfscatter::test::write_temp_file;

namespace {

// Message of the Error thrown by loading `text` as a file with `extension`; "" if none.
std::string load_error(const std::string& text, const std::string& extension) {
    const std::string path = write_temp_file(text, extension);
    std::string message;
    try {
        sm::load_refractive_index(path);
    } catch (const surfscatter::Error& e) {
        message = e.what();
    }
    std::remove(path.c_str());
    return message;
}

}  // namespace

TEST(RefractiveIndexInfo, EveryDatabaseFileLoadsAndReproducesItsRows) {
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(shared_data("refractiveindex"))) {
        if (entry.path().extension() != ".yml") continue;
        ++files;
        const std::string path = entry.path().string();
        const auto ior = sm::load_refractive_index(path);
        EXPECT_LT(ior->min_wavelength_nm(), ior->max_wavelength_nm()) << path;
        // Every tabulated row "lambda_um n k" of the file is reproduced exactly at its own wavelength.
        std::ifstream in(path);
        int rows = 0;
        for (std::string line; std::getline(in, line);) {
            std::istringstream fields(line);
            double lambda_um, n, k;
            if (!(fields >> lambda_um >> n >> k) || !(fields >> std::ws).eof()) continue;
            const auto v = ior->at(lambda_um * 1000.0);
            EXPECT_NEAR(v.real(), n, 1e-12 * n) << path << " " << lambda_um;
            EXPECT_NEAR(v.imag(), k, 1e-12 * k) << path << " " << lambda_um;
            ++rows;
        }
        if (path.find("Malitson") == std::string::npos) {
            EXPECT_GT(rows, 10) << path;
        }
    }
    EXPECT_EQ(files, 14);
}

TEST(RefractiveIndexInfo, JohnsonChristyGoldMatchesSharedCsvAndInterpolates) {
    const auto yml = sm::load_refractive_index(shared_data("refractiveindex/Au_Johnson.yml"));
    const auto csv = sm::load_refractive_index(shared_data("optical_constants/gold.csv"));
    for (const auto& r : read_shared_csv("optical_constants/gold.csv")) {
        EXPECT_NEAR(yml->at(r[0]).real(), r[1], 1e-12);
        EXPECT_NEAR(csv->at(r[0]).imag(), r[2], 1e-12);
    }
    // README spot check: 600 nm between 582.1 nm (0.29, 2.863) and 616.8 nm (0.21, 3.272) -> about 0.25 + 3.07i.
    const auto v = yml->at(600.0);
    const double t = (600.0 - 582.1) / (616.8 - 582.1);
    EXPECT_NEAR(v.real(), 0.29 + t * (0.21 - 0.29), 1e-12);
    EXPECT_NEAR(v.imag(), 2.863 + t * (3.272 - 2.863), 1e-12);
    EXPECT_NEAR(v.imag(), 3.07, 0.01);
}

TEST(RefractiveIndexInfo, SellmeierFormulaOfFusedSilica) {
    const auto silica = sm::load_refractive_index(shared_data("refractiveindex/SiO2_Malitson.yml"));
    // Malitson 1965: n = 1.45846 at the helium d line (587.56 nm), 1.45637 at 632.8 nm; no absorption.
    EXPECT_NEAR(silica->at(587.5618).real(), 1.45846, 2e-5);
    EXPECT_NEAR(silica->at(632.8).real(), 1.45702, 2e-5);
    EXPECT_EQ(silica->at(587.5618).imag(), 0.0);
    EXPECT_NEAR(silica->min_wavelength_nm(), 210.0, 1e-9);
    EXPECT_NEAR(silica->max_wavelength_nm(), 6700.0, 1e-9);
    EXPECT_THROW(silica->at(200.0), surfscatter::Error);
}

TEST(RefractiveIndexInfo, DispersionFormulasAgainstHandEvaluation) {
    const double l = 0.55, l2 = l * l;
    // 2: Sellmeier-2 with C3 = 0.0684043^2 equals formula 1.
    EXPECT_NEAR(sm::dispersion_formula_index(2, {0, 0.6961663, 0.0684043 * 0.0684043}, l),
                sm::dispersion_formula_index(1, {0, 0.6961663, 0.0684043}, l), 1e-14);
    EXPECT_NEAR(sm::dispersion_formula_index(3, {2.0, 0.01, -2}, l), std::sqrt(2.0 + 0.01 / l2), 1e-14);
    EXPECT_NEAR(sm::dispersion_formula_index(4, {2.0, 0.1, 2, 0.2, 2, 0, 0, 0, 0, 0.01, 1}, l),
                std::sqrt(2.0 + 0.1 * l2 / (l2 - 0.04) + 0.01 * l), 1e-14);
    EXPECT_NEAR(sm::dispersion_formula_index(5, {1.5, 0.004, -2}, l), 1.5 + 0.004 / l2, 1e-14);
    EXPECT_NEAR(sm::dispersion_formula_index(6, {0, 0.05792105, 238.0185, 0.00167917, 57.362}, l),
                1 + 0.05792105 / (238.0185 - 1 / l2) + 0.00167917 / (57.362 - 1 / l2), 1e-14);  // air, Ciddor
    const double d = 1 / (l2 - 0.028);
    EXPECT_NEAR(sm::dispersion_formula_index(7, {1.5, 0.01, 0.001, -0.002, 1e-4, -1e-5}, l),
                1.5 + 0.01 * d + 0.001 * d * d - 0.002 * l2 + 1e-4 * l2 * l2 - 1e-5 * l2 * l2 * l2, 1e-14);
    const double a = 0.2 + 0.1 * l2 / (l2 - 0.01) + 0.001 * l2;
    EXPECT_NEAR(sm::dispersion_formula_index(8, {0.2, 0.1, 0.01, 0.001}, l), std::sqrt((1 + 2 * a) / (1 - a)), 1e-14);
    EXPECT_NEAR(sm::dispersion_formula_index(9, {2.0, 0.02, 0.01, 0.1, 0.3, 0.05}, l),
                std::sqrt(2.0 + 0.02 / (l2 - 0.01) + 0.1 * (l - 0.3) / ((l - 0.3) * (l - 0.3) + 0.05)), 1e-14);
    EXPECT_THROW(sm::dispersion_formula_index(10, {1.0}, l), surfscatter::Error);
    EXPECT_THROW(sm::dispersion_formula_index(8, {1, 2, 3, 4, 5}, l), surfscatter::Error);
    EXPECT_THROW(sm::dispersion_formula_index(3, {-4.0}, l), surfscatter::Error);  // n^2 < 0
}

TEST(RefractiveIndexInfo, SeparateNAndKEntries) {
    const std::string text =
        "DATA:\n  - type: formula 2\n    wavelength_range: 0.3 1.0\n    coefficients: 1.0\n"
        "  - type: tabulated k\n    data: |\n        0.4 0.1\n        0.8 0.3\n";
    const std::string path = write_temp_file(text, ".yml");
    const auto ior = sm::load_refractive_index(path);
    EXPECT_NEAR(ior->at(600).real(), std::sqrt(2.0), 1e-14);
    EXPECT_NEAR(ior->at(600).imag(), 0.2, 1e-14);
    EXPECT_NEAR(ior->min_wavelength_nm(), 400, 1e-9);  // intersection of both ranges
    EXPECT_NEAR(ior->max_wavelength_nm(), 800, 1e-9);
    std::remove(path.c_str());
}

TEST(RefractiveIndexInfo, MalformedFilesNameTheProblem) {
    EXPECT_NE(load_error("DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.0 2.0\n        0.5 x 2.1\n", ".yml")
                  .find(".yml:5: 'x' is not a number"), std::string::npos);
    EXPECT_NE(load_error("DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.0\n        0.5 1.1\n", ".yml")
                  .find("expected 3 numbers per row"), std::string::npos);
    EXPECT_NE(load_error("DATA:\n  - type: tabulated nk\n    data: |\n        0.5 1.0 2.0\n        0.4 1.1 2.1\n", ".yml")
                  .find("increase"), std::string::npos);
    EXPECT_NE(load_error("DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.0 -2.0\n        0.5 1.1 2.1\n", ".yml")
                  .find("negative"), std::string::npos);
    EXPECT_NE(load_error("DATA:\n  - type: spline\n", ".yml").find("unknown type 'spline'"), std::string::npos);
    EXPECT_NE(load_error("DATA:\n  - type: formula 12\n    wavelength_range: 0.3 1\n    coefficients: 1\n", ".yml")
                  .find("formula 12"), std::string::npos);
    EXPECT_NE(load_error("REFERENCES: x\n", ".yml").find("no DATA"), std::string::npos);
    EXPECT_NE(load_error("DATA: [unclosed\n", ".yml").find("malformed YAML"), std::string::npos);
    EXPECT_NE(load_error("DATA:\n  - type: tabulated k\n    data: |\n        0.4 0.1\n        0.8 0.3\n", ".yml")
                  .find("no n"), std::string::npos);
}

TEST(RefractiveIndexInfo, ConflictsAndValuesOutsideThePhysicalDomainAreErrors) {
    // A key given twice in any mapping names both lines (yaml-cpp would find the first and ignore the second).
    const std::string twice = load_error("DATA:\n  - type: tabulated nk\n    type: tabulated n\n    data: |\n"
                                         "        0.4 1 2\n        0.5 1 2\n", ".yml");
    EXPECT_NE(twice.find(".yml:3: key 'type' is given twice in one mapping (first at line 2)"), std::string::npos) << twice;
    // n and k of every tabulated kind are >= 0: 'tabulated k' was not checked at all.
    const std::string n = load_error("DATA:\n  - type: tabulated n\n    data: |\n        0.4 1\n        0.5 -1\n", ".yml");
    EXPECT_NE(n.find(".yml:5: n = -1 is negative"), std::string::npos) << n;
    const std::string k = load_error("DATA:\n  - type: formula 2\n    wavelength_range: 0.3 1.0\n    coefficients: 1.0\n"
                                     "  - type: tabulated k\n    data: |\n        0.4 -0.1\n        0.8 0.3\n", ".yml");
    EXPECT_NE(k.find(".yml:7: k = -0.1 is negative"), std::string::npos) << k;
    // A subnormal number is named as what it is.
    const std::string tiny = load_error("DATA:\n  - type: tabulated nk\n    data: |\n        4e-320 1 2\n        0.5 1 2\n",
                                        ".yml");
    EXPECT_NE(tiny.find(".yml:4: '4e-320' is too small (subnormal, below 2.22507e-308)"), std::string::npos) << tiny;
    // Equal keys in different mappings are no conflict.
    const std::string path = write_temp_file("DATA:\n  - type: tabulated n\n    data: |\n        0.4 1\n        0.5 1\n"
                                             "  - type: tabulated k\n    data: |\n        0.4 2\n        0.5 2\n", ".yml");
    EXPECT_NEAR(sm::load_refractive_index(path)->at(450).imag(), 2.0, 1e-14);
    std::remove(path.c_str());
}

TEST(CsvIndex, ReadsCommentsHeaderAndRows) {
    const std::string path = write_temp_file("# comment\nwavelength_nm,n,k\n400,1.0,2.0\n\n500,1.2,3.0E+00\n", ".csv");
    const auto ior = sm::load_refractive_index(path);
    EXPECT_NEAR(ior->at(450).real(), 1.1, 1e-14);
    EXPECT_NEAR(ior->at(450).imag(), 2.5, 1e-14);
    try {
        ior->at(550);
        FAIL();
    } catch (const surfscatter::Error& e) {
        EXPECT_NE(std::string(e.what()).find("wavelength 550 nm is outside the range 400-500 nm of " + path),
                  std::string::npos) << e.what();
    }
    std::remove(path.c_str());
}

TEST(CsvIndex, EverySharedOpticalConstantsFileLoads) {
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(shared_data("optical_constants"))) {
        if (entry.path().extension() != ".csv") continue;
        ++files;
        const auto ior = sm::load_refractive_index(entry.path().string());
        EXPECT_LE(ior->min_wavelength_nm(), 360.0) << entry.path();
        EXPECT_GE(ior->max_wavelength_nm(), 830.0) << entry.path();
    }
    EXPECT_EQ(files, 19);
}

TEST(CsvIndex, MalformedFilesNameFileAndLine) {
    EXPECT_NE(load_error("wavelength_nm,n,k\n400,1,2\n500,1,abc\n", ".csv").find(".csv:3:"), std::string::npos);
    EXPECT_NE(load_error("400,1,2\n500,1\n", ".csv").find(".csv:2:"), std::string::npos);
    EXPECT_NE(load_error("400,1,2\n300,1,2\n", ".csv").find("does not increase"), std::string::npos);
    EXPECT_NE(load_error("400,1,2\n500,1,-2\n", ".csv").find(".csv:2: k = -2 is negative (N = n + i k needs n >= 0 and k >= 0)"),
              std::string::npos);
    EXPECT_NE(load_error("400,1,2\n500,-1,2\n", ".csv").find(".csv:2: n = -1 is negative"), std::string::npos);
    EXPECT_NE(load_error("400,1,2\n500,nan,2\n", ".csv").find(".csv:2:"), std::string::npos);
    EXPECT_NE(load_error("400,1,2\n", ".csv").find("at least two rows"), std::string::npos);
    EXPECT_NE(load_error("-400,1,2\n500,1,2\n", ".csv").find("not positive"), std::string::npos);
}

TEST(LoadRefractiveIndex, UnknownNamesAndMissingFiles) {
    try {
        sm::load_refractive_index("Unobtainium");
        FAIL();
    } catch (const surfscatter::Error& e) {
        EXPECT_NE(std::string(e.what()).find("unknown material 'Unobtainium'"), std::string::npos) << e.what();
    }
    EXPECT_THROW(sm::load_refractive_index("/nonexistent/gold.csv"), surfscatter::Error);
    EXPECT_THROW(sm::load_refractive_index("/nonexistent/gold.yml"), surfscatter::Error);
    EXPECT_THROW(sm::load_refractive_index("au"), surfscatter::Error);  // names are case-sensitive
}
