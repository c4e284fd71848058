#include "surfscatter/surface/elliptical_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <unsupported/Eigen/NonLinearOptimization>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/least_squares_functor.hpp"

namespace surfscatter::surface {

namespace {

// The periodogram's bins in the band, pooled into polar cells.
struct CellData {
    std::vector<double> zx, zy, multiplicity;  // bins
    std::vector<std::size_t> cell;             // of each bin
    // Cells: ln mean P, full-plane points, independent samples if the PSD were flat over the cell, and the weight nu
    // and log bias b of the fit (set_weights()).
    std::vector<double> log_psd, points, samples, weight, log_bias;
};

// Parameters x = (a, e1, e2, g): a = ln sqrt(LU LV), (e1, e2) = ln(LU / LV) (cos 2A, sin 2A), g = ln(gamma - 1).
struct Ellipse {
    double lu, lv, angle, gamma;
};

Ellipse ellipse_of(const Eigen::Vector4d& x) {
    const double delta = std::hypot(x[1], x[2]);
    return {std::exp(x[0] + 0.5 * delta), std::exp(x[0] - 0.5 * delta), 0.5 * std::atan2(x[2], x[1]),
            1.0 + std::exp(x[3])};
}

// The search box: each of LU, LV in [l_min, l_max] (the isotropic fit's range for L) and g in the isotropic fit's.
struct Box {
    double log_l_min, log_l_max, log_g_min, log_g_max;
};

// Levenberg-Marquardt may step far outside the box; there the model is held at the box's edge (slightly beyond it,
// so that the bound test reports such a fit) instead of building an invalid one, as in fit_kc.
Eigen::Vector4d held_in_box(Eigen::Vector4d x, const Box& box) {
    const double margin = 0.5;
    x[3] = std::clamp(x[3], box.log_g_min - margin, box.log_g_max + margin);
    const double lo = box.log_l_min - margin, hi = box.log_l_max + margin;
    x[0] = std::clamp(x[0], lo, hi);
    const double delta = std::hypot(x[1], x[2]);
    const double max_delta = 2.0 * std::min(hi - x[0], x[0] - lo);  // both ln LU, ln LV inside [lo, hi]
    if (delta > max_delta) {
        x[1] *= max_delta / delta;
        x[2] *= max_delta / delta;
    }
    return x;
}

// ln of the model's cell means, ln(norm S_c / points_c) with S_c = sum_k m_k (1 + q_k)^p, and (if `gradient`) its
// derivatives with respect to x (cells x 4), analytic: the fit and its covariance need them at every step.
// With `sums` and `sum_squares`, also S_c and sum_k m_k (1 + q_k)^(2p) per cell (see set_weights()).
void log_cell_model(const CellData& data, const Eigen::Vector4d& x, Eigen::VectorXd& log_model,
                    Eigen::MatrixXd* gradient, std::vector<double>* sums = nullptr,
                    std::vector<double>* sum_squares = nullptr) {
    // LU^2 zeta_u^2 + LV^2 zeta_v^2 = zeta^T M zeta, M = exp(2a) (cosh d I + sinh d / d [[e1, e2], [e2, -e1]]).
    const double e1 = x[1], e2 = x[2], delta = std::hypot(e1, e2);
    const double sinhc = delta > 1e-4 ? std::sinh(delta) / delta : 1.0 + delta * delta / 6.0;
    // (d sinhc / d delta) / delta, 1/3 + delta^2 / 30 near isotropy.
    const double h = delta > 1e-2 ? (delta * std::cosh(delta) - std::sinh(delta)) / (delta * delta * delta)
                                  : 1.0 / 3.0 + delta * delta / 30.0;
    const double scale = std::exp(2.0 * x[0]), gm1 = std::exp(x[3]), cosh = std::cosh(delta);
    const double mxx = scale * (cosh + e1 * sinhc), myy = scale * (cosh - e1 * sinhc), mxy = scale * e2 * sinhc;
    // dM/de1 and dM/de2 (times exp(2a)).
    const double axx = scale * (e1 * sinhc + sinhc + e1 * e1 * h), ayy = scale * (e1 * sinhc - sinhc - e1 * e1 * h);
    const double axy = scale * e1 * e2 * h;
    const double bxx = scale * (e2 * sinhc + e1 * e2 * h), byy = scale * (e2 * sinhc - e1 * e2 * h);
    const double bxy = scale * (sinhc + e2 * e2 * h);
    const double exponent = -0.5 * (gm1 + 2.0);  // -(gamma + 1) / 2
    const std::size_t cells = data.log_psd.size();
    std::vector<double> sum(cells, 0.0);
    std::vector<Eigen::Vector4d> sum_gradient(gradient ? cells : 0, Eigen::Vector4d::Zero());
    if (sum_squares) sum_squares->assign(cells, 0.0);
    for (std::size_t k = 0; k < data.zx.size(); ++k) {
        const double zx = data.zx[k], zy = data.zy[k];
        const double q = mxx * zx * zx + 2.0 * mxy * zx * zy + myy * zy * zy, log1pq = std::log1p(q);
        const double value = data.multiplicity[k] * std::exp(exponent * log1pq);
        sum[data.cell[k]] += value;
        if (sum_squares) (*sum_squares)[data.cell[k]] += value * value / data.multiplicity[k];
        if (!gradient) continue;
        const double dq = value * exponent / (1.0 + q);
        sum_gradient[data.cell[k]] += Eigen::Vector4d(dq * 2.0 * q,
                                                      dq * (axx * zx * zx + 2.0 * axy * zx * zy + ayy * zy * zy),
                                                      dq * (bxx * zx * zx + 2.0 * bxy * zx * zy + byy * zy * zy),
                                                      value * log1pq * -0.5 * gm1);
    }
    if (sums) *sums = sum;
    const double log_norm = std::log(gm1 * scale / (2.0 * kPi));  // (gamma - 1) LU LV / (2 pi)
    log_model.resize(static_cast<Eigen::Index>(cells));
    if (gradient) gradient->resize(static_cast<Eigen::Index>(cells), 4);
    for (std::size_t c = 0; c < cells; ++c) {
        const auto i = static_cast<Eigen::Index>(c);
        log_model[i] = log_norm + std::log(sum[c] / data.points[c]);
        if (gradient) gradient->row(i) = (sum_gradient[c] / sum[c] + Eigen::Vector4d(2.0, 0.0, 0.0, 1.0)).transpose();
    }
}

// Residuals sqrt(nu_c) (ln Pbar_c - b_c - ln sigma^2 - ln Phat_c) with ln sigma^2 profiled out (returned), and (if
// `jacobian`) their derivatives with respect to x.
double cell_residuals(const CellData& data, const Box& box, const Eigen::Vector4d& raw, Eigen::VectorXd& residuals,
                      Eigen::MatrixXd* jacobian = nullptr) {
    Eigen::VectorXd log_model;
    log_cell_model(data, held_in_box(raw, box), log_model, jacobian);
    const auto n = static_cast<Eigen::Index>(data.log_psd.size());
    const Eigen::Map<const Eigen::VectorXd> weight(data.weight.data(), n);
    const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(data.log_psd.data(), n) -
                              Eigen::Map<const Eigen::VectorXd>(data.log_bias.data(), n) - log_model;
    const double log_variance = weight.dot(d) / weight.sum();
    residuals = weight.cwiseSqrt().cwiseProduct((d.array() - log_variance).matrix());
    if (jacobian) {
        // d residual / dx = -sqrt(nu) (G - sum nu G / sum nu): ln sigma^2 follows the model.
        const Eigen::RowVector4d mean = weight.transpose() * *jacobian / weight.sum();
        *jacobian = -(weight.cwiseSqrt().asDiagonal() * (jacobian->rowwise() - mean));
    }
    return log_variance;
}

struct CellResidualFunctor : DynamicLeastSquaresFunctor {
    const CellData* data;
    const Box* box;
    int inputs() const { return 4; }
    int values() const { return static_cast<int>(data->log_psd.size()); }
    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& residuals) const {
        cell_residuals(*data, *box, Eigen::Vector4d(x), residuals);
        return 0;
    }
    int df(const Eigen::VectorXd& x, Eigen::MatrixXd& jacobian) const {
        Eigen::VectorXd residuals;
        cell_residuals(*data, *box, Eigen::Vector4d(x), residuals, &jacobian);
        return 0;
    }
};

// A cell mean of exponential variables with unequal means mu_k has the relative variance sum mu_k^2 / (sum mu_k)^2, not
// 1 / n: where the model varies across a cell (a strongly anisotropic PSD in a wide low-ring sector) it holds fewer
// independent samples. nu_c = samples_c (sum mu)^2 / (n sum mu^2) under the model x (flat if null), and its log bias.
void set_weights(CellData& data, const Eigen::Vector4d* x) {
    const std::size_t cells = data.log_psd.size();
    std::vector<double> concentration(cells, 1.0);
    if (x) {
        Eigen::VectorXd log_model;
        std::vector<double> sums, sum_squares;
        log_cell_model(data, *x, log_model, nullptr, &sums, &sum_squares);
        for (std::size_t c = 0; c < cells; ++c)
            concentration[c] = sums[c] * sums[c] / (data.points[c] * sum_squares[c]);
    }
    for (std::size_t c = 0; c < cells; ++c) {
        const double nu = data.samples[c] * concentration[c];
        data.weight[c] = nu;
        data.log_bias[c] = -1.0 / (2.0 * nu) - 1.0 / (12.0 * nu * nu);
    }
}

CellData pool_cells(const Psd2d& psd, double zeta_min, double zeta_max, std::size_t& skipped) {
    const double ring_width = std::max(psd.dzeta_x, psd.dzeta_y);
    auto ring_of = [&](double zeta) { return static_cast<std::size_t>(std::floor(zeta / ring_width + 0.5)); };
    auto in_band = [&](double zeta) { return zeta >= zeta_min && zeta <= zeta_max; };
    // Pass 1: full-plane points per ring, which sets its number of sectors.
    const std::size_t rings = ring_of(zeta_max) + 1;
    std::vector<double> ring_points(rings, 0.0);
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const double zeta = std::hypot(psd.zeta_x(kx), psd.zeta_y(ky));
            if (in_band(zeta)) ring_points[ring_of(zeta)] += psd.multiplicity(kx);
        }
    std::vector<std::size_t> sectors(rings), first_cell(rings);
    std::size_t cells = 0;
    for (std::size_t r = 0; r < rings; ++r) {
        sectors[r] = std::max<std::size_t>(1, static_cast<std::size_t>(ring_points[r] / kEllipticalCellPoints));
        first_cell[r] = cells;
        cells += ring_points[r] > 0.0 ? sectors[r] : 0;
    }
    // Pass 2: bins into cells, sums of P and of points.
    CellData data;
    std::vector<double> sum_psd(cells, 0.0), points(cells, 0.0), sum_zeta(cells, 0.0);
    std::vector<std::size_t> bin_cell;
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const double zx = psd.zeta_x(kx), zy = psd.zeta_y(ky), zeta = std::hypot(zx, zy);
            if (!in_band(zeta)) continue;
            const std::size_t r = ring_of(zeta);
            double theta = std::atan2(zy, zx);
            if (theta < 0.0) theta += kPi;  // point symmetry: (zx, zy) and (-zx, -zy) in one cell
            const auto sector = std::min(sectors[r] - 1, static_cast<std::size_t>(theta / kPi * static_cast<double>(sectors[r])));
            const std::size_t c = first_cell[r] + sector;
            const double m = psd.multiplicity(kx);
            sum_psd[c] += m * psd.values[ky * psd.half_nx() + kx];
            points[c] += m;
            data.zx.push_back(zx);
            data.zy.push_back(zy);
            data.multiplicity.push_back(m);
            bin_cell.push_back(c);
        }
    // Cells whose mean is not positive (masked estimates far below their scatter) have no log: dropped, renumbered.
    std::vector<std::size_t> index(cells, cells);
    for (std::size_t c = 0; c < cells; ++c) {
        if (!(points[c] > 0.0)) continue;
        if (!(sum_psd[c] > 0.0)) {
            ++skipped;
            continue;
        }
        index[c] = data.log_psd.size();
        data.log_psd.push_back(std::log(sum_psd[c] / points[c]));
        data.samples.push_back(effective_samples(psd.window, points[c], psd.valid_weight));
        data.points.push_back(points[c]);
    }
    std::size_t kept = 0;
    for (std::size_t k = 0; k < bin_cell.size(); ++k) {
        if (index[bin_cell[k]] == cells) continue;
        data.zx[kept] = data.zx[k];
        data.zy[kept] = data.zy[k];
        data.multiplicity[kept] = data.multiplicity[k];
        data.cell.push_back(index[bin_cell[k]]);
        ++kept;
    }
    data.zx.resize(kept);
    data.zy.resize(kept);
    data.multiplicity.resize(kept);
    data.weight.resize(data.log_psd.size());
    data.log_bias.resize(data.log_psd.size());
    set_weights(data, nullptr);
    return data;
}

