// The hero-wavelength spectral MIS with a material whose lobes change with wavelength (as GHS's do): a glossy lobe
// whose exponent and a delta lobe whose probability and strength all depend on lambda.
#include <gtest/gtest.h>

#include <cmath>

#include "render_test_util.hpp"
#include "surfscatter/spectrum/cie.hpp"

using namespace surfscatter;
using namespace surfscatter::render;

namespace {

double unit(double lambda) { return (lambda - 360.0) / 470.0; }

// f cos = rho * p_n(wi) on the continuous part, p_n the cos^n density, n = 1 + 40 t; a delta lobe of strength
// 0.3 t picked with probability 0.2 + 0.6 t (t = (lambda - 360) / 470). Albedo rho + 0.3 t at every angle.
class DispersiveLobe final : public Material {
public:
    static constexpr double kRho = 0.5;
    static double exponent(double lambda) { return 1 + 40 * unit(lambda); }
    static double delta_probability(double lambda) { return 0.2 + 0.6 * unit(lambda); }
    static double delta_reflectance(double lambda) { return 0.3 * unit(lambda); }
    static double lobe_pdf(const Vec3& wi, double lambda) {
        const double n = exponent(lambda);
        return wi.z > 0 ? (n + 1) / kTwoPi * std::pow(wi.z, n) : 0.0;
    }

    SampledSpectrum eval(const ShadingPoint&, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        SampledSpectrum f;
        for (int k = 0; k < 4; ++k) {
            const double lambda = w.lambda[k];
            const double p = wo.z > 0 ? lobe_pdf(wi, lambda) : 0.0;
            f[k] = wi.z > 0 ? kRho * p / wi.z : 0.0;
            if (pdf) (*pdf)[k] = (1 - delta_probability(lambda)) * p;
        }
        return f;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w, double u_lobe,
                                         Vec2 u) const override {
        if (wo.z <= 0) return std::nullopt;
        MaterialSample s;
        if (u_lobe < delta_probability(w.lambda[0])) {
            s.delta = true;
            s.wi = reflect_about_normal(wo);
            for (int k = 0; k < 4; ++k) {
                s.f[k] = delta_reflectance(w.lambda[k]);
                s.pdf[k] = delta_probability(w.lambda[k]);
            }
            return s;
        }
        const double cos_theta = std::pow(u.x, 1 / (exponent(w.lambda[0]) + 1));
        s.wi = spherical_direction(std::acos(cos_theta), kTwoPi * u.y);
        SampledSpectrum pdf;
        s.f = eval(sp, s.wi, wo, w, &pdf);
        s.pdf = pdf;
        return s;
    }
};

}  // namespace

TEST(SpectralMis, WavelengthDependentLobesUnderUniformSky) {
    // A large plane under a constant sky of radiance 1: L(lambda) = rho + 0.3 t(lambda) exactly, for each strategy.
    double expected_y = 0, y_integral = 0;
    for (double lambda = 360; lambda <= 830; lambda += 1) {
        const double ybar = spectrum::cie1931().xyz_bar(lambda).y;
        expected_y += (DispersiveLobe::kRho + DispersiveLobe::delta_reflectance(lambda)) * ybar;
        y_integral += ybar;
    }
    expected_y /= y_integral;
    for (const char* strategy : {"mis", "bsdf", "emitter"}) {
        Scene scene;
        TriangleMesh plane = make_rectangle();
        transform_mesh(plane, Transform::scale({100, 100, 1}), false);
        scene.add_shape(std::move(plane), std::make_shared<DispersiveLobe>(), nullptr);
        scene.add_emitter(make_constant_emitter(make_constant_spectrum(1.0)));
        scene.commit();
        scene.camera.to_world = Transform::look_at({0, -2, 2}, {0, 0, 0}, {0, 0, 1});
        scene.camera.fov_degrees = 10;
        scene.film.width = scene.film.height = 8;
        scene.film.filter = make_box_filter();
        scene.integrator.strategy = strategy;
        scene.integrator.max_depth = 2;  // one bounce: the plane cannot see itself anyway
        // Eight independent renders give the Monte Carlo standard error (emitter sampling alone is noisy here: a
        // uniform sky sample rarely lands in a cos^41 lobe).
        const test::MeanY y = test::mean_y_over_seeds_of(scene, 128, 8);
        const double mean = y.mean, standard_error = y.standard_error;
        EXPECT_NEAR(mean, expected_y, 4 * standard_error) << strategy;
        if (std::string(strategy) != "emitter") { EXPECT_NEAR(mean, expected_y, 0.01 * expected_y) << strategy; }
    }
}
