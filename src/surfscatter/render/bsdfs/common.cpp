#include "surfscatter/render/bsdfs/common.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/material/refractive_index.hpp"
#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::render {

namespace {

struct NamedIor {
    const char* name;
    double value;
};
constexpr NamedIor kNamedIors[] = {
    {"vacuum", 1.0},          {"helium", 1.000036},       {"hydrogen", 1.000132},      {"air", 1.000277},
    {"carbon dioxide", 1.00045}, {"water", 1.3330},       {"acetone", 1.36},           {"ethanol", 1.361},
    {"carbon tetrachloride", 1.461}, {"glycerol", 1.4729}, {"benzene", 1.501},         {"silicone oil", 1.52045},
    {"bromine", 1.661},       {"water ice", 1.31},        {"fused quartz", 1.458},     {"pyrex", 1.470},
    {"acrylic glass", 1.49},  {"polypropylene", 1.49},    {"bk7", 1.5046},             {"sodium chloride", 1.544},
    {"amber", 1.55},          {"pet", 1.5750},            {"diamond", 2.419},
};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}


}  // namespace

double read_ior(Properties& props, const std::string& name, const std::string& fallback) {
    const auto given = props.get_float_or_string(name).value_or(fallback);
    if (const double* value = std::get_if<double>(&given)) {
        if (!(*value > 0)) props.fail_param(name, "{} must be positive, got {}", name, *value);
        return *value;
    }
    const std::string& text = std::get<std::string>(given);
    const std::string key = lower(text);
    for (const NamedIor& n : kNamedIors)
        if (key == n.name) return n.value;
    std::string names;
    for (const NamedIor& n : kNamedIors) names += std::string(names.empty() ? "" : ", ") + n.name;
    props.fail_param(name, "{}: '{}' is neither a number nor a known material ({})", name, text, names);
}

double read_relative_ior(Properties& props, const std::string& int_default, const std::string& ext_default,
                         bool must_differ) {
    const double int_ior = read_ior(props, "int_ior", int_default);
    const double ext_ior = read_ior(props, "ext_ior", ext_default);
    if (must_differ && int_ior == ext_ior) props.fail("int_ior and ext_ior must differ, both are {}", int_ior);
    return int_ior / ext_ior;
}

ConductorIor::ConductorIor(const std::function<std::complex<double>(double)>& index) {
    for (int i = 0; i < kTableSize; ++i) table_.push_back(index(spectrum::kSampledLambdaMin + i));
}

SampledSpectrum ConductorIor::reflectance(double cos_theta, const SampledWavelengths& w) const {
    if (perfect()) return SampledSpectrum(1.0);
    constexpr int kN = spectrum::kSpectrumSamples;
    float n[kN], k[kN], r[kN];
    for (int i = 0; i < kN; ++i) {
        const std::complex<double> eta = at(w.lambda[static_cast<std::size_t>(i)]);
        n[i] = static_cast<float>(eta.real());
        k[i] = static_cast<float>(eta.imag());
    }
    const float c = static_cast<float>(std::clamp(cos_theta, 0.0, 1.0));
    for (int i = 0; i < kN; ++i) r[i] = material::fresnel_conductor_sp_unchecked(c, n[i], k[i]).unpolarized();
    SampledSpectrum out;
    for (int i = 0; i < kN; ++i) out[i] = r[i];
    return out;
}

ConductorIor read_conductor_ior(Properties& props) {
    const bool has_eta = props.has("eta"), has_k = props.has("k");
    std::string name = props.get_string("material", "none");
    if (name == "perfect") name = "none";  // surfscatter's name for the perfect mirror
    if (has_eta || has_k || name == "none") {
        if (name != "none") props.fail("give either material or eta/k, not both");
        if (!has_eta && !has_k) return ConductorIor();  // Mitsuba: eta = 0, k = 1, a perfect mirror
        const SpectrumPtr eta = props.get_spectrum("eta", false, 0.0), k = props.get_spectrum("k", false, 1.0);
        return ConductorIor([&](double lambda) { return std::complex<double>(eta->eval(lambda), k->eval(lambda)); });
    }
    if (name.size() > 6 && name.substr(name.size() - 6) == "_palik")
        props.fail_param("material", "material '{}' names Palik's tables, which surfscatter does not ship; use '{}' (Rakic "
                      "1998 Lorentz-Drude fit) or give eta/k", name, name.substr(0, name.size() - 6));
    const auto builtin = material::builtin_metal_names();
    const bool is_file = name.find('.') != std::string::npos;
    if (!is_file && std::find(builtin.begin(), builtin.end(), name) == builtin.end())
        props.fail_param("material", "material '{}' is not built in (built-in metals: {}; or a .yml / .csv file, or eta/k "
                      "spectra)", name, fmt::join(builtin, ", "));
    try {
        const material::Conductor conductor = material::Conductor::from_name(is_file ? props.get_file("material").string() : name);
        return ConductorIor([&](double lambda) { return conductor.ior(lambda); });
    } catch (const SceneError&) {
        throw;
    } catch (const Error& e) {
        props.fail_param("material", "{}", e.what());
    }
}

Microfacet::Microfacet(bool beckmann, double alpha_u, double alpha_v, bool sample_visible)
    : beckmann_(beckmann), visible_(sample_visible && !beckmann), ggx_(alpha_u, alpha_v),
      beckmann_distribution_(alpha_u, alpha_v) {}

