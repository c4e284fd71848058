#include "surfscatter/reference/exact_1d.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include <Eigen/Dense>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/banded_solve.hpp"
#include "surfscatter/reference/circulant.hpp"
#include "surfscatter/reference/dense_solve.hpp"
#include "surfscatter/reference/far_field_sum.hpp"
#include "surfscatter/reference/far_interaction.hpp"
#include "surfscatter/reference/gmres.hpp"
#include "surfscatter/reference/hankel.hpp"

namespace surfscatter::reference {

namespace {

using Complex = std::complex<double>;
constexpr Complex kI{0.0, 1.0};
constexpr double kEulerGamma = 0.57721566490153286061;
// zeta'(-2) = -zeta(3)/(4 pi^2) and zeta'(-4) = 3 zeta(5)/(4 pi^4).
constexpr double kZetaPrimeMinus2 = -0.030448457058393270780;
constexpr double kZetaPrimeMinus4 = 0.0079838114502686242;

// Navot's expansion of the trapezoid rule for f(x) ln|x - x_i| on a uniform grid (step D, node x_i included with
// the weight ln(D / 2 pi)): int = D sum_{j != i} f_j ln|x_j - x_i| + D f_i ln(D/2pi)
//   + 2 sum_{p >= 1} D^{2p+1} zeta'(-2p) f^(2p)(x_i) / (2p)!.
// The p = 1, 2 terms with f'' and f'''' from five-point differences leave an error O(D^7) (docs/REFERENCE.md);
// kLogCorrection[m + 2] is the weight of f_{i+m} over D.
constexpr double kLogCorrection[5] = {
    kZetaPrimeMinus2 * -1.0 / 12.0 + kZetaPrimeMinus4 / 12.0,
    kZetaPrimeMinus2 * 16.0 / 12.0 - 4.0 * kZetaPrimeMinus4 / 12.0,
    kZetaPrimeMinus2 * -30.0 / 12.0 + 6.0 * kZetaPrimeMinus4 / 12.0,
    kZetaPrimeMinus2 * 16.0 / 12.0 - 4.0 * kZetaPrimeMinus4 / 12.0,
    kZetaPrimeMinus2 * -1.0 / 12.0 + kZetaPrimeMinus4 / 12.0,
};

// |(dx, dz)| without std::hypot's overflow guards (slow, and a profile's lengths in um are far from overflow).
double distance(double dx, double dz) { return std::sqrt(dx * dx + dz * dz); }

struct Surface {
    std::size_t n = 0;
    double step = 0.0;
    std::vector<double> x, h, dh, d2h;
};

// Nodes per profile interval (>= 1); counted in double so that a coarse profile or a tiny wavelength cannot wrap
// around (check_options bounds the total).
double subdivisions_of(const Profile& profile, double lambda_um, double points_per_wavelength) {
    return std::max(1.0, std::ceil(profile.spacing_um * points_per_wavelength / lambda_um - 1e-9));
}

Surface solver_surface(const Profile& profile, double lambda_um, double points_per_wavelength) {
    const auto subdivisions = static_cast<std::size_t>(subdivisions_of(profile, lambda_um, points_per_wavelength));
    SplineNodes nodes = spline_nodes(profile, subdivisions);
    Surface s;
    s.n = nodes.h.size();
    s.step = nodes.step_um;
    s.x.resize(s.n);
    for (std::size_t j = 0; j < s.n; ++j) s.x[j] = nodes.x0_um + nodes.step_um * static_cast<double>(j);
    s.h = std::move(nodes.h);
    s.dh = std::move(nodes.dh);
    s.d2h = std::move(nodes.d2h);
    return s;
}

// fill(i, j) for every pair i < j <= i + band: each kernel is evaluated once per pair and gives both entries.
template <typename Fill>
void for_each_pair(std::size_t n, std::size_t band, Fill fill) {
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j <= std::min(i + band, n - 1); ++j) fill(i, j);
}

// Navot's corrections on the five central entries of each row: D kLogCorrection[o + 2] A(x_i, x_{i+o}), A = the
// kernel's log part log_part(i, j); at(i, j) is the entry, for |i - j| <= 2.
template <typename LogPart, typename At>
void add_log_corrections(const Surface& s, LogPart log_part, At at) {
    const auto n = static_cast<std::ptrdiff_t>(s.n);
    for (std::ptrdiff_t i = 0; i < n; ++i)
        for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(i - 2, 0); j <= std::min(i + 2, n - 1); ++j) {
            const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
            at(ui, uj) += s.step * kLogCorrection[j - i + 2] * log_part(ui, uj);
        }
}

// The s kernel's entry step (i/4) H0(k r) between nodes r apart (beyond Navot's corrected entries).
Complex dirichlet_entry(double step, double k, double r) {
    return step * 0.25 * Complex(-::y0(k * r), ::j0(k * r));
}

// s (Dirichlet): psi_inc(x_i) = int (i/4) H0(k R) U(x') dx', U = dpsi/dn sqrt(1 + h'^2). Log part of the kernel
// -J0(kR)/(2 pi) ln|x - x'|; the rest tends to i/4 - (ln(k s/2) + gamma)/(2 pi), s = sqrt(1 + h'^2).
// Entries with |i - j| <= band (>= 2) through at(i, j).
template <typename At>
void fill_dirichlet(const Surface& s, double k, std::size_t band, At at) {
    const double step = s.step;
    for_each_pair(s.n, band, [&](std::size_t i, std::size_t j) {
        at(i, j) = at(j, i) = dirichlet_entry(step, k, distance(s.x[j] - s.x[i], s.h[j] - s.h[i]));
    });
    for (std::size_t i = 0; i < s.n; ++i) {
        const double slope_norm = std::sqrt(1.0 + s.dh[i] * s.dh[i]);
        at(i, i) = step * (-std::log(step / kTwoPi) / kTwoPi + 0.25 * kI -
                           (std::log(0.5 * k * slope_norm) + kEulerGamma) / kTwoPi);
    }
    add_log_corrections(s, [&](std::size_t i, std::size_t j) {
        return -::j0(k * distance(s.x[j] - s.x[i], s.h[j] - s.h[i])) / kTwoPi;
    }, at);
}

