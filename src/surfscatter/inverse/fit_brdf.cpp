#include "surfscatter/inverse/fit_brdf.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <numeric>
#include <utility>

#include <Eigen/Core>
#include <Eigen/SVD>
#include <unsupported/Eigen/NonLinearOptimization>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/table_cache.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/least_squares_functor.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::inverse {

namespace {

enum Parameter { kSigma, kLength, kGamma, kLengthV, kLay, kParameterCount };

// Bounds of the physical values; the solver works in ln sigma, ln L, ln(gamma - 1), ln LV and the lay angle itself.
struct Bounds {
    double lo, hi;
};
constexpr std::array<Bounds, kParameterCount> kBounds = {
    Bounds{1e-4, 20.0}, Bounds{1e-3, 1e4}, Bounds{1.02, 50.0}, Bounds{1e-3, 1e4}, Bounds{-90.0, 90.0}};
// ggx_stats with alpha from the KC statistics needs a finite rms slope: gamma > 3 (bsdf/factory.cpp).
constexpr double kGgxKcGammaMin = 3.02;
// Forward-difference steps in the solver's variables: 0.2 % of a length or of gamma - 1, 0.1 degree of the lay.
constexpr double kLogStep = 2e-3, kLayStep = 0.1;
// A free parameter whose standard error in the solver's variable exceeds this (a factor e in a length, 57 degrees
// of lay) is reported as unconstrained.
constexpr double kUnconstrainedLogError = 1.0, kUnconstrainedLayError = 45.0;
// The residual of every row where the model refuses the parameters: far beyond any fit's.
constexpr double kRefusedResidual = 1e6;

bool is_log(int p) { return p != kLay; }

double to_internal(int p, double value) {
    if (p == kGamma) return std::log(value - 1.0);
    return is_log(p) ? std::log(value) : value;
}

double to_physical(int p, double x) {
    if (p == kGamma) return 1.0 + std::exp(x);
    return is_log(p) ? std::exp(x) : x;
}

// d(physical) / d(internal), for the standard errors.
double physical_slope(int p, double x) { return is_log(p) ? std::exp(x) : 1.0; }

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// The rows of one (wavelength, incidence) of profile data, with exact-1d's signed scattering angles (light in the x-z
// plane from negative x, specular at theta_o = +theta_i: the local frame's phi_o = 180 side).
struct ProfileGroup {
    double lambda_nm = 0, theta_i_rad = 0;
    std::vector<std::size_t> rows;
    std::vector<double> theta_o_rad;
};

// Throws Error naming the first row outside the plane of incidence.
std::vector<ProfileGroup> profile_groups(const BrdfData& data) {
    std::map<std::pair<double, double>, ProfileGroup> groups;
    // An azimuth within 1e-6 degree of a multiple of 180 (of 360 for phi_i) lies in the plane of incidence.
    const auto off = [](double phi, double period) { return std::abs(std::remainder(phi, period)) > 1e-6; };
    for (std::size_t j = 0; j < data.size(); ++j) {
        if (off(data.phi_i_deg[j], 360))
            fail("{}: phi_i_deg must be 0 for profile data (light in the x-z plane), got {}", row_name(data, j),
                 data.phi_i_deg[j]);
        if (off(data.phi_o_deg[j], 180) && data.theta_o_deg[j] != 0)
            fail("{}: phi_o_deg must be 0 or 180 for profile data (the plane of incidence), got {}", row_name(data, j),
                 data.phi_o_deg[j]);
        ProfileGroup& g = groups[{data.wavelength_nm[j], data.theta_i_deg[j]}];
        g.lambda_nm = data.wavelength_nm[j];
        g.theta_i_rad = data.theta_i_deg[j] * kDegree;
        g.rows.push_back(j);
        g.theta_o_rad.push_back(data.theta_o_deg[j] * kDegree * (std::cos(data.phi_o_deg[j] * kDegree) < 0 ? 1 : -1));
    }
    std::vector<ProfileGroup> out;
    for (auto& entry : groups) out.push_back(std::move(entry.second));
    return out;
}

Vec3 direction(double theta_deg, double phi_deg) {
    const double t = theta_deg * kDegree, f = phi_deg * kDegree;
    return {std::sin(t) * std::cos(f), std::sin(t) * std::sin(f), std::cos(t)};
}

class Problem {
public:
    Problem(const BrdfData& data, const FitOptions& options, bsdf::ModelKind model)
        : data_(data), options_(options), model_(model) {
        if (options.profile) {
            if (model == bsdf::ModelKind::two_scale) fail("two_scale has no 1-D form: fit profile data with ghs, ghs_ssa or ggx_stats");
            groups_ = profile_groups(data);
            conductor_ = material::Conductor::from_name(options.material);
        }
        std::map<std::pair<double, double>, std::size_t> incidences;
        for (std::size_t j = 0; j < data.size(); ++j) {
            wi_.push_back(direction(data.theta_i_deg[j], data.phi_i_deg[j]));
            wo_.push_back(direction(data.theta_o_deg[j], data.phi_o_deg[j]));
            const auto at = incidences.try_emplace({data.theta_i_deg[j], data.wavelength_nm[j]}, incidences.size());
            incidence_.push_back(at.first->second);
        }
        incidences_.resize(incidences.size());
        for (const auto& entry : incidences) incidences_[entry.second] = entry.first;
        bounds_ = kBounds;
        if (model == bsdf::ModelKind::ggx && options.psd == bsdf::PsdKind::kc) bounds_[kGamma].lo = kGgxKcGammaMin;
        active_ = {kSigma, kLength};
        if (options.psd == bsdf::PsdKind::kc) active_.push_back(kGamma);
        if (options.anisotropic) active_.insert(active_.end(), {kLengthV, kLay});
        for (int p : active_) {
            const auto fixed = options.fixed.find(kParameterNames[p]);
            if (fixed == options.fixed.end()) {
                free_.push_back(p);
                continue;
            }
            if (!(fixed->second >= bounds_[p].lo && fixed->second <= bounds_[p].hi))
                fail("{} {}={}: the {} fit takes {} in [{}, {}]", options.names.fix, kParameterNames[p], fixed->second,
                     bsdf::to_string(model), kParameterNames[p], bounds_[p].lo, bounds_[p].hi);
            value_[p] = fixed->second;
        }
    }

