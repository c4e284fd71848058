// Built-in Lorentz-Drude metals (Rakic et al. 1998) against the refractiveindex.info Rakic-LD tables, our shared
// evaluation in optical_constants/rakic1998_ld, and measured data (Johnson & Christy etc.).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "spectrum/test_data.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/lorentz_drude.hpp"
#include "surfscatter/material/refractive_index.hpp"

namespace sm = surfscatter::material;
using surfscatter::test::read_shared_csv;
using surfscatter::test::shared_data;

TEST(LorentzDrude, ElevenBuiltInMetals) {
    const std::vector<std::string> expected = {"Ag", "Al", "Au", "Be", "Cr", "Cu", "Ni", "Pd", "Pt", "Ti", "W"};
    EXPECT_EQ(sm::builtin_metal_names(), expected);
}

TEST(LorentzDrude, MatchesRefractiveIndexInfoTablesTo1e3) {
    // Database files with rows "lambda_um n k" (5 significant digits).
    for (const std::string metal : {"Ag", "Al", "Au", "Cu"}) {
        std::ifstream in(shared_data("refractiveindex/" + metal + "_Rakic-LD.yml"));
        const auto ior = sm::load_refractive_index(metal);
        int rows = 0;
        double max_error = 0;
        for (std::string line; std::getline(in, line);) {
            std::istringstream fields(line);
            double lambda_um, n, k;
            if (!(fields >> lambda_um >> n >> k)) continue;
            const double lambda_nm = lambda_um * 1000.0;
            if (lambda_nm < ior->min_wavelength_nm() || lambda_nm > ior->max_wavelength_nm()) continue;
            const auto v = ior->at(lambda_nm);
            max_error = std::max({max_error, std::abs(v.real() - n) / n, std::abs(v.imag() - k) / k});
            ++rows;
        }
        EXPECT_GT(rows, 50) << metal;
        EXPECT_LT(max_error, 1e-3) << metal;  // measured: 2.0e-4 (Ag), the tables print 5 digits
    }
}

TEST(LorentzDrude, MatchesSharedEvaluationInTheVisible) {
    const std::map<std::string, std::string> files = {{"Ag", "silver"},   {"Al", "aluminium"}, {"Au", "gold"},
                                                      {"Cr", "chromium"}, {"Cu", "copper"},    {"Ni", "nickel"},
                                                      {"Pt", "platinum"}, {"Ti", "titanium"},  {"W", "tungsten"}};
    for (const auto& [metal, file] : files) {
        const auto ior = sm::load_refractive_index(metal);
        const auto rows = read_shared_csv("optical_constants/rakic1998_ld/" + file + ".csv");
        ASSERT_GT(rows.size(), 90u) << file;
        for (const auto& r : rows) {
            const auto v = ior->at(r[0]);
            // 6 decimals in the file.
            EXPECT_NEAR(v.real(), r[1], 1e-6 + 1e-9 * r[1]) << metal << " " << r[0];
            EXPECT_NEAR(v.imag(), r[2], 1e-6 + 1e-9 * r[2]) << metal << " " << r[0];
        }
    }
}