// Double layer: (DL psi)_i ~ int D(x_i, x') psi(x') dx', D = (-ik/4) H1(kR) num / R with num = (h(x') - h(x)) -
// h'(x') (x' - x) (the unnormalised normal (-h', 1) at x' dotted with r' - r). D -> h''/(4 pi s^2) as x' -> x; its
// log part (k/2pi) J1(kR) num/R ln|x - x'| vanishes there like (x' - x)^2.
template <typename At>
void fill_double_layer(const Surface& s, double k, std::size_t band, At at) {
    const double step = s.step;
    for_each_pair(s.n, band, [&](std::size_t i, std::size_t j) {
        const double dx = s.x[j] - s.x[i], dz = s.h[j] - s.h[i];
        const double r = distance(dx, dz), z = k * r;
        const Complex h1 = Complex(::j1(z), ::y1(z)) * (-0.25 * k * kI) / r;  // one Hankel call for both entries
        at(i, j) = step * h1 * (dz - s.dh[j] * dx);
        at(j, i) = step * h1 * (-dz + s.dh[i] * dx);
    });
    for (std::size_t i = 0; i < s.n; ++i) at(i, i) = step * s.d2h[i] / (4.0 * kPi * (1.0 + s.dh[i] * s.dh[i]));
    add_log_corrections(s, [&](std::size_t i, std::size_t j) {
        if (i == j) return 0.0;
        const double dx = s.x[j] - s.x[i], dz = s.h[j] - s.h[i];
        const double r = distance(dx, dz);
        return k / kTwoPi * ::j1(k * r) * (dz - s.dh[j] * dx) / r;
    }, at);
}

Eigen::MatrixXcd dirichlet_matrix(const Surface& s, double k) {
    Eigen::MatrixXcd m(s.n, s.n);
    fill_dirichlet(s, k, s.n - 1, [&](std::size_t i, std::size_t j) -> Complex& { return m(i, j); });
    return m;
}

Eigen::MatrixXcd double_layer_matrix(const Surface& s, double k) {
    Eigen::MatrixXcd m(s.n, s.n);
    fill_double_layer(s, k, s.n - 1, [&](std::size_t i, std::size_t j) -> Complex& { return m(i, j); });
    return m;
}

// The same operators' entries with |i - j| <= band only: the near part of the iterative route.
BandedMatrix dirichlet_band(const Surface& s, double k, std::size_t band) {
    BandedMatrix m(s.n, band);
    fill_dirichlet(s, k, band, [&](std::size_t i, std::size_t j) -> Complex& { return m.at(i, j); });
    return m;
}

BandedMatrix double_layer_band(const Surface& s, double k, std::size_t band) {
    BandedMatrix m(s.n, band);
    fill_double_layer(s, k, band, [&](std::size_t i, std::size_t j) -> Complex& { return m.at(i, j); });
    return m;
}

// The interior medium (wavenumber k2 = N k, Im k2 > 0): its kernels decay like exp(-Im(k2) R), often within one node
// spacing (a skin depth of ~25 nm against 55 nm), too fast for a Nystrom rule. Product integration instead: psi
// and L are the cubic Lagrange interpolants of their node values (four nodes around each interval), and each
// interval within reach / Im(k2) of x_i is integrated by Gauss-Legendre (the two next to x_i graded as
// t = u^3 against the logarithm). Entries beyond are below exp(-reach) of the nearest ones and left out: the
// matrices are banded.
// 16 Gauss-Legendre points on the two graded intervals at x_i, and on the others while |k2| D > 3; 8 on the others
// otherwise (the kernel there is smooth on the interval, e^{-Im(k2) r} at most e^{-3} across it: 8 points integrate
// it to ~1e-13 of the interval's weight; docs/REFERENCE.md).
constexpr int kInteriorGauss = 16, kInteriorGaussFar = 8;

struct BandedPair {
    BandedMatrix single, dbl;  // (S2 L)_i and (DL2 psi)_i
};

// Intervals within reach of a node, and the interior matrices' band (cells plus the interpolation's reach).
std::size_t interior_cells(std::size_t n, double step, Complex k2, double reach_decay_lengths) {
    const double reach = reach_decay_lengths / std::max(k2.imag(), 1e-300);
    return static_cast<std::size_t>(std::min(std::ceil(reach / step), static_cast<double>(n)));
}
std::size_t interior_band(std::size_t n, std::size_t cells) { return std::min(cells + 3, n - 1); }