    const std::vector<int>& active() const { return active_; }
    const std::vector<int>& free() const { return free_; }
    const Bounds& bounds(int p) const { return bounds_[p]; }
    double fixed_value(int p) const { return value_[p]; }
    int evaluations() const { return evaluations_; }

    double lower(int p) const { return to_internal(p, bounds_[p].lo); }
    double upper(int p) const { return to_internal(p, bounds_[p].hi); }

    // Solver variables held inside the bounds (the residuals are flat beyond them, so the solver turns back).
    Eigen::VectorXd clamped(const Eigen::VectorXd& x) const {
        Eigen::VectorXd c = x;
        for (std::size_t k = 0; k < free_.size(); ++k) {
            const int p = free_[k];
            c[k] = std::clamp(x[k], lower(p), upper(p));
        }
        return c;
    }

    std::array<double, kParameterCount> physical(const Eigen::VectorXd& x) const {
        std::array<double, kParameterCount> v = value_;
        const Eigen::VectorXd c = clamped(x);
        for (std::size_t k = 0; k < free_.size(); ++k) v[free_[k]] = to_physical(free_[k], c[k]);
        return v;
    }

    // The 1-D model at every row of profile data (bsdf/profile_lobes.hpp), one lobe per (wavelength, incidence).
    std::vector<double> profile_values(const std::array<double, kParameterCount>& v) const {
        std::unique_ptr<surface::RadialStatistics> statistics;
        if (options_.psd == bsdf::PsdKind::kc)
            statistics = std::make_unique<surface::KCorrelation>(v[kSigma], v[kLength], v[kGamma]);
        else
            statistics = std::make_unique<surface::GaussianAcv>(v[kSigma], v[kLength]);
        bsdf::ProfileModelOptions o;
        o.model = model_ == bsdf::ModelKind::ghs_ssa ? bsdf::ProfileModel::ghs_ssa : bsdf::ProfileModel::ghs;
        std::vector<double> f(data_.size());
        for (const ProfileGroup& g : groups_) {
            const bsdf::ProfileLobe lobe =
                model_ == bsdf::ModelKind::ggx
                    ? bsdf::ggx_profile_lobe(*statistics, *conductor_, g.lambda_nm, g.theta_i_rad, *options_.profile,
                                             g.theta_o_rad)
                    : bsdf::profile_lobe(*statistics, *conductor_, g.lambda_nm, g.theta_i_rad, *options_.profile, o,
                                         g.theta_o_rad);
            for (std::size_t k = 0; k < g.rows.size(); ++k) f[g.rows[k]] = lobe.intensity_per_rad[k];
        }
        return f;
    }

