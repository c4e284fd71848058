#include "surfscatter/heightmap/form.hpp"

#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "surfscatter/core/error.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr int kMaxDegree = 4;

// P_0 .. P_degree (Legendre) at u in [-1, 1].
std::array<double, kMaxDegree + 1> legendre(double u, int degree) {
    std::array<double, kMaxDegree + 1> p{};
    p[0] = 1.0;
    if (degree >= 1) p[1] = u;
    for (int n = 1; n < degree; ++n)
        p[n + 1] = ((2.0 * n + 1.0) * u * p[n] - n * p[n - 1]) / (n + 1.0);
    return p;
}

// Legendre values at every column (or row) of a grid side of n samples, u = (2 i - (n - 1)) / (n - 1).
std::vector<std::array<double, kMaxDegree + 1>> legendre_table(std::size_t n, int degree) {
    std::vector<std::array<double, kMaxDegree + 1>> table(n);
    const double half = 0.5 * static_cast<double>(n - 1);
    for (std::size_t i = 0; i < n; ++i) table[i] = legendre((static_cast<double>(i) - half) / half, degree);
    return table;
}

struct Term {
    int i, j;  // P_i(u) P_j(v)
};

std::vector<Term> terms_of(int degree) {
    std::vector<Term> terms;
    for (int total = 0; total <= degree; ++total)
        for (int j = 0; j <= total; ++j) terms.push_back({total - j, j});
    return terms;
}

// "choose a lower form: poly2, plane or none" (the advice when the valid points cannot determine `form`); the CLI's
// --form and Python's form= take the same names.
std::string lower_forms_advice(Form form) {
    std::string lower;
    for (int d = form_degree(form) - 1; d >= 0; --d) {
        lower += to_string(static_cast<Form>(d));
        lower += d == 1 ? " or " : d > 1 ? ", " : "";
    }
    return lower.empty() ? std::string("the map has too few valid points for any form")
                         : "choose a lower form (--form, Python form=): " + lower;
}

}  // namespace

Form parse_form(const std::string& name, const std::string& where) {
    for (Form form : {Form::none, Form::plane, Form::poly2, Form::poly3, Form::poly4})
        if (name == to_string(form)) return form;
    fail("{} must be none, plane, poly2, poly3 or poly4, got '{}'", where, printable(name));
}

std::string to_string(Form form) {
    switch (form) {
        case Form::none: return "none";
        case Form::plane: return "plane";
        case Form::poly2: return "poly2";
        case Form::poly3: return "poly3";
        case Form::poly4: return "poly4";
    }
    return "plane";
}

int form_degree(Form form) {
    switch (form) {
        case Form::none: return 0;
        case Form::plane: return 1;
        case Form::poly2: return 2;
        case Form::poly3: return 3;
        case Form::poly4: return 4;
    }
    return 1;
}

HeightMap remove_form(const HeightMap& map, Form form) {
    const int degree = form_degree(form);
    const std::vector<Term> terms = terms_of(degree);
    const auto n_terms = static_cast<Eigen::Index>(terms.size());
    const std::size_t nx = map.nx(), ny = map.ny();
    const auto px = legendre_table(nx, degree), py = legendre_table(ny, degree);
    const std::string origin = map.origin();
    if (map.valid_count() < 4 * terms.size())
        fail("{}: {} valid points cannot determine a {} form ({} coefficients need {}); {}", origin, map.valid_count(),
             to_string(form), terms.size(), 4 * terms.size(), lower_forms_advice(form));

    // Normal equations sum_p b_a(p) b_b(p) c_b = sum_p b_a(p) h(p), with b_(i,j) = P_i(u) P_j(v): per row, the x
    // sums S_ii' = sum P_i P_i' and R_i = sum P_i h over the row's valid points, then weighted by P_j P_j'.
    Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n_terms, n_terms);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n_terms);
    for (std::size_t iy = 0; iy < ny; ++iy) {
        double s[kMaxDegree + 1][kMaxDegree + 1] = {};
        double r[kMaxDegree + 1] = {};
        for (std::size_t ix = 0; ix < nx; ++ix) {
            if (!map.valid(ix, iy)) continue;
            const double h = map(ix, iy);
            for (int i = 0; i <= degree; ++i) {
                r[i] += px[ix][i] * h;
                for (int k = i; k <= degree; ++k) s[i][k] += px[ix][i] * px[ix][k];
            }
        }
        for (Eigen::Index a = 0; a < n_terms; ++a) {
            const Term ta = terms[static_cast<std::size_t>(a)];
            rhs[a] += r[ta.i] * py[iy][ta.j];
            for (Eigen::Index b = a; b < n_terms; ++b) {
                const Term tb = terms[static_cast<std::size_t>(b)];
                const double sx = ta.i <= tb.i ? s[ta.i][tb.i] : s[tb.i][ta.i];
                normal(a, b) += sx * py[iy][ta.j] * py[iy][tb.j];
            }
        }
    }
    normal.triangularView<Eigen::StrictlyLower>() = normal.transpose().triangularView<Eigen::StrictlyLower>();

    // The Legendre basis is near-orthogonal on a full grid (condition ~1-10); a tiny eigenvalue means the valid
    // points leave some combination of the terms undetermined.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normal, Eigen::EigenvaluesOnly);
    const double smallest = eigen.eigenvalues().minCoeff(), largest = eigen.eigenvalues().maxCoeff();
    if (!(smallest > 1e-10 * largest))
        fail("{}: the valid points do not determine a {} form (they lie on too few rows or columns); {}", origin,
             to_string(form), lower_forms_advice(form));
    const Eigen::VectorXd c = normal.ldlt().solve(rhs);

    std::vector<double> residual(map.size(), 0.0);
    for (std::size_t iy = 0; iy < ny; ++iy) {
        double row[kMaxDegree + 1] = {};  // sum_j c_(i,j) P_j(v) for this row
        for (Eigen::Index a = 0; a < n_terms; ++a) {
            const Term t = terms[static_cast<std::size_t>(a)];
            row[t.i] += c[a] * py[iy][t.j];
        }
        for (std::size_t ix = 0; ix < nx; ++ix) {
            if (!map.valid(ix, iy)) continue;
            double f = 0.0;
            for (int i = 0; i <= degree; ++i) f += row[i] * px[ix][i];
            residual[iy * nx + ix] = map(ix, iy) - f;
        }
    }
    return map.with_heights(std::move(residual));
}

HeightMoments height_moments(const HeightMap& map) {
    double sum = 0.0;
    for (std::size_t i = 0; i < map.size(); ++i)
        if (map.valid(i)) sum += map.heights()[i];
    const double count = static_cast<double>(map.valid_count());
    const double mean = sum / count;
    double m2 = 0.0, m3 = 0.0, m4 = 0.0;
    for (std::size_t i = 0; i < map.size(); ++i) {
        if (!map.valid(i)) continue;
        const double d = map.heights()[i] - mean, d2 = d * d;
        m2 += d2;
        m3 += d2 * d;
        m4 += d2 * d2;
    }
    HeightMoments moments;
    moments.rms = std::sqrt(m2 / count);
    if (m2 > 0.0) {
        moments.skewness = (m3 / count) / (moments.rms * moments.rms * moments.rms);
        moments.kurtosis = (m4 / count) / ((m2 / count) * (m2 / count));
    }
    return moments;
}

double rms_height(const HeightMap& map, Form form) { return height_moments(remove_form(map, form)).rms; }

}  // namespace surfscatter::heightmap