// Lay angle and LV / LU from the band's second-moment tensor sum P zeta zeta^T (THEORY 7.1: the slope covariance,
// diagonal in (u, v) with variances in the ratio LV^2 : LU^2).
Eigen::Vector2d moment_start(const Psd2d& psd, double zeta_min, double zeta_max) {
    Eigen::Matrix2d tensor = Eigen::Matrix2d::Zero();
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const double zx = psd.zeta_x(kx), zy = psd.zeta_y(ky), zeta = std::hypot(zx, zy);
            if (zeta < zeta_min || zeta > zeta_max) continue;
            const double p = psd.multiplicity(kx) * std::max(0.0, psd.values[ky * psd.half_nx() + kx]);
            tensor(0, 0) += p * zx * zx;
            tensor(0, 1) += p * zx * zy;
            tensor(1, 1) += p * zy * zy;
        }
    tensor(1, 0) = tensor(0, 1);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(tensor);
    const Eigen::Vector2d u = eigen.eigenvectors().col(0);  // the smaller eigenvalue: along the lay
    const double lo = eigen.eigenvalues()[0], hi = eigen.eigenvalues()[1];
    const double delta = lo > 0.0 && hi > 0.0 ? 0.5 * std::log(hi / lo) : 0.0;  // ln(LU / LV)
    const double angle = std::atan2(u.y(), u.x());
    return {delta * std::cos(2.0 * angle), delta * std::sin(2.0 * angle)};
}

}  // namespace