BandedPair interior_matrices(const Surface& s, Complex k2, double reach_decay_lengths) {
    const std::size_t n = s.n;
    const double step = s.step;
    const std::size_t cells = interior_cells(n, step, k2, reach_decay_lengths);
    BandedPair out;
    out.single = BandedMatrix(n, interior_band(n, cells));
    out.dbl = BandedMatrix(n, out.single.band);
    const math::GaussLegendreRule near_rule(kInteriorGauss);
    const math::GaussLegendreRule far_rule(std::abs(k2) * step <= 3.0 ? kInteriorGaussFar : kInteriorGauss);
    // Interpolated from one node spacing on (every interval but the two at x_i lies that far): the Hankel functions
    // were more than half the interior's set-up time (docs/REFERENCE.md, "Speed").
    const auto [h_lo, h_hi] = std::minmax_element(s.h.begin(), s.h.end());
    const HankelRay hankel(k2, step, step * static_cast<double>(cells + 1) + (*h_hi - *h_lo));
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t first = i > cells ? i - cells : 0, last = std::min(i + cells, n - 1);  // intervals [m, m+1]
        for (std::size_t m = first; m < last; ++m) {
            const std::size_t start = std::min(m > 0 ? m - 1 : 0, n - 4);  // the four interpolation nodes
            const bool right = m == i, left = m + 1 == i;
            const math::GaussLegendreRule& rule = right || left ? near_rule : far_rule;
            for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
                const double u = 0.5 * (rule.nodes[q] + 1.0);
                double t = u, jacobian = 1.0;
                if (right) { t = u * u * u; jacobian = 3.0 * u * u; }
                if (left) { t = 1.0 - u * u * u; jacobian = 3.0 * u * u; }
                const double weight = 0.5 * rule.weights[q] * jacobian * step;
                // Cubic Hermite through (h, h') at nodes m, m+1: the spline itself.
                const double t2 = t * t, t3 = t2 * t;
                const double hx = (2 * t3 - 3 * t2 + 1) * s.h[m] + (t3 - 2 * t2 + t) * step * s.dh[m] +
                                  (-2 * t3 + 3 * t2) * s.h[m + 1] + (t3 - t2) * step * s.dh[m + 1];
                const double dhx = ((6 * t2 - 6 * t) * s.h[m] + (-6 * t2 + 6 * t) * s.h[m + 1]) / step +
                                   (3 * t2 - 4 * t + 1) * s.dh[m] + (3 * t2 - 2 * t) * s.dh[m + 1];
                const double dx = step * (static_cast<double>(m) - static_cast<double>(i) + t), dz = hx - s.h[i];
                const double r = distance(dx, dz);
                if (r == 0.0) continue;  // u = 0 is never a Gauss node; guards a degenerate surface only
                const HankelPair hp = hankel(r);
                const Complex single = 0.25 * kI * hp.h0;
                const Complex dbl = -0.25 * kI * k2 * hp.h1 * (dz - dhx * dx) / r;
                const double v = static_cast<double>(m - start) + t;  // position among the four nodes
                for (int a = 0; a < 4; ++a) {
                    double lagrange = 1.0;
                    for (int b = 0; b < 4; ++b)
                        if (b != a) lagrange *= (v - b) / static_cast<double>(a - b);
                    out.single.at(i, start + a) += weight * lagrange * single;
                    out.dbl.at(i, start + a) += weight * lagrange * dbl;
                }
            }
        }
    }
    return out;
}

// LU factors of a banded matrix without pivoting (the interior single layer is dominated by its diagonal: its
// kernel's integral over the node's own cells), in place; throws if a pivot vanishes.
void banded_lu(BandedMatrix& a) {
    const std::size_t n = a.n, band = a.band;
    for (std::size_t p = 0; p < n; ++p) {
        const Complex pivot = a.at(p, p);
        if (!(std::abs(pivot) > 0)) fail("exact-1d: the interior single-layer matrix is singular at node {}", p);
        const std::size_t end = std::min(p + band + 1, n);
        for (std::size_t r = p + 1; r < end; ++r) {
            const Complex f = a.at(r, p) / pivot;
            a.at(r, p) = f;
            if (f == Complex(0.0)) continue;
            for (std::size_t c = p + 1; c < end; ++c) a.at(r, c) -= f * a.at(p, c);
        }
    }
}

// x = A^{-1} b for the banded LU factors of A.
Eigen::VectorXcd banded_solve(const BandedMatrix& lu, Eigen::VectorXcd b) {
    const std::size_t n = lu.n, band = lu.band;
    for (std::size_t r = 0; r < n; ++r) {
        const std::size_t lo = r > band ? r - band : 0;
        b[r] -= dot_segment(&lu.at(r, lo), b.data() + lo, r - lo);
    }
    for (std::size_t r = n; r-- > 0;) {
        const std::size_t hi = std::min(r + band + 1, n);
        if (hi > r + 1) b[r] -= dot_segment(&lu.at(r, r + 1), b.data() + r + 1, hi - r - 1);
        b[r] /= lu.at(r, r);
    }
    return b;
}

// W = B A^{-1} for the banded LU factors of A (row by row: w^T L U = b^T).
Eigen::MatrixXcd banded_right_solve(const BandedMatrix& lu, const Eigen::MatrixXcd& b) {
    const std::size_t n = lu.n, band = lu.band;
    Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w = b;
    for (std::size_t row = 0; row < n; ++row) {
        Complex* x = w.row(row).data();
        for (std::size_t j = 0; j < n; ++j) {  // y U = b
            Complex v = x[j];
            for (std::size_t k = j > band ? j - band : 0; k < j; ++k) v -= x[k] * lu.at(k, j);
            x[j] = v / lu.at(j, j);
        }
        for (std::size_t j = n; j-- > 0;) {  // w L = y (unit diagonal)
            Complex v = x[j];
            for (std::size_t k = j + 1; k < std::min(j + band + 1, n); ++k) v -= x[k] * lu.at(k, j);
            x[j] = v;
        }
    }
    return w;
}

// The profile's length in um.
double profile_length(const Profile& profile) {
    return profile.spacing_um * static_cast<double>(profile.h_um.size() - 1);
}

// Solver nodes of the profile at the options' sampling (a double: cannot wrap around).
double node_count(const Profile& profile, const Exact1dOptions& o) {
    return static_cast<double>(profile.h_um.size() - 1) * subdivisions_of(profile, o.lambda_nm * 1e-3, o.points_per_wavelength) + 1;
}