    // The model at every row for the solver variables x.
    std::vector<double> model_values(const Eigen::VectorXd& x) const {
        const auto v = physical(x);
        if (options_.profile) {
            ++evaluations_;
            return profile_values(v);
        }
        bsdf::ModelOptions o;
        o.model = model_;
        o.material = options_.material;
        o.surface.psd = options_.psd;
        o.surface.sigma = v[kSigma];
        o.surface.corr_length = v[kLength];
        if (options_.psd == bsdf::PsdKind::kc) o.surface.gamma = v[kGamma];
        if (options_.anisotropic) {
            o.surface.corr_length_v = v[kLengthV];
            o.surface.lay_angle = v[kLay];
        }
        ++evaluations_;
        // The last model is kept: its lobe table (which does not depend on sigma: surface/scatter_lobe_table.hpp) then
        // serves the next model of the same L and gamma (the Jacobian's sigma column) from the process cache.
        last_model_ = bsdf::make_bsdf(o);
        std::vector<double> f(data_.size());
        // An isotropic GHS-family model (ghs, ghs_ssa) with sigma and N computed at the data's incidences and
        // wavelengths only (GhsBsdf::direct): its tables over 64 incidences per wavelength node, ~70 % of a
        // tabulated model's cost, are never built.
        if (const auto* ghs = dynamic_cast<const bsdf::GhsBsdf*>(last_model_.get())) {
            std::vector<bsdf::GhsBsdf::Direct> at;
            for (const auto& [theta_i_deg, lambda_nm] : incidences_)
                at.push_back(ghs->direct(theta_i_deg * kDegree, lambda_nm));
            for (std::size_t j = 0; j < f.size(); ++j)
                f[j] = ghs->eval(wi_[j], wo_[j], data_.wavelength_nm[j], at[incidence_[j]]);
            return f;
        }
        for (std::size_t j = 0; j < f.size(); ++j) f[j] = last_model_->eval(wi_[j], wo_[j], data_.wavelength_nm[j]);
        return f;
    }

    Eigen::VectorXd residuals(const std::vector<double>& f) const {
        Eigen::VectorXd r(static_cast<Eigen::Index>(f.size()));
        const bool errors = !data_.brdf_stderr.empty();
        for (std::size_t j = 0; j < f.size(); ++j)
            r[static_cast<Eigen::Index>(j)] =
                (f[j] - data_.brdf[j]) / (errors ? data_.brdf_stderr[j] : data_.brdf[j]);
        return r;
    }

    // A parameter set the model refuses (make_bsdf throws: GGX's alpha beyond its range, ...) is a wall for the
    // solver: residuals of kRefusedResidual each, counted and the first reason kept for the fit's notes.
    Eigen::VectorXd residuals(const Eigen::VectorXd& x) const { return evaluated(x).r; }
    // The model at every row for the solver variables x (not refused there).
    const std::vector<double>& values(const Eigen::VectorXd& x) const { return evaluated(x).f; }
    int refused() const { return refused_; }
    const std::string& first_refusal() const { return first_refusal_; }

