#include "surfscatter/photo/marker_corners.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace surfscatter::photo {

namespace {

constexpr double kProfileStep = 0.25;     // pixels between bilinear samples along a profile
constexpr std::size_t kMinimumPoints = 8;  // edge points a side needs for its line

// Bilinear sample of a CV_32FC1 image at pixel-centre coordinates; nothing outside the image.
std::optional<double> sample(const cv::Mat& image, cv::Point2d p) {
    const int x0 = static_cast<int>(std::floor(p.x)), y0 = static_cast<int>(std::floor(p.y));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= image.cols || y0 + 1 >= image.rows) return std::nullopt;
    const double fx = p.x - x0, fy = p.y - y0;
    const float* r0 = image.ptr<float>(y0);
    const float* r1 = image.ptr<float>(y0 + 1);
    return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

// Mean of three samples spread along the edge direction: the plateau levels are read less noisily.
std::optional<double> plateau(const cv::Mat& image, cv::Point2d p, cv::Point2d along) {
    double sum = 0;
    for (int k = -1; k <= 1; ++k) {
        const auto v = sample(image, p + k * along);
        if (!v) return std::nullopt;
        sum += *v;
    }
    return sum / 3;
}

// Area estimate of a dark-to-bright edge: the signed distance along `outward` from `p` at which a sharp step between
// `dark` and `bright` would have the same integral over [-half_width, half_width]. Exact for any symmetric blur
// inside the window; the window is re-centred once (from `start`) so that the blur's tails are cut symmetrically.
std::optional<double> edge_offset(const cv::Mat& image, cv::Point2d p, cv::Point2d outward, double dark, double bright,
                                  double half_width, double start = 0) {
    const double contrast = bright - dark;
    if (!(contrast > 0)) return std::nullopt;
    // Trapezoid rule on bilinear samples.
    const int steps = static_cast<int>(std::ceil(2 * half_width / kProfileStep));
    const double h = 2 * half_width / steps;
    double offset = start;
    for (int pass = 0; pass < 2; ++pass) {
        const cv::Point2d centre = p + offset * outward;
        double area = 0;
        for (int i = 0; i <= steps; ++i) {
            const auto v = sample(image, centre + (-half_width + i * h) * outward);
            if (!v) return std::nullopt;
            area += (i == 0 || i == steps ? 0.5 : 1.0) * h * (*v - dark) / contrast;
        }
        offset += half_width - area;
        if (!(std::abs(offset - start) < half_width)) return std::nullopt;
    }
    return offset;
}

// Least-squares straight line y = a + b t through (t_i, y_i): the plateau levels vary slowly along a side (lighting),
// and fitting them removes most of the per-profile noise.
struct Linear {
    double a = 0, b = 0;
    double operator()(double t) const { return a + b * t; }
};
Linear fit_linear(const std::vector<double>& t, const std::vector<double>& y) {
    const double n = static_cast<double>(t.size());
    double st = 0, sy = 0, stt = 0, sty = 0;
    for (std::size_t i = 0; i < t.size(); ++i) st += t[i], sy += y[i], stt += t[i] * t[i], sty += t[i] * y[i];
    const double det = n * stt - st * st;
    if (!(det > 0)) return {sy / n, 0};
    return {(stt * sy - st * sty) / det, (n * sty - st * sy) / det};
}

struct Line {
    cv::Point2d point, direction;  // direction unit length
};

// Standard deviation of the edge's blur (its line spread function), from the mean of a side's normalised profiles
// aligned at their edge estimates: the derivative's second moment over [-reach, reach].
double line_spread_sigma(const cv::Mat& image, const std::vector<cv::Point2d>& edges, cv::Point2d outward,
                         const std::vector<double>& darks, const std::vector<double>& brights, double reach) {
    const int steps = static_cast<int>(std::floor(2 * reach / kProfileStep));
    std::vector<double> mean(static_cast<std::size_t>(steps) + 1, 0.0);
    std::vector<int> count(mean.size(), 0);
    for (std::size_t i = 0; i < edges.size(); ++i)
        for (int j = 0; j <= steps; ++j)
            if (const auto v = sample(image, edges[i] + (-reach + j * kProfileStep) * outward)) {
                mean[static_cast<std::size_t>(j)] += (*v - darks[i]) / (brights[i] - darks[i]);
                ++count[static_cast<std::size_t>(j)];
            }
    double mass = 0, moment = 0;
    for (int j = 0; j < steps; ++j) {
        const auto a = static_cast<std::size_t>(j), b = a + 1;
        if (count[a] == 0 || count[b] == 0) continue;
        const double slope = std::max(0.0, mean[b] / count[b] - mean[a] / count[a]);  // noise can go negative
        const double s = -reach + (j + 0.5) * kProfileStep;
        mass += slope, moment += slope * s * s;
    }
    return mass > 0 ? std::sqrt(moment / mass) : reach;
}

// Edge points along the side from `a` to `b` (marker on the right), away from the corners; nothing if too few.
std::optional<std::vector<cv::Point2f>> side_edge_points(const cv::Mat& image, cv::Point2d a, cv::Point2d b,
                                                         double cell) {
    const double length = cv::norm(b - a);
    const cv::Point2d along = (b - a) * (1.0 / length);
    const cv::Point2d outward(along.y, -along.x);
    // The plateau levels are read in the middle of the black border cell and of the white quiet zone, and fitted
    // along the side (lighting varies slowly; the fit removes most of their noise).
    const double reach = 0.5 * cell;
    // Stay half a cell away from the corners: the neighbouring side's edge must not enter the profile.
    std::vector<double> positions, darks, brights;
    for (double t = reach; t <= length - reach; t += 1.0) {
        const cv::Point2d p = a + t * along;
        const auto dark = plateau(image, p - reach * outward, along);
        const auto bright = plateau(image, p + reach * outward, along);
        if (!dark || !bright) continue;
        positions.push_back(t), darks.push_back(*dark), brights.push_back(*bright);
    }
    if (positions.size() < kMinimumPoints) return std::nullopt;
    const Linear dark_fit = fit_linear(positions, darks), bright_fit = fit_linear(positions, brights);
    for (std::size_t i = 0; i < positions.size(); ++i) darks[i] = dark_fit(positions[i]), brights[i] = bright_fit(positions[i]);

    // First pass over a window of up to 4 px; then the window is set to 3 sigma of the measured blur, wide enough
    // to hold the edge and no wider (the noise of the area estimate grows with the window).
    const auto locate = [&](double half_width, const std::vector<double>& starts) {
        std::vector<double> offsets(positions.size(), std::nan(""));
        for (std::size_t i = 0; i < positions.size(); ++i)
            if (const auto e = edge_offset(image, a + positions[i] * along, outward, darks[i], brights[i], half_width,
                                           starts[i]))
                offsets[i] = *e;
        return offsets;
    };
    std::vector<double> offsets = locate(std::min(reach, 4.0), std::vector<double>(positions.size(), 0.0));
    std::vector<cv::Point2d> edges;
    std::vector<double> edge_darks, edge_brights;
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (std::isfinite(offsets[i])) {
            edges.push_back(a + positions[i] * along + offsets[i] * outward);
            edge_darks.push_back(darks[i]), edge_brights.push_back(brights[i]);
        }
    if (edges.size() < kMinimumPoints) return std::nullopt;
    const double sigma = line_spread_sigma(image, edges, outward, edge_darks, edge_brights, reach);
    for (double& o : offsets) o = std::isfinite(o) ? o : 0.0;
    offsets = locate(std::clamp(3 * sigma, 1.0, reach), offsets);

    std::vector<cv::Point2f> points;
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (std::isfinite(offsets[i])) points.emplace_back(a + positions[i] * along + offsets[i] * outward);
    if (points.size() < kMinimumPoints) return std::nullopt;
    return points;
}

// Total least squares fit, refitted once without points beyond 3 robust sigma (occluders, dirt, the noise tail).
std::optional<Line> fit_line(std::vector<cv::Point2d> points) {
    for (int pass = 0; pass < 2; ++pass) {
        if (points.size() < kMinimumPoints) return std::nullopt;
        cv::Point2d mean(0, 0);
        for (const auto& p : points) mean += p;
        mean *= 1.0 / static_cast<double>(points.size());
        double sxx = 0, sxy = 0, syy = 0;
        for (const auto& p : points) {
            const cv::Point2d d = p - mean;
            sxx += d.x * d.x, sxy += d.x * d.y, syy += d.y * d.y;
        }
        const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
        const Line line{mean, {std::cos(angle), std::sin(angle)}};
        if (pass == 1) return line;
        const cv::Point2d normal(-line.direction.y, line.direction.x);
        std::vector<double> residuals;
        for (const auto& p : points) residuals.push_back(std::abs((p - mean).dot(normal)));
        std::vector<double> sorted = residuals;
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
        const double limit = 3 * 1.4826 * sorted[sorted.size() / 2] + 1e-9;
        std::vector<cv::Point2d> kept;
        for (std::size_t i = 0; i < points.size(); ++i)
            if (residuals[i] <= limit) kept.push_back(points[i]);
        points = std::move(kept);
    }
    return std::nullopt;
}

std::optional<cv::Point2d> intersect(const Line& a, const Line& b) {
    const double det = a.direction.x * b.direction.y - a.direction.y * b.direction.x;
    if (std::abs(det) < 1e-6) return std::nullopt;
    const cv::Point2d d = b.point - a.point;
    const double t = (d.x * b.direction.y - d.y * b.direction.x) / det;
    return a.point + t * a.direction;
}

}  // namespace