EllipticalStatistics EllipticalKcFit::statistics() const {
    return EllipticalStatistics(std::make_shared<KCorrelation>(sigma_h_um, corr_length_u_um, gamma), corr_length_v_um,
                                lay_angle_deg * kPi / 180.0);
}

EllipticalKcFit fit_elliptical_kc(const Psd2d& psd, const KcFit& isotropic) {
    EllipticalKcFit fit;
    fit.window = psd.window;
    fit.zeta_min = isotropic.zeta_min;
    fit.zeta_max = isotropic.zeta_max;
    CellData data = pool_cells(psd, fit.zeta_min, fit.zeta_max, fit.skipped_cells);
    fit.cells = data.log_psd.size();
    if (fit.cells < 16) {
        // Too small a map for the 2-D fit (the isotropic one may still stand): the isotropic fit is the best attempt.
        fit.sigma_h_um = isotropic.sigma_h_um;
        fit.corr_length_u_um = fit.corr_length_v_um = isotropic.corr_length_um;
        fit.gamma = isotropic.gamma;
        fit.lay_angle_error_deg = 90.0;
        fit.failure = fmt::format("elliptical KC fit: only {} cells of the 2-D PSD between {:.4g} and {:.4g} rad/um; "
                                  "the map is too small to fit (need >= 16)",
                                  fit.cells, fit.zeta_min, fit.zeta_max);
        return fit;
    }
    const Box box{std::log(0.25 / fit.zeta_max), std::log(4.0 / fit.zeta_min), std::log(kKcGammaMinusOneMin),
                  std::log(kKcGammaMinusOneMax)};

    CellResidualFunctor functor{{}, &data, &box};
    // Levenberg-Marquardt from x; false if it left the finite numbers.
    const auto minimise = [&functor](Eigen::VectorXd& x) {
        Eigen::LevenbergMarquardt<CellResidualFunctor> solver(functor);
        solver.parameters.xtol = 1e-10;
        solver.parameters.ftol = 1e-12;
        solver.parameters.maxfev = 2000;
        solver.minimize(x);
        return x.allFinite();
    };
    Eigen::VectorXd residuals;
    const Eigen::Vector2d moments = moment_start(psd, fit.zeta_min, fit.zeta_max);
    Eigen::Vector4d best;
    double best_cost = std::numeric_limits<double>::infinity();
    // From the moments' ellipse and from isotropy, both with the isotropic fit's L and gamma: the better end wins.
    for (const Eigen::Vector2d& e : {moments, Eigen::Vector2d(0.0, 0.0)}) {
        Eigen::VectorXd x(4);
        x << std::log(isotropic.corr_length_um), e.x(), e.y(), std::log(isotropic.gamma - 1.0);
        if (!minimise(x)) continue;
        const Eigen::Vector4d held = held_in_box(Eigen::Vector4d(x), box);
        cell_residuals(data, box, held, residuals);
        if (residuals.squaredNorm() < best_cost) {
            best_cost = residuals.squaredNorm();
            best = held;
        }
    }
    if (!std::isfinite(best_cost)) fail("elliptical KC fit: the 2-D PSD gives no finite misfit anywhere");
    // Reweighted once by the fitted model's spread over each cell (set_weights()) and polished from there.
    set_weights(data, &best);
    if (Eigen::VectorXd x = best; minimise(x)) best = held_in_box(Eigen::Vector4d(x), box);

    const double log_variance = cell_residuals(data, box, best, residuals);
    double sum_w = 0.0;
    for (double w : data.weight) sum_w += w;
    fit.log_residual_rms = std::sqrt(residuals.squaredNorm() / sum_w);
    fit.statistical_floor = std::sqrt(static_cast<double>(fit.cells) / sum_w);
    const Ellipse ellipse = ellipse_of(best);
    fit.sigma_h_um = std::exp(0.5 * log_variance);
    fit.corr_length_u_um = ellipse.lu;
    fit.corr_length_v_um = ellipse.lv;
    fit.gamma = ellipse.gamma;
    double angle = ellipse.angle * 180.0 / kPi;
    if (angle < 0.0) angle += 180.0;
    fit.lay_angle_deg = angle >= 180.0 ? angle - 180.0 : angle;

    // Covariance of (ln sigma^2, a, e1, e2, g) from the weighted Jacobian -sqrt(nu) (1, d ln Phat / dx), inflated by
    // the reduced chi-square where the model misfits.
    const auto n = static_cast<Eigen::Index>(fit.cells);
    Eigen::VectorXd log_model;
    Eigen::MatrixXd model_gradient;
    log_cell_model(data, best, log_model, &model_gradient);
    const Eigen::VectorXd root_weight = Eigen::Map<const Eigen::VectorXd>(data.weight.data(), n).cwiseSqrt();
    Eigen::MatrixXd jacobian(n, 5);
    jacobian.col(0) = -root_weight;
    jacobian.rightCols(4) = -(root_weight.asDiagonal() * model_gradient);
    const double reduced_chi2 = residuals.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, n - 5));
    const Eigen::MatrixXd covariance =
        (jacobian.transpose() * jacobian).inverse() * std::max(1.0, reduced_chi2);
    const double delta = std::hypot(best[1], best[2]);
    const Eigen::Matrix2d cov_e = covariance.block<2, 2>(2, 2);
    fit.anisotropy_chi2 = best.segment<2>(1).dot(cov_e.inverse() * best.segment<2>(1));
    auto spread = [&](const Eigen::VectorXd& gradient) { return std::sqrt(gradient.dot(covariance * gradient)); };
    Eigen::VectorXd g = Eigen::VectorXd::Zero(5);
    g[0] = 0.5;
    fit.sigma_h_error_um = fit.sigma_h_um * spread(g);
    const double cu = delta > 1e-12 ? best[1] / delta : 0.0, su = delta > 1e-12 ? best[2] / delta : 0.0;
    g.setZero();
    g << 0.0, 1.0, 0.5 * cu, 0.5 * su, 0.0;
    fit.corr_length_u_error_um = fit.corr_length_u_um * spread(g);
    g << 0.0, 1.0, -0.5 * cu, -0.5 * su, 0.0;
    fit.corr_length_v_error_um = fit.corr_length_v_um * spread(g);
    g << 0.0, 0.0, cu, su, 0.0;
    fit.axis_ratio_error = fit.axis_ratio() * spread(g);  // d ln(LV / LU) = -d delta
    g << 0.0, 0.0, 0.0, 0.0, 1.0;
    fit.gamma_error = (fit.gamma - 1.0) * spread(g);
    g << 0.0, 0.0, -best[2], best[1], 0.0;
    // Near isotropy A is undefined: its error is capped at 90 deg (any angle).
    fit.lay_angle_error_deg = delta > 1e-12 ? std::min(90.0, 90.0 / kPi * spread(g) / (delta * delta)) : 90.0;
    const bool constrained = covariance.allFinite() && std::isfinite(fit.anisotropy_chi2);
    if (!constrained) {
        fit.sigma_h_error_um = fit.corr_length_u_error_um = fit.corr_length_v_error_um = fit.gamma_error = 0.0;
        fit.axis_ratio_error = fit.anisotropy_chi2 = 0.0;
        fit.lay_angle_error_deg = 90.0;
    }

    const std::string band = fmt::format("the 2-D PSD between {:.4g} and {:.4g} rad/um ({} cells)", fit.zeta_min,
                                         fit.zeta_max, fit.cells);
    const std::string attempt = fmt::format(
        "best attempt LU = {:.4g} um, LV = {:.4g} um, lay angle {:.4g} deg, gamma = {:.4g}, misfit log_residual_rms "
        "{:.3g} against a statistical floor of {:.3g}",
        fit.corr_length_u_um, fit.corr_length_v_um, fit.lay_angle_deg, fit.gamma, fit.log_residual_rms,
        fit.statistical_floor);
    const double log_lu = std::log(fit.corr_length_u_um), log_lv = std::log(fit.corr_length_v_um);
    const char* end_u = search_box_end(log_lu, box.log_l_min, box.log_l_max);
    const char* end_v = search_box_end(log_lv, box.log_l_min, box.log_l_max);
    if (!constrained)
        fit.failure = fmt::format("elliptical KC fit: {} does not constrain the parameters (singular covariance; {})",
                                  band, attempt);
    else if (end_u || end_v)
        fit.failure = fmt::format(
            "elliptical KC fit: no elliptical KC fits {}: {} lies at the {} end of the range searched, {:.4g} to "
            "{:.4g} um (1/(4 zeta_max) to 4/zeta_min): the PSD has no KC knee along that axis inside the band ({})",
            band, end_u ? "LU (along the lay)" : "LV (across the lay)", end_u ? end_u : end_v,
            std::exp(box.log_l_min), std::exp(box.log_l_max), attempt);
    else if (const char* end = search_box_end(best[3], box.log_g_min, box.log_g_max))
        fit.failure = fmt::format(
            "elliptical KC fit: gamma is not resolved by {}: gamma was searched from {:.4g} to {:.4g} and the best "
            "attempt lies at the {} end ({})",
            band, 1.0 + kKcGammaMinusOneMin, 1.0 + kKcGammaMinusOneMax, end, attempt);
    return fit;
}

void require_resolved(const EllipticalKcFit& fit) {
    if (!fit.failure.empty()) fail("{}", fit.failure);
}

Psd2d fitted_psd(const EllipticalKcFit& fit, const Psd2d& like) {
    const EllipticalStatistics model = fit.statistics();
    const double variance = fit.sigma_h_um * fit.sigma_h_um;
    Psd2d out = like;
    for (std::size_t ky = 0; ky < like.ny; ++ky)
        for (std::size_t kx = 0; kx < like.half_nx(); ++kx)
            out.values[ky * like.half_nx() + kx] = variance * model.psd_unit({like.zeta_x(kx), like.zeta_y(ky)});
    return out;
}

}  // namespace surfscatter::surface