void check_options(const Profile& profile, const material::Conductor& conductor, const Exact1dOptions& o) {
    const OptionNames& names = o.option_names;
    require_valid_profile(profile, "profile");
    require_positive(o.lambda_nm, fmt::format("{} (nm)", names.wavelength).c_str());
    require_finite(o.theta_i_rad, "theta_i");
    if (!(o.theta_i_rad >= 0 && o.theta_i_rad < 0.5 * kPi))
        fail("theta_i must be in [0, 90) degrees, got {} deg", o.theta_i_rad / kDegree);
    require_positive(o.beam_width_um, fmt::format("{} (um)", names.beam_width).c_str());
    if (!(o.points_per_wavelength >= 4 && o.points_per_wavelength <= 1000))
        fail("{} must be between 4 and 1000, got {}", names.points_per_wavelength, o.points_per_wavelength);
    if (!(o.interior_reach >= 10 && o.interior_reach <= 100))
        fail("interior reach must be between 10 and 100 decay lengths, got {}", o.interior_reach);
    // A medium of index 0 has no wave number inside: its Hankel functions have no argument (was "Hankel function
    // argument 0+0i", naming neither the material nor the wavelength).
    if (!conductor.is_perfect() && conductor.ior(o.lambda_nm) == Complex(0.0, 0.0))
        fail("{} {}: the refractive index at {} nm is n = k = 0, which no medium has (check its table at that "
             "wavelength)", names.material, printable(conductor.name(), kShownPathChars), o.lambda_nm);
    const double k = kTwoPi / (o.lambda_nm * 1e-3);
    const double kgc = k * o.beam_width_um * std::cos(o.theta_i_rad);
    const double correction = (1.0 + 2.0 * std::pow(std::tan(o.theta_i_rad), 2)) / (2.0 * kgc * kgc);
    // Thorsos' beam solves the wave equation only to O(1/(k g cos)^2): beyond 1e-2 its power formula misleads.
    if (correction > 1e-2)
        fail("{} {} um is too narrow for theta_i = {} deg at {} nm: (1 + 2 tan^2) / (2 (k g cos)^2) = {:.3g} > 0.01 "
             "(Thorsos' beam no longer solves the wave equation): use a wider {} or a shorter {}",
             names.beam_width, o.beam_width_um, o.theta_i_rad / kDegree, o.lambda_nm, correction, names.beam_width,
             names.wavelength);
    const double nodes = node_count(profile, o);
    if (!(nodes <= kMaxExact1dNodes))
        fail("exact-1d: a profile of {} samples {} um apart needs {:.3g} solver nodes at {} nm, more than {:.0e}: {}",
             profile.h_um.size(), profile.spacing_um, nodes, o.lambda_nm, kMaxExact1dNodes,
             exact_1d_remedy(o, profile_length(profile)));
    const double margin = kProfileBeamMargin * o.beam_width_um;
    if (profile.x0_um > -margin || profile.x_end_um() < margin)
        fail("profile x from {} to {} um does not hold the beam: it must reach from -{} to {} um ({} beam widths "
             "of {} um either side of x = 0, where the beam is centred)",
             profile.x0_um, profile.x_end_um(), margin, margin, kProfileBeamMargin, o.beam_width_um);
}

}  // namespace

std::vector<double> FarField::intensity_per_rad() const {
    std::vector<double> out(amplitude.size());
    for (std::size_t j = 0; j < amplitude.size(); ++j) out[j] = std::norm(amplitude[j]);
    return out;
}

double thorsos_incident_power(double k, double theta_i, double g) {
    const double c = std::cos(theta_i), t = std::tan(theta_i);
    return std::sqrt(0.5 * kPi) * g * c * (1.0 - (1.0 + 2.0 * t * t) / (2.0 * k * k * g * g * c * c));
}

double incident_power(double k, double theta_i, double g) {
    // A(K) is a Gaussian of width ~2/g around alpha = k sin(theta_i): K steps of 0.2/g over +-14/g; the field
    // without its carrier e^{i alpha x} is smooth on the scale g: x steps of g/40 over +-6 g (taper exp(-36)).
    const double alpha = k * std::sin(theta_i);
    const double dk = 0.2 / g, k_lo = std::max(-k, alpha - 14.0 / g), k_hi = std::min(k, alpha + 14.0 / g);
    const double dx = g / 40.0;
    const long nx = 240;
    std::vector<Complex> field(2 * static_cast<std::size_t>(nx) + 1);
    for (long j = -nx; j <= nx; ++j) {
        const double x = static_cast<double>(j) * dx;
        field[static_cast<std::size_t>(j + nx)] = thorsos_beam(k, theta_i, g, x, 0.0) * std::exp(Complex(0.0, -alpha * x));
    }
    double power = 0.0;
    const auto nk = static_cast<long>(std::ceil((k_hi - k_lo) / dk));
    for (long q = 0; q <= nk; ++q) {
        const double kx = k_lo + (k_hi - k_lo) * static_cast<double>(q) / static_cast<double>(nk);
        Complex a = 0.0;
        for (long j = -nx; j <= nx; ++j)
            a += field[static_cast<std::size_t>(j + nx)] * std::exp(Complex(0.0, (alpha - kx) * static_cast<double>(j) * dx));
        const double weight = (q == 0 || q == nk) ? 0.5 : 1.0;
        power += weight * std::sqrt(std::max(0.0, 1.0 - kx * kx / (k * k))) * std::norm(a * dx);
    }
    return power * (k_hi - k_lo) / static_cast<double>(nk) / kTwoPi;
}

std::complex<double> thorsos_beam(double k, double theta_i, double g, double x, double z) {
    const double c = std::cos(theta_i), s = std::sin(theta_i), t = std::tan(theta_i);
    const double u = x + z * t;
    const double w = (2.0 * u * u / (g * g) - 1.0) / (k * k * g * g * c * c);
    return std::exp(Complex(-u * u / (g * g), k * (x * s - z * c) * (1.0 + w)));
}

