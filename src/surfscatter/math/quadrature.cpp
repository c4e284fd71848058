#include "surfscatter/math/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <queue>

namespace surfscatter::math {
namespace {

constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Piece {
    double a, b, value, error;
    bool operator<(const Piece& o) const { return error < o.error; }
};

Piece kronrod(const std::function<double(double)>& f, double a, double b) {
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    const double fc = f(c);
    double k = fc * kWgk[7], g = fc * kWg[3];
    for (int j = 0; j < 7; ++j) {
        const double x = h * kXgk[j];
        const double s = f(c - x) + f(c + x);
        k += kWgk[j] * s;
        if (j % 2 == 1) g += kWg[j / 2] * s;
    }
    return {a, b, k * h, std::abs((k - g) * h)};
}

// Genz & Malik (1980), as in Johnson's cubature and HCubature.jl, for n = 2: generators and weights with the 2^n of the
// rectangle's volume folded in (the result is times the product of the half-widths).
constexpr double kL2 = 0.35856858280031809, kL4 = 0.94868329805051379, kL5 = 0.68824720161168529;  // sqrt(9/70),
                                                                                                     // sqrt(9/10), sqrt(9/19)
constexpr double kW7[5] = {4.0 * (12824.0 - 9120.0 * 2 + 400.0 * 4) / 19683.0, 4.0 * 980.0 / 6561.0,
                           4.0 * (1820.0 - 400.0 * 2) / 19683.0, 4.0 * 200.0 / 19683.0, 6859.0 / 19683.0};
constexpr double kW5[4] = {4.0 * (729.0 - 950.0 * 2 + 50.0 * 4) / 729.0, 4.0 * 245.0 / 486.0,
                           4.0 * (265.0 - 100.0 * 2) / 1458.0, 4.0 * 25.0 / 729.0};

struct Region {
    Box2 box;
    double value, error;
    int split_axis;
    bool operator<(const Region& o) const { return error < o.error; }
};

Region genz_malik(const std::function<double(double, double, int)>& f, const Box2& b) {
    const double cx = 0.5 * (b.x0 + b.x1), cy = 0.5 * (b.y0 + b.y1), hx = 0.5 * (b.x1 - b.x0), hy = 0.5 * (b.y1 - b.y0);
    auto at = [&](double dx, double dy) { return f(cx + dx * hx, cy + dy * hy, b.tag); };
    const double f0 = at(0, 0);
    const double x2 = at(kL2, 0) + at(-kL2, 0), y2 = at(0, kL2) + at(0, -kL2);
    const double x4 = at(kL4, 0) + at(-kL4, 0), y4 = at(0, kL4) + at(0, -kL4);
    const double corners4 = at(kL4, kL4) + at(kL4, -kL4) + at(-kL4, kL4) + at(-kL4, -kL4);
    const double corners5 = at(kL5, kL5) + at(kL5, -kL5) + at(-kL5, kL5) + at(-kL5, -kL5);
    const double volume = hx * hy;
    const double i7 = volume * (kW7[0] * f0 + kW7[1] * (x2 + y2) + kW7[2] * (x4 + y4) + kW7[3] * corners4 + kW7[4] * corners5);
    const double i5 = volume * (kW5[0] * f0 + kW5[1] * (x2 + y2) + kW5[2] * (x4 + y4) + kW5[3] * corners4);
    // Fourth differences along each axis ((lambda_2 / lambda_4)^2 = 1/7): the axis where the integrand is least
    // polynomial is cut.
    const double dx = std::abs(x2 - 2 * f0 - (x4 - 2 * f0) / 7.0), dy = std::abs(y2 - 2 * f0 - (y4 - 2 * f0) / 7.0);
    const int axis = dx > dy ? 0 : dy > dx ? 1 : (hx >= hy ? 0 : 1);
    return {b, i7, std::abs(i7 - i5), axis};
}

}  // namespace

Cubature integrate_adaptive_2d(const std::function<double(double, double, int)>& f, const std::vector<Box2>& boxes,
                               double rel_tol, double abs_tol, long max_evaluations) {
    constexpr long kRuleNodes = 17;
    std::priority_queue<Region> regions;
    Cubature c;
    for (const Box2& b : boxes) {
        const Region r = genz_malik(f, b);
        c.value += r.value;
        c.error += r.error;
        regions.push(r);
    }
    c.evaluations = kRuleNodes * long(boxes.size());
    while (!regions.empty() && c.error > std::max(abs_tol, rel_tol * std::abs(c.value)) &&
           c.evaluations + 2 * kRuleNodes <= max_evaluations) {
        const Region worst = regions.top();
        regions.pop();
        Box2 lo = worst.box, hi = worst.box;
        if (worst.split_axis == 0)
            lo.x1 = hi.x0 = 0.5 * (worst.box.x0 + worst.box.x1);
        else
            lo.y1 = hi.y0 = 0.5 * (worst.box.y0 + worst.box.y1);
        const Region a = genz_malik(f, lo), b = genz_malik(f, hi);
        c.value += a.value + b.value - worst.value;
        c.error += a.error + b.error - worst.error;
        c.evaluations += 2 * kRuleNodes;
        regions.push(a);
        regions.push(b);
    }
    // The running sums drift by rounding over many updates; the final ones are summed afresh.
    c.value = c.error = 0;
    while (!regions.empty()) {
        c.value += regions.top().value;
        c.error += regions.top().error;
        regions.pop();
    }
    return c;
}

double integrate_adaptive(const std::function<double(double)>& f, double a, double b, double rel_tol,
                          double abs_tol, int max_intervals) {
    if (a == b) return 0.0;
    std::priority_queue<Piece> pieces;
    Piece first = kronrod(f, a, b);
    double total = first.value, error = first.error;
    pieces.push(first);
    for (int n = 1; n < max_intervals; ++n) {
        if (error <= std::max(abs_tol, rel_tol * std::abs(total))) break;
        const Piece worst = pieces.top();
        pieces.pop();
        const double mid = 0.5 * (worst.a + worst.b);
        const Piece left = kronrod(f, worst.a, mid), right = kronrod(f, mid, worst.b);
        total += left.value + right.value - worst.value;
        error += left.error + right.error - worst.error;
        pieces.push(left);
        pieces.push(right);
    }
    return total;
}

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(n, 0.0);
    weights.assign(n, 0.0);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double x = std::cos(3.14159265358979323846 * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        weights[i] = weights[n - 1 - i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
}

}  // namespace surfscatter::math