    // The Jacobian of the residuals at x; the last one is kept (the fit's errors take it at the solver's end point).
    Eigen::MatrixXd jacobian(const Eigen::VectorXd& x) const {
        if (jacobian_x_.size() == x.size() && jacobian_x_ == x && jacobian_.rows() > 0) return jacobian_;
        const Eigen::VectorXd r0 = residuals(x);
        Eigen::MatrixXd j(r0.size(), x.size());
        for (Eigen::Index k = 0; k < x.size(); ++k) {
            Eigen::VectorXd step = x;
            const int p = free_[static_cast<std::size_t>(k)];
            // Step inwards at an upper bound, so the difference sees the model, not the flat clamp.
            const double h = (is_log(p) ? kLogStep : kLayStep) * (x[k] + kLogStep >= upper(p) ? -1.0 : 1.0);
            step[k] += h;
            j.col(k) = (residuals(step) - r0) / h;
        }
        jacobian_x_ = x;
        jacobian_ = j;
        return j;
    }

private:
    const BrdfData& data_;
    const FitOptions& options_;
    bsdf::ModelKind model_;
    std::vector<Vec3> wi_, wo_;
    std::vector<std::pair<double, double>> incidences_;  // the distinct (theta_i_deg, wavelength_nm) of the rows
    std::vector<std::size_t> incidence_;                 // each row's index into incidences_
    mutable std::unique_ptr<bsdf::Bsdf> last_model_;
    // The last kEvaluationsKept points evaluated: the solver asks for the Jacobian at a point it has evaluated, and
    // the fit's result for its best one.
    struct Evaluation {
        Eigen::VectorXd x, r;
        std::vector<double> f;  // empty where the model refused x
    };
    static constexpr std::size_t kEvaluationsKept = 8;
    mutable std::vector<Evaluation> evaluations_kept_;
    mutable Eigen::VectorXd jacobian_x_;
    mutable Eigen::MatrixXd jacobian_;

    const Evaluation& evaluated(const Eigen::VectorXd& x) const {
        for (const Evaluation& e : evaluations_kept_)
            if (e.x.size() == x.size() && e.x == x) return e;
        Evaluation e;
        e.x = x;
        try {
            e.f = model_values(x);
            e.r = residuals(e.f);
        } catch (const Error& error) {
            if (refused_++ == 0) first_refusal_ = error.what();
            e.r = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(data_.size()), kRefusedResidual);
        }
        if (evaluations_kept_.size() == kEvaluationsKept) evaluations_kept_.erase(evaluations_kept_.begin());
        evaluations_kept_.push_back(std::move(e));
        return evaluations_kept_.back();
    }
    std::vector<ProfileGroup> groups_;          // profile data only
    std::optional<material::Conductor> conductor_;  // profile data only
    std::array<Bounds, kParameterCount> bounds_{};
    std::array<double, kParameterCount> value_{};
    std::vector<int> active_, free_;
    mutable int evaluations_ = 0;
    mutable int refused_ = 0;
    mutable std::string first_refusal_;
};

struct Functor : surface::DynamicLeastSquaresFunctor {
    const Problem* problem;
    int rows;
    int values() const { return rows; }
    int inputs() const { return static_cast<int>(problem->free().size()); }
    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
        r = problem->residuals(x);
        return 0;
    }
    int df(const Eigen::VectorXd& x, Eigen::MatrixXd& j) const {
        j = problem->jacobian(x);
        return 0;
    }
};

// Starting points: sigma at g0 = (4 pi sigma cos theta_i / lambda)^2 of 0.5, 3 and 15 at the data's mean wavelength
// and incidence; L from the rms slope the lobe's width implies, m^2 = mean |i_xy + o_xy|^2 / (cos i + cos o)^2
// weighted by f cos theta_o (the half-vector slope), as for a Gaussian ACV, m = 2 sigma / L.
std::vector<Eigen::VectorXd> starting_points(const BrdfData& data, const Problem& problem, int starts) {
    double lambda = 0, cos_i = 0, weight = 0, slope2 = 0;
    for (std::size_t j = 0; j < data.size(); ++j) {
        lambda += data.wavelength_nm[j];
        cos_i += std::cos(data.theta_i_deg[j] * kDegree);
        const Vec3 wi = direction(data.theta_i_deg[j], data.phi_i_deg[j]);
        const Vec3 wo = direction(data.theta_o_deg[j], data.phi_o_deg[j]);
        const double w = data.brdf[j] * wo.z;
        const double hx = wi.x + wo.x, hy = wi.y + wo.y, hz = wi.z + wo.z;
        slope2 += w * (hx * hx + hy * hy) / (hz * hz);
        weight += w;
    }
    const double n = static_cast<double>(data.size());
    lambda /= n;
    cos_i /= n;
    const double slope = std::max(std::sqrt(slope2 / std::max(weight, 1e-300)), 1e-3);
    std::vector<Eigen::VectorXd> points;
    for (const double g0 : {3.0, 0.5, 15.0}) {
        if (static_cast<int>(points.size()) >= starts) break;
        const double sigma = std::sqrt(g0) * lambda * 1e-3 / (4 * kPi * cos_i);
        const double start[kParameterCount] = {sigma, 2 * sigma / slope, 3.5, 2 * sigma / slope, 0.0};
        Eigen::VectorXd x(static_cast<Eigen::Index>(problem.free().size()));
        for (std::size_t k = 0; k < problem.free().size(); ++k) {
            const int p = problem.free()[k];
            const double v = std::clamp(start[p], problem.bounds(p).lo, problem.bounds(p).hi);
            x[static_cast<Eigen::Index>(k)] = to_internal(p, v);
        }
        points.push_back(x);
    }
    return points;
}