namespace {

struct Densities {
    Eigen::VectorXcd psi, normal;  // psi and L = dpsi/dn sqrt(1 + h'^2) on the outside
};

// A metal's interior: the banded LU factors of S2 and 1/2 + DL2, so that L = (rho S2)^-1 (1/2 + DL2) psi.
struct Interior {
    BandedMatrix single_lu, half_plus_dbl;
    Complex rho;
    Eigen::VectorXcd normal(const Eigen::VectorXcd& psi) const {
        return banded_solve(single_lu, half_plus_dbl.multiply(psi)) / rho;
    }
};

Interior interior(const Surface& surface, double k, const material::Conductor& conductor, const Exact1dOptions& o) {
    const Complex index = conductor.ior(o.lambda_nm);
    BandedPair inside = interior_matrices(surface, index * k, o.interior_reach);
    for (std::size_t i = 0; i < surface.n; ++i) inside.dbl.at(i, i) += 0.5;
    banded_lu(inside.single);
    return {std::move(inside.single), std::move(inside.dbl),
            o.polarisation == Polarisation::s ? Complex(1.0) : index * index};
}

Densities solve_dense_route(const Surface& surface, double k, const material::Conductor& conductor,
                            const Exact1dOptions& options, const Eigen::VectorXcd& incident) {
    const std::size_t n = surface.n;
    Densities out{Eigen::VectorXcd::Zero(n), Eigen::VectorXcd::Zero(n)};
    if (conductor.is_perfect() && options.polarisation == Polarisation::s) {
        out.normal = solve_dense(dirichlet_matrix(surface, k), incident, "the perfect conductor's s-polarised system");
    } else if (conductor.is_perfect()) {
        Eigen::MatrixXcd m = -double_layer_matrix(surface, k);
        m.diagonal().array() += 0.5;
        out.psi = solve_dense(std::move(m), incident, "the perfect conductor's p-polarised system");
    } else {
        const Interior inside = interior(surface, k, conductor, options);
        const std::size_t band = inside.single_lu.band;
        // S1 (rho S2)^-1 (1/2 + DL2), by rows against the banded factors and then a banded product.
        const Eigen::MatrixXcd w = banded_right_solve(inside.single_lu, dirichlet_matrix(surface, k));
        Eigen::MatrixXcd m = -double_layer_matrix(surface, k);
        m.diagonal().array() += 0.5;
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < n; ++j) {
                Complex sum = 0.0;
                const std::size_t lo = j > band ? j - band : 0, hi = std::min(j + band + 1, n);
                for (std::size_t l = lo; l < hi; ++l) sum += w(i, l) * inside.half_plus_dbl.at(l, j);
                m(i, j) += sum / inside.rho;
            }
        out.psi = solve_dense(std::move(m), incident, "the metal's boundary system");
        out.normal = inside.normal(out.psi);
    }
    return out;
}

// The iterative route (docs/REFERENCE.md, "Solve"): the operators' entries within `near` nodes of the diagonal are
// computed as the dense route computes them, the rest by FarInteraction's FFT series; GMRES preconditioned by the
// inverse of the flat surface's operator (a circulant, by FFT), or for a perfect conductor in p (whose flat operator
// is 1/2) by the banded LU of the near system truncated to kPreconditionerWavelengths.
constexpr double kFarTolerance = 1e-10;         // tail of the far series against its first term, per entry
constexpr int kFarTermsWanted = 10;             // widen the near band until the series needs no more terms
// A perfect conductor in p: 9 GMRES products on the 100 um profiles of docs/PERFORMANCE.md. (6 rather than 1.5 when
// the band preconditioned every case: on the supplemental rough surface perfect s fell from 30 to 18 products.)
constexpr double kPreconditionerWavelengths = 6;
// Automatic takes the dense route when the near band exceeds n / this: a 60 um profile of KC sigma 0.3 um (k sigma
// 3.4) at 550 nm solved 1.1-1.25x slower by the iterative route than by the dense LU (perfect s, Ag p).
constexpr std::size_t kDenseFromNearFraction = 8;
constexpr double kGmresTolerance = 1e-8;         // relative residual
constexpr int kGmresRestart = 200, kGmresMaxIterations = 600;

// The route a solve takes and the widths its buffers scale with, decided before any of them is allocated.
struct RoutePlan {
    bool iterative = false;
    std::size_t near = 0, interior_band = 0;  // interior_band: a metal's, else 0
    std::size_t precondition_band = 0;        // a perfect conductor in p: its banded LU's; else 0 (the flat operator)
    std::size_t flat_size = 0;                // the flat operator's circulant: a power of 2 >= 2 n
    int terms = 0;                            // of the far series
    std::string why;                          // why the iterative route declines
};

// The near band for the profile's height range and its far series' terms, or {0, 0} when none short of the whole
// matrix keeps the series short.
std::pair<std::size_t, int> near_band(const Surface& s, double k, double lambda_um) {
    const auto [lo, hi] = std::minmax_element(s.h.begin(), s.h.end());
    std::size_t band = std::max<std::size_t>(4, static_cast<std::size_t>(std::ceil(lambda_um / s.step)));
    while (band + 1 < s.n) {
        const int terms = FarInteraction::terms_needed(s.step, s.n, *hi - *lo, k, band, kFarTolerance);
        if (terms > 0 && terms <= kFarTermsWanted) return {band, terms};
        band = static_cast<std::size_t>(std::ceil(1.25 * static_cast<double>(band))) + 1;
    }
    return {0, 0};
}