TEST(LorentzDrude, CloseToMeasuredDataInTheVisible) {
    // LD is a fit to several data sets, so only rough agreement with one measured sample is expected. Compared
    // through the normal-incidence reflectance R = |(N-1)/(N+1)|^2 at the measured rows in 450-750 nm: mean and
    // maximum |R_LD - R_measured|. Measured (mean, max): Au 0.041, 0.069; Ag 0.036, 0.061; Al 0.003, 0.008;
    // Ni 0.041, 0.057; Ti 0.029, 0.047; W 0.004, 0.007; Cu 0.058, 0.158 (J&C have 3 points across the 520-620 nm
    // edge); Cr 0.091, 0.099; Pt 0.088, 0.099 (Tselin 2024 data: k 15-20 % above the older data LD was fitted to).
    struct Case { std::string metal, file; double mean_tolerance, max_tolerance; };
    const Case cases[] = {{"Au", "gold", 0.05, 0.08},       {"Ag", "silver", 0.05, 0.08},
                          {"Al", "aluminium", 0.01, 0.02},  {"Ni", "nickel", 0.05, 0.08},
                          {"Ti", "titanium", 0.05, 0.08},   {"W", "tungsten", 0.01, 0.02},
                          {"Cu", "copper", 0.07, 0.17},     {"Cr", "chromium", 0.1, 0.11},
                          {"Pt", "platinum", 0.1, 0.11}};
    const auto reflectance = [](std::complex<double> n) { return std::norm((n - 1.0) / (n + 1.0)); };
    for (const auto& c : cases) {
        const auto ior = sm::load_refractive_index(c.metal);
        double max_difference = 0, sum = 0;
        int count = 0;
        for (const auto& r : read_shared_csv("optical_constants/" + c.file + ".csv")) {
            if (r[0] < 450 || r[0] > 750) continue;
            const double difference = std::abs(reflectance(ior->at(r[0])) - reflectance({r[1], r[2]}));
            max_difference = std::max(max_difference, difference);
            sum += difference;
            ++count;
        }
        ASSERT_GT(count, 3) << c.metal;
        EXPECT_LT(sum / count, c.mean_tolerance) << c.metal;
        EXPECT_LT(max_difference, c.max_tolerance) << c.metal;
    }
}

TEST(LorentzDrude, IndexHasPositiveKAndStaysFiniteOverItsRange) {
    for (const auto& name : sm::builtin_metal_names()) {
        const auto ior = sm::load_refractive_index(name);
        const double lo = ior->min_wavelength_nm(), hi = ior->max_wavelength_nm();
        EXPECT_LE(lo, 360.0) << name;
        EXPECT_GE(hi, 830.0) << name;
        for (int i = 0; i <= 200; ++i) {
            const double lambda = lo * std::pow(hi / lo, i / 200.0);
            const auto v = ior->at(std::clamp(lambda, lo, hi));
            EXPECT_TRUE(std::isfinite(v.real()) && std::isfinite(v.imag())) << name << " " << lambda;
            EXPECT_GE(v.imag(), 0.0) << name << " " << lambda;
            EXPECT_GE(v.real(), 0.0) << name << " " << lambda;
        }
    }
}

TEST(LorentzDrude, OutsideTheFitRangeIsAnErrorNamingWavelengthAndRange) {
    const auto au = sm::load_refractive_index("Au");
    EXPECT_NEAR(au->min_wavelength_nm(), 247.968, 1e-3);  // 5 eV
    EXPECT_NEAR(au->max_wavelength_nm(), 6199.21, 1e-2);  // 0.2 eV
    try {
        au->at(200.0);
        FAIL();
    } catch (const surfscatter::Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("200 nm"), std::string::npos) << message;
        EXPECT_NE(message.find("247.968-6199.21 nm"), std::string::npos) << message;
        EXPECT_NE(message.find("Au"), std::string::npos) << message;
    }
    EXPECT_THROW(au->at(std::nan("")), surfscatter::Error);
    EXPECT_THROW(au->at(-500), surfscatter::Error);
    EXPECT_THROW(au->at(0), surfscatter::Error);
}

TEST(LorentzDrude, PermittivityBranch) {
    // eps with Im >= 0 -> N in the first quadrant; a pure Drude metal below the plasma energy has Re(eps) < 0.
    const auto n = sm::index_from_permittivity({-10.0, 1.0});
    EXPECT_GT(n.imag(), 3.0);
    EXPECT_GT(n.real(), 0.0);
    EXPECT_NEAR(std::norm(n * n - std::complex<double>(-10.0, 1.0)), 0.0, 1e-24);
    const auto real = sm::index_from_permittivity({2.25, 0.0});
    EXPECT_DOUBLE_EQ(real.real(), 1.5);
    EXPECT_DOUBLE_EQ(real.imag(), 0.0);
}
