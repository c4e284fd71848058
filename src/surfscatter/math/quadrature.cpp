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

}  // namespace

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