RoutePlan plan_route(const Surface& surface, double k, double lambda_um, const material::Conductor& conductor,
                     const Exact1dOptions& options) {
    const std::size_t n = surface.n;
    RoutePlan plan;
    if (!(options.solver == Exact1dSolver::iterative ||
          (options.solver == Exact1dSolver::automatic && n >= kIterativeFromUnknowns)))
        return plan;
    std::tie(plan.near, plan.terms) = near_band(surface, k, lambda_um);
    if (plan.near == 0) {
        plan.why = fmt::format("no near band short of the whole profile keeps the far series within {} terms", kFarTermsWanted);
        return plan;
    }
    if (options.solver == Exact1dSolver::automatic && plan.near > n / kDenseFromNearFraction) {
        plan.why = fmt::format("a near band of {} of {} nodes: the dense LU is cheaper", plan.near, n);
        return plan;
    }
    plan.iterative = true;
    if (conductor.is_perfect() && options.polarisation == Polarisation::p)
        plan.precondition_band = std::min(
            plan.near, static_cast<std::size_t>(std::ceil(kPreconditionerWavelengths * lambda_um / surface.step)));
    else
        plan.flat_size = padded_fft_size(n);
    if (!conductor.is_perfect())
        plan.interior_band = interior_band(
            n, interior_cells(n, surface.step, conductor.ior(options.lambda_nm) * k, options.interior_reach));
    return plan;
}

// Bytes per node that every solve holds: the nodes (x, h, h', h''), the incident field, the two densities, and at
// the end the far field's three coefficient and three phase arrays.
constexpr double kCommonBytesPerNode = 4 * 8 + 16 + 2 * 16 + 3 * 16 + 3 * 8;

// The peak bytes of one solve by `plan`'s route (docs/REFERENCE.md, "Memory"): every buffer that scales with the
// node count, as solve_iterative_route and solve_dense_route allocate them.
double route_bytes(const RoutePlan& plan, std::size_t nodes, bool perfect) {
    const double n = static_cast<double>(nodes), c = sizeof(Complex);
    if (!plan.iterative)  // the matrix, the temporary it is built in, and a metal's S1 (rho S2)^-1 beside them
        return c * n * n * (perfect ? 2.2 : 3.2);
    const auto band = [&](std::size_t half_width) { return c * n * (2.0 * static_cast<double>(half_width) + 1.0); };
    const double pre = static_cast<double>(plan.precondition_band);
    // A perfect conductor in p: the preconditioner's LAPACK factors (3 b + 1 rows, int pivots) and the truncated copy
    // they are made from, beside 1/2 - DL1. Otherwise the flat operator's circulant (symbol and FFT buffers: 3 L)
    // and, while it is built, its kernel column and a metal's two interior circulants (7 L more) and the two interior
    // matrices of its short flat surface (m = 2 b + 17 nodes, half-width at most m), beside S1 and for a metal
    // 1/2 - DL1 and the interior's S2 factors and 1/2 + DL2.
    double bytes = 0.0;
    if (plan.precondition_band > 0) {
        bytes += c * n * (3.0 * pre + 1.0) + 4.0 * n + band(plan.precondition_band) + band(plan.near);
    } else if (perfect) {
        bytes += c * 4.0 * static_cast<double>(plan.flat_size) + band(plan.near);
    } else {
        const double m = 2.0 * static_cast<double>(plan.interior_band) + 17.0;
        bytes += c * 10.0 * static_cast<double>(plan.flat_size) + 2.0 * c * m * (2.0 * m + 1.0) + 2.0 * band(plan.near) +
                 2.0 * band(plan.interior_band);
    }
    bytes += FarInteraction::bytes(nodes, plan.terms);
    // GMRES: the Krylov basis at its full restart length, and ~10 vectors of products, residuals and temporaries.
    bytes += c * n * (kGmresRestart + 1.0) + c * (kGmresRestart + 1.0) * kGmresRestart + 10.0 * c * n;
    return bytes;
}

// One line naming the options that set the node count (as the caller spells them), exit status 2 at the CLI.
void require_solve_memory(double bytes, std::size_t nodes, const Profile& profile, const Exact1dOptions& o,
                          std::size_t concurrent) {
    const auto available = static_cast<double>(available_memory_bytes());
    const double total = bytes * static_cast<double>(concurrent);
    if (total <= available) return;
    fail("exact-1d: {} solver nodes (a {:.4g} um profile at {} nm, {} points per wavelength){} need {} of memory, more "
         "than the {} available: {}",
         nodes, profile_length(profile), o.lambda_nm, o.points_per_wavelength,
         concurrent > 1 ? fmt::format(" on {} threads", concurrent) : std::string(), format_bytes(total),
         format_bytes(available), exact_1d_remedy(o, profile_length(profile), concurrent));
}

// A flat surface of n nodes `step` apart.
Surface flat_surface(std::size_t n, double step) {
    Surface s;
    s.n = n;
    s.step = step;
    s.x.resize(n);
    for (std::size_t j = 0; j < n; ++j) s.x[j] = step * static_cast<double>(j);
    s.h.assign(n, 0.0);
    s.dh = s.d2h = s.h;
    return s;
}

// The circulant column c(d) = m(mid, mid - d), |d| <= m's band and < size / 2, of a matrix translation invariant
// around row mid.
Eigen::VectorXcd band_column(const BandedMatrix& m, std::size_t mid, std::size_t size) {
    Eigen::VectorXcd c = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(size));
    for (std::size_t d = 0; d <= std::min(m.band, size / 2 - 1); ++d) {
        c[static_cast<Eigen::Index>(d)] = m.at(mid, mid - d);
        if (d > 0) c[static_cast<Eigen::Index>(size - d)] = m.at(mid, mid + d);
    }
    return c;
}