Microfacet Microfacet::read(Properties& props, bool anisotropic) {
    const std::string distribution = props.get_string("distribution", "beckmann");
    if (distribution != "beckmann" && distribution != "ggx")
        props.fail_param("distribution", "distribution must be beckmann or ggx, got '{}'", distribution);
    double alpha_u = 0.1, alpha_v = 0.1;
    if (props.has("alpha_u") || props.has("alpha_v")) {
        if (props.has("alpha")) props.fail("give either alpha or alpha_u/alpha_v, not both");
        alpha_u = props.get_float_required("alpha_u");
        alpha_v = props.get_float_required("alpha_v");
        if (!anisotropic && alpha_u != alpha_v)
            props.fail_param("alpha_u", "anisotropic roughness (alpha_u {} != alpha_v {}) is not supported by this bsdf",
                             alpha_u, alpha_v);
    } else {
        alpha_u = alpha_v = props.get_float("alpha", 0.1);
    }
    const auto check = [&](double value, const char* name) {
        try {
            bsdf::require_microfacet_alpha(value, name);
        } catch (const Error& e) {
            props.fail("{}", e.what());
        }
    };
    check(alpha_u, props.has("alpha_u") ? "alpha_u" : "alpha");
    if (props.has("alpha_v")) check(alpha_v, "alpha_v");
    return Microfacet(distribution == "beckmann", alpha_u, alpha_v, props.get_bool("sample_visible", true));
}

double Microfacet::D(const Vec3& m) const { return beckmann_ ? beckmann_distribution_.D(m) : ggx_.D(m); }

double Microfacet::lambda(const Vec3& w) const {
    const Vec3 up(w.x, w.y, std::abs(w.z));
    return beckmann_ ? beckmann_distribution_.lambda(up) : ggx_.lambda(up);
}

double Microfacet::G1(const Vec3& w, const Vec3& m) const {
    if (dot(w, m) * w.z <= 0) return 0.0;
    return 1 / (1 + lambda(w));
}

Vec3 Microfacet::sample(const Vec3& w, Vec2 u) const { return visible_ ? ggx_.sample_visible(w, u) : sample_projected(u); }

Vec3 Microfacet::sample_projected(Vec2 u) const {
    if (beckmann_) return beckmann_distribution_.sample_projected(u);
    if (!ggx_.isotropic()) {
        // The unit-roughness slope distribution (tan^2 theta = u / (1 - u)) stretched by (alpha_u, alpha_v), as
        // BeckmannDistribution::sample_projected.
        const double r = std::sqrt(u.x / std::max(1 - u.x, 1e-300)), phi = kTwoPi * u.y;
        return normalize(Vec3(ggx_.alpha_x() * r * std::cos(phi), ggx_.alpha_y() * r * std::sin(phi), 1.0));
    }
    // GGX by D(m) cos(theta_m): tan^2 theta = alpha^2 u / (1 - u).
    const double alpha = ggx_.alpha_x();
    const double t2 = alpha * alpha * u.x / std::max(1 - u.x, 1e-300);
    const double c = 1 / std::sqrt(1 + t2), s = std::sqrt(std::max(0.0, 1 - c * c));
    return {s * std::cos(kTwoPi * u.y), s * std::sin(kTwoPi * u.y), c};
}

double Microfacet::reflection_albedo(const Vec3& wo, double eta) const {
    static const math::GaussLegendreRule rule(24);
    // With m ~ D(m) m.z, wi = reflect(wo, m) and dwi = 4 |wo.m| dm: albedo = E[F G |wo.m| / (wo.z m.z)].
    double total = 0;
    for (std::size_t a = 0; a < rule.nodes.size(); ++a)
        for (std::size_t b = 0; b < rule.nodes.size(); ++b) {
            const Vec3 m = sample_projected({0.5 * (rule.nodes[a] + 1), 0.5 * (rule.nodes[b] + 1)});
            const double wo_m = dot(wo, m);
            if (!(wo_m > 0) || !(m.z > 0)) continue;
            const Vec3 wi = reflect(wo, m);
            const double g = G(wi, wo, m);
            if (!(g > 0)) continue;
            total += 0.25 * rule.weights[a] * rule.weights[b] * material::fresnel_dielectric(wo_m, eta).reflectance * g *
                     wo_m / (wo.z * m.z);
        }
    return total;
}

double Microfacet::pdf(const Vec3& w, const Vec3& m) const {
    if (m.z <= 0) return 0.0;
    if (visible_) return ggx_.visible_density(w, m);
    return D(m) * m.z;
}

SmoothDielectricLobes::SmoothDielectricLobes(Properties& props)
    : eta_(read_relative_ior(props, "bk7", "air", true)),
      reflectance_(props.get_texture("specular_reflectance", 1.0)),
      transmittance_(props.get_texture("specular_transmittance", 1.0)) {}

MaterialSample SmoothDielectricLobes::choose_lobe(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                                  double u_lobe, double r, const Vec3& wi_transmitted,
                                                  double transmitted_scale) const {
    MaterialSample s;
    s.delta = true;
    if (u_lobe < r) {
        s.wi = reflect_about_normal(wo);
        s.f = reflectance_->eval(sp.uv, w) * r;
        s.pdf = SampledSpectrum(r);
    } else {
        s.wi = wi_transmitted;
        s.f = transmittance_->eval(sp.uv, w) * ((1 - r) * transmitted_scale);
        s.pdf = SampledSpectrum(1 - r);
    }
    return s;
}

}  // namespace surfscatter::render