std::string bound_note(int p, double value, const Bounds& b) {
    const double span = to_internal(p, b.hi) - to_internal(p, b.lo);
    if (to_internal(p, value) <= to_internal(p, b.lo) + 1e-3 * span)
        return fmt::format("at the lower bound {} of the search", b.lo);
    if (to_internal(p, value) >= to_internal(p, b.hi) - 1e-3 * span)
        return fmt::format("at the upper bound {} of the search", b.hi);
    return {};
}

std::string internal_name(int p) {
    switch (p) {
        case kGamma: return "ln(gamma - 1)";
        case kLay: return "lay_angle_deg";
        default: return fmt::format("ln {}", kParameterNames[p]);
    }
}

ModelFit fit_model(const BrdfData& data, const FitOptions& options, bsdf::ModelKind kind) {
    const double cpu_start = cpu_seconds();
    Problem problem(data, options, kind);
    ModelFit fit;
    fit.model = kind;
    fit.with_errors = !data.brdf_stderr.empty();
    const std::size_t free_count = problem.free().size();
    if (data.size() <= free_count)
        fail("{}: {} rows cannot determine {} free parameters", data.source, data.size(), free_count);
    fit.dof = data.size() - free_count;
    if (kind == bsdf::ModelKind::ggx && options.psd == bsdf::PsdKind::kc)
        fit.notes.push_back(fmt::format("ggx_stats takes alpha from the KC rms slope, finite for gamma > 3: gamma "
                                        "searched from {}", kGgxKcGammaMin));

    Eigen::VectorXd best;
    double best_cost = std::numeric_limits<double>::infinity();
    if (free_count == 0) {
        best = Eigen::VectorXd(0);
        best_cost = problem.residuals(best).squaredNorm();
    }
    if (free_count > 0) {
        // Several starts, screened by their misfit (one model each); the solver runs from the best `refined` of them
        // (a GHS model costs 0.1-0.3 CPU s to build, the solver 30-60 of them per start).
        std::vector<std::pair<double, Eigen::VectorXd>> starts;
        for (const Eigen::VectorXd& x : starting_points(data, problem, std::max(1, options.starts))) {
            const double cost = problem.residuals(x).squaredNorm();
            starts.emplace_back(std::isfinite(cost) ? cost : std::numeric_limits<double>::max(), x);
        }
        std::stable_sort(starts.begin(), starts.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        starts.resize(std::min<std::size_t>(starts.size(), static_cast<std::size_t>(std::max(1, options.refined))));
        for (auto& [start_cost, x] : starts) {
            Functor functor;
            functor.problem = &problem;
            functor.rows = static_cast<int>(data.size());
            Eigen::LevenbergMarquardt<Functor> solver(functor);
            solver.parameters.maxfev = options.max_evaluations_per_start;
            // A relative step of 1e-4 in the solver's variables is 1/20 of the forward-difference step and far below
            // any standard error the data allow: iterating further only refines noise.
            solver.parameters.xtol = 1e-4;
            solver.parameters.ftol = 1e-8;
            solver.minimize(x);
            x = problem.clamped(x);
            const double cost = problem.residuals(x).squaredNorm();
            if (std::isfinite(cost) && cost < best_cost) {
                best_cost = cost;
                best = x;
            }
        }
    }
    if (!std::isfinite(best_cost)) fail("{}: the {} fit found no finite misfit", data.source, bsdf::to_string(kind));

    if (best_cost >= 0.5 * static_cast<double>(data.size()) * kRefusedResidual * kRefusedResidual)
        fail("{}: the {} model refused every parameter set tried, e.g.: {}", data.source, bsdf::to_string(kind),
             problem.first_refusal());
    fit.fitted = problem.values(best);
    const Eigen::VectorXd r = problem.residuals(best);
    fit.residual.assign(r.data(), r.data() + r.size());
    fit.sum_squares = r.squaredNorm();
    fit.misfit = fit.with_errors ? fit.sum_squares / static_cast<double>(fit.dof)
                                 : std::sqrt(fit.sum_squares / static_cast<double>(data.size()));
    std::vector<std::size_t> order(data.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return std::abs(fit.residual[a]) > std::abs(fit.residual[b]); });
    order.resize(std::min<std::size_t>(5, order.size()));
    fit.worst = order;

    // Covariance of the solver variables: (J^T J)^-1 through the SVD of J, times chi2/dof without errors.
    const double scale = fit.with_errors ? 1.0 : fit.sum_squares / static_cast<double>(fit.dof);
    const auto values = problem.physical(best);
    std::vector<bool> constrained(free_count, true);
    std::vector<std::string> why(free_count);
    Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(free_count),
                                                       static_cast<Eigen::Index>(free_count));
    if (free_count > 0) {
        const Eigen::MatrixXd j = problem.jacobian(best);
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeThinV);
        const Eigen::VectorXd s = svd.singularValues();
        const Eigen::MatrixXd& v = svd.matrixV();
        for (Eigen::Index i = 0; i < s.size(); ++i) {
            // The standard error along this direction of the solver variables.
            const double along = s[i] > 1e-12 * std::max(s[0], 1e-300) ? std::sqrt(scale) / s[i]
                                                                        : std::numeric_limits<double>::infinity();
            if (std::isfinite(along)) covariance += scale / (s[i] * s[i]) * v.col(i) * v.col(i).transpose();
            if (along <= kUnconstrainedLogError) continue;
            std::string combination;
            for (Eigen::Index k = 0; k < v.rows(); ++k) {
                if (std::abs(v(k, i)) < 0.1) continue;
                combination += fmt::format("{}{:+.2f} {}", combination.empty() ? "" : " ", v(k, i),
                                           internal_name(problem.free()[static_cast<std::size_t>(k)]));
                if (!std::isfinite(along)) {
                    constrained[static_cast<std::size_t>(k)] = false;
                    why[static_cast<std::size_t>(k)] = "the data do not depend on it";
                }
            }
            fit.degenerate_directions.push_back(
                std::isfinite(along) ? fmt::format("{} (standard error {:.3g})", combination, along)
                                     : fmt::format("{} (no effect on the data)", combination));
        }
    }
    for (std::size_t k = 0; k < free_count; ++k) {
        const int p = problem.free()[k];
        const double se = std::sqrt(std::max(0.0, covariance(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k))));
        const double limit = is_log(p) ? kUnconstrainedLogError : kUnconstrainedLayError;
        if (constrained[k] && se > limit) {
            constrained[k] = false;
            why[k] = fmt::format("standard error {:.3g} in {} (> {})", se, internal_name(p), limit);
        }
        if (const std::string at = bound_note(p, values[p], problem.bounds(p)); !at.empty()) {
            constrained[k] = false;
            why[k] = at;
        }
    }
    for (int p : problem.active()) {
        ParameterEstimate e;
        e.name = kParameterNames[p];
        e.value = values[p];
        const auto at = std::find(problem.free().begin(), problem.free().end(), p);
        if (at == problem.free().end()) {
            e.fixed = true;
        } else {
            const auto k = static_cast<std::size_t>(at - problem.free().begin());
            e.constrained = constrained[k];
            e.note = why[k];
            const auto kk = static_cast<Eigen::Index>(k);
            if (e.constrained)
                e.standard_error = physical_slope(p, best[kk]) * std::sqrt(std::max(0.0, covariance(kk, kk)));
            fit.free.push_back(e.name);
        }
        fit.parameters.push_back(e);
    }
    fit.correlation.assign(free_count, std::vector<std::optional<double>>(free_count));
    for (std::size_t a = 0; a < free_count; ++a)
        for (std::size_t b = 0; b < free_count; ++b) {
            if (!constrained[a] || !constrained[b]) continue;
            const auto ia = static_cast<Eigen::Index>(a), ib = static_cast<Eigen::Index>(b);
            const double d = std::sqrt(covariance(ia, ia) * covariance(ib, ib));
            if (d > 0) fit.correlation[a][b] = std::clamp(covariance(ia, ib) / d, -1.0, 1.0);
        }
    if (problem.refused() > 0)
        fit.notes.push_back(fmt::format("the model refused {} of the parameter sets tried, e.g.: {}", problem.refused(),
                                        problem.first_refusal()));
    fit.evaluations = problem.evaluations();
    fit.cpu_seconds = cpu_seconds() - cpu_start;
    return fit;
}

}  // namespace