// The boundary operator of a flat surface with the profile's node spacing, periodic over `size` nodes: the same
// Nystrom and product-integration entries as a profile's, translation invariant on a flat line, hence a circulant
// (its kernels reach size / 2 nodes either way). A perfect conductor in s: S1; a metal: 1/2 - DL1 + S1 Z with
// Z = (rho S2)^-1 (1/2 + DL2) and DL1 = 0 (its numerator dz - h' dx and h'' vanish on a flat line). Its inverse is
// the iterative route's preconditioner: it holds what couples distant nodes on a nearly flat surface (a silver
// surface's plasmons in p, which cross a 100 um profile), which no band does.
std::unique_ptr<Circulant> flat_operator(double step, double k, std::size_t nodes, std::size_t size,
                                         const material::Conductor& conductor, const Exact1dOptions& options) {
    Eigen::VectorXcd column = band_column(dirichlet_band(flat_surface(5, step), k, 4), 2, size);  // Navot's within 2
    for (std::size_t d = 3; d <= size / 2; ++d)
        column[static_cast<Eigen::Index>(d)] = column[static_cast<Eigen::Index>(size - d)] =
            dirichlet_entry(step, k, step * static_cast<double>(d));
    auto op = std::make_unique<Circulant>(column);
    if (conductor.is_perfect()) return op;
    const Complex index = conductor.ior(options.lambda_nm);
    // The interior's rows on a flat surface long enough that the middle one sees neither end (and reaches no further
    // than the profile's `nodes`).
    const std::size_t cells = interior_cells(nodes, step, index * k, options.interior_reach);
    const std::size_t m = 2 * (cells + 8) + 1, mid = m / 2;
    BandedPair inside = interior_matrices(flat_surface(m, step), index * k, options.interior_reach);
    inside.dbl.at(mid, mid) += 0.5;
    const Circulant single(band_column(inside.single, mid, size)), dbl(band_column(inside.dbl, mid, size));
    const Complex rho = options.polarisation == Polarisation::s ? Complex(1.0) : index * index;
    op->symbol() = (0.5 + op->symbol().array() * dbl.symbol().array() / (rho * single.symbol().array())).matrix();
    return op;
}

// The densities by the iterative route planned, or nothing (with the reason in `why`) when GMRES does not converge.
std::optional<Densities> solve_iterative_route(const Surface& surface, double k, const RoutePlan& plan,
                                               const material::Conductor& conductor, const Exact1dOptions& options,
                                               const Eigen::VectorXcd& incident, std::string& why) {
    const std::size_t n = surface.n, near = plan.near;
    const FarInteraction far(surface.step, surface.h, surface.dh, k, near, kFarTolerance);
    std::unique_ptr<Circulant> flat;
    if (plan.flat_size > 0) flat = flat_operator(surface.step, k, n, plan.flat_size, conductor, options);
    const LinearOperator flat_inverse = [&](const Eigen::VectorXcd& v) { return flat->solve_head(v); };
    Densities out{Eigen::VectorXcd::Zero(n), Eigen::VectorXcd::Zero(n)};
    GmresResult result;
    if (conductor.is_perfect() && options.polarisation == Polarisation::s) {
        const BandedMatrix single = dirichlet_band(surface, k, near);
        result = gmres([&](const Eigen::VectorXcd& v) -> Eigen::VectorXcd { return single.multiply(v) + far.single(v); },
                       flat_inverse, incident, kGmresTolerance, kGmresRestart, kGmresMaxIterations);
        out.normal = result.x;
    } else if (conductor.is_perfect()) {
        BandedMatrix half_minus_dbl = double_layer_band(surface, k, near);
        for (auto& a : half_minus_dbl.data) a = -a;
        for (std::size_t i = 0; i < n; ++i) half_minus_dbl.at(i, i) += 0.5;
        const BandedLu preconditioner(half_minus_dbl.truncated(plan.precondition_band), "the near-field boundary system");
        result = gmres([&](const Eigen::VectorXcd& psi) -> Eigen::VectorXcd {
                           return half_minus_dbl.multiply(psi) - far.double_layer(psi);
                       },
                       [&](const Eigen::VectorXcd& v) { return preconditioner.solve(v); }, incident, kGmresTolerance,
                       kGmresRestart, kGmresMaxIterations);
        out.psi = result.x;
    } else {
        BandedMatrix half_minus_dbl = double_layer_band(surface, k, near);
        for (auto& a : half_minus_dbl.data) a = -a;
        for (std::size_t i = 0; i < n; ++i) half_minus_dbl.at(i, i) += 0.5;
        const Interior inside = interior(surface, k, conductor, options);
        const BandedMatrix single = dirichlet_band(surface, k, near);
        result = gmres([&](const Eigen::VectorXcd& psi) -> Eigen::VectorXcd {
                           const Eigen::VectorXcd normal = inside.normal(psi);
                           return half_minus_dbl.multiply(psi) + single.multiply(normal) +
                                  far.single_minus_double_layer(normal, psi);
                       },
                       flat_inverse, incident, kGmresTolerance, kGmresRestart, kGmresMaxIterations);
        out.psi = result.x;
        out.normal = inside.normal(out.psi);
    }
    if (!result.converged) {
        why = fmt::format("GMRES reached a relative residual of {:.2g} after {} products (tolerance {:.0e})",
                          result.relative_residual, result.iterations, kGmresTolerance);
        return std::nullopt;
    }
    return out;
}

}  // namespace