std::optional<std::vector<cv::Point2f>> refine_marker_corners(const cv::Mat& linear_gray,
                                                              const std::vector<cv::Point2f>& corners,
                                                              const CameraModel& camera, int cells_per_side) {
    CV_Assert(linear_gray.type() == CV_32FC1 && corners.size() == 4 && cells_per_side >= 3);
    double perimeter = 0;
    for (int k = 0; k < 4; ++k) perimeter += cv::norm(corners[(k + 1) % 4] - corners[k]);
    const double cell = perimeter / 4 / cells_per_side;
    constexpr double kMinimumCell = 4;  // pixels: below this the border cell cannot hold a profile
    if (cell < kMinimumCell) return std::nullopt;
    std::array<Line, 4> sides;
    for (int k = 0; k < 4; ++k) {
        const auto edge_points = side_edge_points(linear_gray, corners[k], corners[(k + 1) % 4], cell);
        if (!edge_points) return std::nullopt;
        std::vector<cv::Point2f> ideal;
        cv::undistortPoints(*edge_points, ideal, camera.matrix, camera.distortion, cv::noArray(), camera.matrix);
        const auto line = fit_line(std::vector<cv::Point2d>(ideal.begin(), ideal.end()));
        if (!line) return std::nullopt;
        sides[static_cast<std::size_t>(k)] = *line;
    }

    // Corner k joins side k - 1 and side k; back to normalised coordinates, then through the lens.
    std::vector<cv::Point3d> normalised;
    const cv::Matx33d k_inv = camera.matrix.inv();
    for (int k = 0; k < 4; ++k) {
        const auto corner = intersect(sides[static_cast<std::size_t>((k + 3) % 4)], sides[static_cast<std::size_t>(k)]);
        if (!corner) return std::nullopt;
        const cv::Vec3d n = k_inv * cv::Vec3d(corner->x, corner->y, 1.0);
        normalised.emplace_back(n[0] / n[2], n[1] / n[2], 1.0);
    }
    std::vector<cv::Point2d> distorted;
    cv::projectPoints(normalised, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera.matrix, camera.distortion, distorted);
    std::vector<cv::Point2f> refined;
    for (int k = 0; k < 4; ++k) {
        if (!(cv::norm(distorted[static_cast<std::size_t>(k)] - cv::Point2d(corners[k])) <= cell / 3)) return std::nullopt;
        refined.emplace_back(distorted[static_cast<std::size_t>(k)]);
    }
    return refined;
}