FitResult fit_brdf(const BrdfData& data, const FitOptions& options) {
    validate(data);
    if (options.models.empty()) fail("give at least one model to fit");
    if (options.psd != bsdf::PsdKind::kc && options.psd != bsdf::PsdKind::gaussian)
        fail("{} must be kc or gaussian for a fit, got {}", options.names.psd, bsdf::to_string(options.psd));
    if (options.starts < 1 || options.starts > 3) fail("starts must be 1, 2 or 3, got {}", options.starts);
    if (options.refined < 1 || options.refined > options.starts)
        fail("refined must be between 1 and starts ({}), got {}", options.starts, options.refined);
    if (options.profile && options.anisotropic)
        fail("{} data are a cut through isotropic statistics: {} does not apply", options.names.profile,
             options.names.anisotropic);
    if (options.max_evaluations_per_start < 1)
        fail("max_evaluations_per_start must be >= 1, got {}", options.max_evaluations_per_start);
    for (const auto& fixed : options.fixed) {
        const auto& [name, value] = fixed;
        const auto* end = std::end(kParameterNames);
        // By the pair, not the binding: clang 14 (the fuzz and sanitizer builds) cannot capture a structured binding.
        if (std::find_if(std::begin(kParameterNames), end, [&](const char* n) { return fixed.first == n; }) == end)
            fail("{} {}: not a parameter; the parameters are sigma_um, corr_length_um, gamma, corr_length_v_um, "
                 "lay_angle_deg", options.names.fix, printable(name));
        if (!std::isfinite(value)) fail("{} {}={}: the value must be finite", options.names.fix, name, value);
        if (name == "gamma" && options.psd != bsdf::PsdKind::kc)
            fail("{} gamma applies to {} kc only (gaussian has no gamma)", options.names.fix, options.names.psd);
        if ((name == "corr_length_v_um" || name == "lay_angle_deg") && !options.anisotropic)
            fail("{} {} applies to an anisotropic fit only ({})", options.names.fix, name, options.names.anisotropic);
    }
    // Hundreds of one-off surfaces: their tables are not worth the disk cache (core/table_cache.hpp).
    const TableCacheWritesPaused paused;
    FitResult result;
    for (const auto model : options.models) result.fits.push_back(fit_model(data, options, model));

    // Best: the smallest sum of squares; another fit is indistinguishable when its sum of squares exceeds the best's
    // by less than one standard deviation of a chi-square with the best's degrees of freedom, sqrt(2 dof), in units
    // of the best's residual variance (1 with errors given, its sum of squares / dof without).
    for (std::size_t m = 1; m < result.fits.size(); ++m)
        if (result.fits[m].sum_squares < result.fits[result.best].sum_squares) result.best = m;
    const ModelFit& best = result.fits[result.best];
    const double unit = best.with_errors ? 1.0 : best.sum_squares / static_cast<double>(best.dof);
    std::string others;
    for (std::size_t m = 0; m < result.fits.size(); ++m) {
        if (m == result.best) continue;
        const double delta = (result.fits[m].sum_squares - best.sum_squares) / std::max(unit, 1e-300);
        if (delta < std::sqrt(2.0 * static_cast<double>(best.dof))) {
            result.indistinguishable.push_back(m);
            others += (others.empty() ? "" : ", ") + bsdf::to_string(result.fits[m].model);
        }
    }
    const std::string name = bsdf::to_string(best.model);
    const std::string misfit = fmt::format("{} {:.4g}", best.with_errors ? "chi2/dof" : "relative rms", best.misfit);
    if (result.fits.size() == 1)
        result.verdict = fmt::format("{}: {} (the only model fitted)", name, misfit);
    else
        result.verdict = others.empty()
                         ? fmt::format("best: {} ({}); every other model fits worse beyond the data's errors", name,
                                       misfit)
                         : fmt::format("best: {} ({}), indistinguishable within the errors from {}", name, misfit,
                                       others);
    return result;
}

}  // namespace surfscatter::inverse
