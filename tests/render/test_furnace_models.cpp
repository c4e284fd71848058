// Furnace renders of every scattering model: a large plane of perfect conductor under a constant sky of radiance 1,
// seen at 60 deg (one bounce: the plane cannot see itself), renders int f(light, viewer) cos(theta_light) d light,
// averaged over the spectrum with the CIE Y weight. The expected value comes from the bsdf tests' own quadrature
// (tests/bsdf/disc_albedo.hpp) at 24 wavelengths, over the light direction: the models whose sigma_rel, K and R
// depend on the incidence (GHS, SSA, the two-scale micro part) are not reciprocal, so this is not their directional
// albedo R (it is 1.5 % lower for the GHS here); for GGX it is. This checks sampling, pdfs, weights and the delta lobes
// through the renderer's hero-wavelength MIS, for every model and both strategies.
#include <gtest/gtest.h>

#include <cmath>

#include "../bsdf/disc_albedo.hpp"
#include "render_test_util.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/render/material.hpp"
#include "surfscatter/render/emitter.hpp"
#include "surfscatter/render/filter.hpp"
#include "surfscatter/render/mesh.hpp"
#include "surfscatter/render/spectrum_source.hpp"
#include "surfscatter/spectrum/cie.hpp"

using namespace surfscatter;
using namespace surfscatter::render;

namespace {

constexpr double kView = 60.0;  // deg from the normal

// A model with its arguments swapped: disc_albedo of it integrates f(light, viewer) over the light direction.
class Swapped final : public bsdf::Bsdf {
public:
    explicit Swapped(const bsdf::Bsdf& model) : model_(model) {}
    double eval(const Vec3& a, const Vec3& b, double lambda) const override { return model_.eval(b, a, lambda); }
    std::optional<bsdf::BsdfSample> sample(const Vec3&, double, double, Vec2) const override { return std::nullopt; }
    double pdf(const Vec3&, const Vec3&, double) const override { return 0; }
    double delta_reflectance(const Vec3& w, double lambda) const override { return model_.delta_reflectance(w, lambda); }
    std::string name() const override { return "swapped " + model_.name(); }

private:
    const bsdf::Bsdf& model_;
};

// Y-weighted spectral mean of int f(light, viewer) cos(theta_light) at the view angle.
double expected_y(const bsdf::Bsdf& model) {
    const Vec3 viewer = spherical_direction(kView * kDegree, 0.0);
    double sum = 0, weight = 0;
    for (double lambda = 370; lambda <= 830; lambda += 20) {
        const double ybar = spectrum::cie1931().xyz_bar(lambda).y;
        sum += ybar * bsdf::test::disc_albedo(Swapped(model), viewer, lambda);
        weight += ybar;
    }
    return sum / weight;
}

test::MeanY furnace(std::shared_ptr<const bsdf::Bsdf> model, const char* strategy) {
    Scene scene;
    TriangleMesh plane = make_rectangle();
    transform_mesh(plane, Transform::scale({100, 100, 1}), false);
    scene.add_shape(std::move(plane), make_model_material(std::move(model)), nullptr);
    scene.add_emitter(make_constant_emitter(make_constant_spectrum(1.0)));
    scene.commit();
    const double t = kView * kDegree;
    scene.camera.to_world = Transform::look_at({0, -3 * std::sin(t), 3 * std::cos(t)}, {0, 0, 0}, {0, 0, 1});
    scene.camera.fov_degrees = 1;
    scene.film.width = scene.film.height = 4;
    scene.film.filter = make_box_filter();
    scene.integrator.strategy = strategy;
    scene.integrator.max_depth = 2;
    return test::mean_y_over_seeds_of(scene, 256, 6);
}

bsdf::ModelOptions kc(bsdf::ModelKind model, double sigma) {
    bsdf::ModelOptions o;
    o.model = model;
    o.surface.psd = bsdf::PsdKind::kc;
    o.surface.sigma = sigma;
    o.surface.corr_length = 1.0;
    o.surface.gamma = 3.0;
    return o;
}

}  // namespace

TEST(Furnace, EveryModelRendersItsAlbedo) {
    std::vector<std::pair<std::string, bsdf::ModelOptions>> models;
    models.push_back({"ghs exact", kc(bsdf::ModelKind::ghs, 0.1)});
    auto refit = kc(bsdf::ModelKind::ghs, 0.1);
    refit.method = bsdf::GhsMethod::refit;
    models.push_back({"ghs refit", refit});
    models.push_back({"ghs_ssa", kc(bsdf::ModelKind::ghs_ssa, 0.1)});
    auto ggx = kc(bsdf::ModelKind::ggx, 0.1);
    ggx.alpha_from = bsdf::AlphaFrom::kc_link;
    models.push_back({"ggx", ggx});
    auto two_scale = kc(bsdf::ModelKind::two_scale, 0.1);
    two_scale.cutoff_wavelengths = 20;
    models.push_back({"two_scale N 20", two_scale});
    for (const auto& [name, o] : models) {
        const std::shared_ptr<const bsdf::Bsdf> model = bsdf::make_bsdf(o);
        const double expected = expected_y(*model);
        for (const char* strategy : {"mis", "bsdf"}) {
            const test::MeanY y = furnace(model, strategy);
            std::printf("furnace %-15s %-4s: %.5f +- %.5f (expected %.5f)\n", name.c_str(), strategy, y.mean,
                        y.standard_error, expected);
            EXPECT_NEAR(y.mean, expected, std::max(4 * y.standard_error, 2e-3)) << name << " " << strategy;
        }
    }
}