MarkerCorners refine_marker(const cv::Mat& linear_gray, const std::vector<cv::Point2f>& detected,
                            const CameraModel& camera, const cv::Mat& cells) {
    CV_Assert(linear_gray.type() == CV_32FC1 && detected.size() == 4);
    const int n = cells.rows;
    double perimeter = 0;
    for (int k = 0; k < 4; ++k) perimeter += cv::norm(detected[(k + 1) % 4] - detected[k]);
    const double cell = perimeter / 4 / n;

    MarkerCorners out;
    out.candidates.push_back({"detector", detected, std::nullopt});
    // cornerSubPix looks at (2 w + 1)^2 pixels: w is chosen so that this window is no wider than a cell.
    const int half_window = static_cast<int>(std::floor((cell - 1) / 2));
    if (half_window >= 1) {
        std::vector<cv::Point2f> corners = detected;
        cv::cornerSubPix(linear_gray, corners, cv::Size(half_window, half_window), cv::Size(-1, -1),
                         cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-4));
        out.candidates.push_back({"cornerSubPix", corners, std::nullopt});
    }
    if (auto edges = refine_marker_corners(linear_gray, detected, camera, n))
        out.candidates.push_back({"edges", *edges, std::nullopt});

    const CornerCandidate* best = nullptr;
    for (auto& candidate : out.candidates) {
        if (const auto score = score_marker_corners(linear_gray, candidate.corners, camera, cells))
            candidate.pattern_residual = score->residual;
        if (candidate.pattern_residual && (!best || *candidate.pattern_residual < *best->pattern_residual))
            best = &candidate;
    }
    if (!best) {
        // Nothing could be scored: the edge fit if it worked (measured to 0.03 px on its own), else the detector.
        const bool edges = out.candidates.back().method == "edges";
        out.method = edges ? "edges" : "detector";
        out.corners = edges ? out.candidates.back().corners : detected;
        return out;
    }
    const std::vector<cv::Point2f> start = best->corners;
    out.method = best->method, out.corners = best->corners;
    double best_residual = *best->pattern_residual;
    if (auto fit = fit_marker_pattern(linear_gray, start, camera, cells)) {
        out.candidates.push_back({"pattern", fit->corners, fit->residual});
        if (fit->residual < best_residual) out.method = "pattern", out.corners = fit->corners;
        out.pattern = std::move(fit);
    }
    return out;
}

}  // namespace surfscatter::photo
