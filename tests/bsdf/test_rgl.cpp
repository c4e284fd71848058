// The RGL measured format (bsdf/rgl_measured.hpp): the seven real files of RGL's database read, each checked against
// its own fields' invariants computed here (luminance = Rec. 709 Y of the rgb table; sigma = projected area of the
// ndf, by quadrature; the VNDF slices = D(m) <wi, m> / sigma over u_m, up to the table's own discretisation); a
// write + read round trip is exact; the `measured` sampler passes chi-square tests on real files.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "chi2_harness.hpp"
#include "surfscatter/bsdf/rgl_measured.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

const std::filesystem::path kRgl = std::filesystem::path(SURFSCATTER_SHARED_DATA) / "realdata" / "rgl";

struct RealFile {
    const char* name;
    const char* description;
};
const RealFile kFiles[] = {
    {"cc_ibiza_sunset_rgb.bsdf", "TeckWrap vinyl wrapping film (Ibiza Sunset RD02)"},
    {"cc_iris_purple_gem_rgb.bsdf", "TeckWrap vinyl wrapping film (Iris Purple Gem RD03)"},
    {"cg_sunflower_rgb.bsdf", "TeckWrap vinyl wrapping film (Sunflower CG12)"},
    {"colodur_napoli_4f_rgb.bsdf", "Coop Colodur wall paint sample swatch (Napoli 4F)"},
    {"paper_white_rgb.bsdf", "White A4 paper (160 gsm)"},
    {"satin_rosaline_rgb.bsdf", "TeckWrap vinyl wrapping film (Rosaline Satin CK904)"},
    {"vch_golden_yellow_rgb.bsdf", "TeckWrap vinyl wrapping film (Golden Yellow VCH508N)"},
};

// Linear interpolation of an isotropic table row over u = sqrt(2 theta / pi) at nodes k / (n - 1) (the format's
// definition of its ndf and sigma tables), written out here rather than through Marginal2D.
double row_at(const std::vector<double>& row, std::size_t n, double theta) {
    const double x = std::sqrt(theta * 2 / kPi) * double(n - 1);
    const std::size_t i = std::min(std::size_t(x), n - 2);
    const double w = x - double(i);
    return row[i] * (1 - w) + row[i + 1] * w;
}

// int D(m) max(0, wi . m) dm for the isotropic ndf row: Gauss-Legendre over u_m (one panel per table cell, where D is
// linear) and over phi_m.
double projected_area(const std::vector<double>& ndf, std::size_t n, double theta_i) {
    const math::GaussLegendreRule rule(8);
    const Vec3 wi = spherical_direction(theta_i, 0.0);
    double sum = 0;
    for (std::size_t cell = 0; cell + 1 < n; ++cell)
        for (std::size_t a = 0; a < rule.nodes.size(); ++a) {
            const double u = (double(cell) + 0.5 + 0.5 * rule.nodes[a]) / double(n - 1);
            const double theta = u * u * kPi / 2, dtheta_du = u * kPi;
            const double d = row_at(ndf, n, theta);
            double ring = 0;
            for (std::size_t b = 0; b < 64; ++b)
                for (std::size_t c = 0; c < rule.nodes.size(); ++c) {
                    const double phi = (double(b) + 0.5 + 0.5 * rule.nodes[c]) * kTwoPi / 64;
                    ring += rule.weights[c] * 0.5 * std::max(0.0, dot(wi, spherical_direction(theta, phi)));
                }
            sum += rule.weights[a] * 0.5 / double(n - 1) * d * ring * (kTwoPi / 64) * std::sin(theta) * dtheta_du;
        }
    return sum;
}

}  // namespace

TEST(RglRealFiles, LuminanceIsTheRec709LuminanceOfTheRgbTable) {
    for (const RealFile& file : kFiles) {
        const RglData d = read_rgl(kRgl / file.name);
        EXPECT_EQ(d.description, file.description) << file.name;
        ASSERT_TRUE(d.rgb) << file.name;
        ASSERT_TRUE(d.isotropic()) << file.name;
        EXPECT_TRUE(d.jacobian) << file.name;
        const std::size_t plane = d.rows * d.cols;
        double worst = 0;
        for (std::size_t slice = 0; slice < d.theta_i.size(); ++slice)
            for (std::size_t i = 0; i < plane; ++i) {
                const double r = d.spectra[(slice * 3 + 0) * plane + i], g = d.spectra[(slice * 3 + 1) * plane + i],
                             b = d.spectra[(slice * 3 + 2) * plane + i];
                const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;  // IEC 61966-2-1
                const double l = d.luminance[slice * plane + i];
                worst = std::max(worst, std::abs(y - l) / std::max(l, 1e-2));
            }
        // Measured: 2.4e-4 at worst over the seven files (float32 rounding of the database's own sums).
        EXPECT_LT(worst, 1e-3) << file.name;
    }
}

TEST(RglRealFiles, SigmaIsTheProjectedAreaOfTheNdf) {
    for (const RealFile& file : kFiles) {
        const RglData d = read_rgl(kRgl / file.name);
        ASSERT_EQ(d.ndf_rows, 2u);
        const std::vector<double> ndf(d.ndf.begin(), d.ndf.begin() + long(d.ndf_cols));
        const std::vector<double> sigma(d.sigma.begin(), d.sigma.begin() + long(d.sigma_cols));
        double worst = 0;
        for (double theta_deg : {0.0, 20.0, 40.0, 60.0, 75.0, 85.0}) {
            const double theta = theta_deg * kDegree;
            const double computed = projected_area(ndf, d.ndf_cols, theta);
            const double stored = row_at(sigma, d.sigma_cols, theta);
            worst = std::max(worst, std::abs(computed / stored - 1));
        }
        // Measured: 0.8-0.9 % (the database integrates its ndf on a grid of its own): within 1.5 %.
        EXPECT_LT(worst, 0.015) << file.name;
    }
}