std::string exact_1d_remedy(const Exact1dOptions& o, double length_um, std::size_t concurrent) {
    const OptionNames& names = o.option_names;
    std::vector<std::string> ways;
    if (!names.points_per_wavelength.empty())
        ways.push_back(fmt::format("fewer {} (now {})", names.points_per_wavelength, o.points_per_wavelength));
    if (!names.length.empty()) ways.push_back(fmt::format("a shorter {} (now {:.4g} um)", names.length, length_um));
    if (!names.wavelength.empty()) ways.push_back(fmt::format("a longer {} (now {} nm)", names.wavelength, o.lambda_nm));
    std::string out = "use ";
    for (std::size_t i = 0; i < ways.size(); ++i)
        out += (i == 0 ? "" : i + 1 == ways.size() ? " or " : ", ") + ways[i];
    if (concurrent > 1 && !names.threads.empty())
        out += fmt::format(", or fewer {} (now {} at once)", names.threads, concurrent);
    return out;
}

double exact_1d_solve_bytes(const Profile& profile, const material::Conductor& conductor, const Exact1dOptions& options) {
    check_options(profile, conductor, options);
    const double lambda_um = options.lambda_nm * 1e-3, k = kTwoPi / lambda_um;
    const Surface surface = solver_surface(profile, lambda_um, options.points_per_wavelength);
    const RoutePlan plan = plan_route(surface, k, lambda_um, conductor, options);
    return kCommonBytesPerNode * static_cast<double>(surface.n) + route_bytes(plan, surface.n, conductor.is_perfect());
}

void require_exact_1d_memory(const Profile& profile, const material::Conductor& conductor,
                             const Exact1dOptions& options, std::size_t concurrent_solves) {
    check_options(profile, conductor, options);
    require_solve_memory(exact_1d_solve_bytes(profile, conductor, options),
                         static_cast<std::size_t>(node_count(profile, options)), profile, options, concurrent_solves);
}

FarField solve_exact_1d(const Profile& profile, const material::Conductor& conductor, const Exact1dOptions& options) {
    check_options(profile, conductor, options);
    const double lambda_um = options.lambda_nm * 1e-3, k = kTwoPi / lambda_um;
    const double theta_i = options.theta_i_rad, g = options.beam_width_um;
    // The nodes' own arrays checked before they exist; the route's once it is planned (docs/REFERENCE.md, "Memory").
    require_solve_memory(kCommonBytesPerNode * node_count(profile, options), static_cast<std::size_t>(node_count(profile, options)),
                         profile, options, 1);
    const Surface surface = solver_surface(profile, lambda_um, options.points_per_wavelength);
    const std::size_t n = surface.n;
    Eigen::VectorXcd incident(n);
    for (std::size_t j = 0; j < n; ++j) incident[j] = thorsos_beam(k, theta_i, g, surface.x[j], surface.h[j]);
    // Unknowns on the surface: psi and L = dpsi/dn sqrt(1 + h'^2) on the outside. Outside,
    //   psi/2 = psi_inc + int [psi dG1/dn' - G1 L] dx'    (DL1, S1);
    // a perfect conductor has psi = 0 (s) or L = 0 (p). A metal adds the inside, with its index N and
    // L_inside = rho L (rho = 1 in s, N^2 in p: continuity of H_y / eps's normal derivative),
    //   psi/2 = -int [psi dG2/dn' - G2 rho L] dx',  so  L = (rho S2)^-1 (1/2 + DL2) psi.
    RoutePlan plan = plan_route(surface, k, lambda_um, conductor, options);
    if (!plan.iterative && options.solver == Exact1dSolver::iterative)
        fail("exact-1d: the iterative solve of {} unknowns failed: {}", n, plan.why);
    std::optional<Densities> solved;
    if (plan.iterative) {
        require_solve_memory(kCommonBytesPerNode * static_cast<double>(n) + route_bytes(plan, n, conductor.is_perfect()),
                             n, profile, options, 1);
        solved = solve_iterative_route(surface, k, plan, conductor, options, incident, plan.why);
        if (!solved && options.solver == Exact1dSolver::iterative)
            fail("exact-1d: the iterative solve of {} unknowns failed: {}", n, plan.why);
    }
    if (!solved) {
        plan.iterative = false;
        require_solve_memory(kCommonBytesPerNode * static_cast<double>(n) + route_bytes(plan, n, conductor.is_perfect()),
                             n, profile, options, 1);
        solved = solve_dense_route(surface, k, conductor, options, incident);
    }
    const Eigen::VectorXcd& psi = solved->psi;
    const Eigen::VectorXcd& normal = solved->normal;

    // Far field of int [psi dG1/dn' - G1 L] dx': |psi_sc|^2 r = |F|^2 / (8 pi k) with
    // F = int [L + i k psi (cos - h' sin)] e^{-i k o.r'} dx'.
    std::vector<Complex> plain(n), cosine(n), sine(n);
    for (std::size_t j = 0; j < n; ++j) {
        plain[j] = normal[j];
        cosine[j] = kI * k * psi[j];
        sine[j] = cosine[j] * surface.dh[j];
    }
    FarField out;
    out.amplitude = far_field_sum(k, surface.x[0], surface.step, surface.h, plain, cosine, sine);
    const double scale = surface.step / std::sqrt(8.0 * kPi * k * incident_power(k, theta_i, g));
    out.theta_o_rad.resize(out.amplitude.size());
    for (std::size_t q = 0; q < out.amplitude.size(); ++q) {
        out.theta_o_rad[q] = (-90.0 + 180.0 * static_cast<double>(q) / kFarFieldSteps) * kDegree;
        out.amplitude[q] *= scale;
    }
    for (const Complex& a : out.amplitude)
        if (!std::isfinite(a.real()) || !std::isfinite(a.imag()))
            fail("exact-1d: the solve gave a non-finite far field ({} unknowns): the profile is too rough for its sampling", n);
    return out;
}

}  // namespace surfscatter::reference