TEST(RglRealFiles, VndfSlicesAreTheVisibleNormalsOfTheNdf) {
    for (const RealFile& file : kFiles) {
        const RglData d = read_rgl(kRgl / file.name);
        const std::vector<double> ndf(d.ndf.begin(), d.ndf.begin() + long(d.ndf_cols));
        const std::vector<double> sigma(d.sigma.begin(), d.sigma.begin() + long(d.sigma_cols));
        const std::size_t nx = d.vndf_cols, ny = d.vndf_rows;
        for (std::size_t t = 0; t < d.theta_i.size(); ++t) {
            // Density over u_m = (u_theta, u_phi) of D(m) <wi, m> / sigma(wi) times d(omega)/d(u) = 2 pi^2 u sin(theta);
            // the stored slice integrates to an arbitrary constant: compare the mass in the quarters of the u square.
            const double theta_i = d.theta_i[t], s = row_at(sigma, d.sigma_cols, theta_i);
            const Vec3 wi = spherical_direction(theta_i, 0.0);
            double model[4] = {}, table[4] = {};
            for (std::size_t y = 0; y < ny; ++y)
                for (std::size_t x = 0; x < nx; ++x) {
                    const double ux = double(x) / double(nx - 1), uy = double(y) / double(ny - 1);
                    const double theta = ux * ux * kPi / 2, phi = (2 * uy - 1) * kPi;
                    const double v = row_at(ndf, d.ndf_cols, theta) *
                                     std::max(0.0, dot(wi, spherical_direction(theta, phi))) / s * 2 * kPi * kPi * ux *
                                     std::sin(theta);
                    const int q = (2 * x >= nx ? 1 : 0) + (2 * y >= ny ? 2 : 0);
                    model[q] += v;
                    table[q] += d.vndf[(t * ny + y) * nx + x];
                }
            const double model_total = model[0] + model[1] + model[2] + model[3];
            const double table_total = table[0] + table[1] + table[2] + table[3];
            for (int q = 0; q < 4; ++q)
                EXPECT_NEAR(table[q] / table_total, model[q] / model_total, 0.01)
                    << file.name << " theta_i " << theta_i << " quarter " << q;
        }
    }
}

TEST(RglRealFiles, WriteThenReadIsExact) {
    const RglData d = read_rgl(kRgl / "paper_white_rgb.bsdf");
    const auto dir = std::filesystem::temp_directory_path() / ("rgl_roundtrip_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    write_rgl(dir / "copy.bsdf", d);
    const RglData e = read_rgl(dir / "copy.bsdf");
    EXPECT_EQ(e.description, d.description);
    EXPECT_EQ(e.theta_i, d.theta_i);
    EXPECT_EQ(e.ndf, d.ndf);
    EXPECT_EQ(e.sigma, d.sigma);
    EXPECT_EQ(e.vndf, d.vndf);
    EXPECT_EQ(e.luminance, d.luminance);
    EXPECT_EQ(e.spectra, d.spectra);
    EXPECT_EQ(e.valid, d.valid);
    std::filesystem::remove_all(dir);
}

TEST(RglRealFiles, RefusesWhatIsNotAnRglFile) {
    io::TensorFile file = rgl_to_tensor(read_rgl(kRgl / "paper_white_rgb.bsdf"));
    std::erase_if(file.fields, [](const io::TensorField& f) { return f.name == "vndf"; });
    try {
        rgl_from_tensor(file, "cut.bsdf");
        FAIL() << "a file without vndf was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no field 'vndf'"), std::string::npos) << e.what();
    }
    const RglMeasuredBsdf paper(read_rgl(kRgl / "paper_white_rgb.bsdf"));
    EXPECT_THROW(paper.eval({0, 0, 1}, {0, 0, 1}, 900.0), Error);  // rgb files: 360-830 nm
}

// The sampler draws what pdf() states (chi-square over a theta x phi grid), pdf() equals the density sample()
// returns, and the weights are f cos / pdf, on a diffuse-like and a glossy real file (ndf peak 27: lobes wider than the 3 x 6 degree cells) at four incidences.
TEST(RglMeasured, SamplerChiSquare) {
    const char* names[] = {"paper_white_rgb.bsdf", "cc_ibiza_sunset_rgb.bsdf"};
    const double level = test::sidak(0.01, 8);
    for (const char* name : names) {
        const RglMeasuredBsdf bsdf(read_rgl(kRgl / name));
        for (double theta_deg : {0.0, 30.0, 55.0, 75.0}) {
            const Vec3 wi = spherical_direction(theta_deg * kDegree, 0.7);
            const auto r = test::chi2_test(bsdf, wi, 550.0, 200000, 30, 60);
            const std::string what = std::string(name) + " theta_i " + std::to_string(theta_deg) + ": " + r.summary();
            EXPECT_GT(r.p_value, level) << what;
            // pdf() recovers the sample point by inverting the two warps (quadratic roots per cell): 2e-6 measured.
            EXPECT_LT(r.pdf_mismatch, 1e-5) << what;
            EXPECT_LT(r.weight_mismatch, 1e-5) << what;
            EXPECT_LE(r.expected_total, 1.0 + 2e-3) << what;
        }
    }
}
