#include "surfscatter/photo/marker_pattern.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace surfscatter::photo {

namespace {

constexpr double kQuietZone = 0.5;   // cells of white around the marker that enter the fit
// Synthetic fits converge in about 10 iterations; on the tutorial photographs the corners did not change (to a
// thousandth of a pixel) between 20 iterations and 60.
constexpr int kMaxIterations = 20;
// Levenberg-Marquardt stops when a step changes the parameters or the sum of squares by less than this fraction.
constexpr double kTolerance = 1e-6;
constexpr double kStartSigma = 0.7;  // pixels
constexpr double kHomographyStep = 1e-4;  // pixels, for the derivative of the homography by a corner coordinate

// Parameters: the four corners in undistorted pixels (x0 y0 ... x3 y3), the dark and bright levels, the blur, and
// a linear illumination gradient across the box (a multiplicative 1 + gx X + gy Y, X and Y in [-1, 1]).
enum Parameter { kDark = 8, kBright, kSigma, kGradientX, kGradientY, kParameters };

// The homography from undistorted pixel coordinates to marker coordinates (cells, origin at the marker's top-left
// corner, u along its top edge, v down its left edge) for four corners, solved in double precision so that the
// small steps that differentiate it by a corner coordinate are not lost to rounding. NaN if the corners are
// degenerate (the fit then fails its finiteness check).
cv::Matx33d pixel_to_marker(const double* corners, int cells) {
    const double n = cells;
    const double marker[4][2] = {{0, 0}, {n, 0}, {n, n}, {0, n}};
    cv::Matx<double, 8, 8> a = cv::Matx<double, 8, 8>::zeros();
    cv::Vec<double, 8> b;
    for (int k = 0; k < 4; ++k) {
        const double x = corners[2 * k], y = corners[2 * k + 1], u = marker[k][0], v = marker[k][1];
        const double row_u[8] = {x, y, 1, 0, 0, 0, -x * u, -y * u};
        const double row_v[8] = {0, 0, 0, x, y, 1, -x * v, -y * v};
        for (int j = 0; j < 8; ++j) a(2 * k, j) = row_u[j], a(2 * k + 1, j) = row_v[j];
        b[2 * k] = u, b[2 * k + 1] = v;
    }
    cv::Vec<double, 8> h;
    if (!cv::solve(a, b, h, cv::DECOMP_LU)) return cv::Matx33d::all(std::nan(""));
    return {h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], 1.0};
}

// Taps each side of a Gaussian kernel: its tails beyond 4 sigma weigh 3e-4 of the peak.
int kernel_radius(double sigma) { return static_cast<int>(std::ceil(4 * sigma)); }

// Normalised 1-D Gaussian of `radius` taps each side and its derivative by sigma.
void gaussian_kernel(double sigma, int radius, cv::Mat& kernel, cv::Mat& d_sigma) {
    kernel.create(2 * radius + 1, 1, CV_64F);
    d_sigma.create(2 * radius + 1, 1, CV_64F);
    double sum = 0, d_sum = 0;
    for (int i = -radius; i <= radius; ++i) {
        const double g = std::exp(-0.5 * i * i / (sigma * sigma));
        kernel.at<double>(i + radius) = g;
        d_sigma.at<double>(i + radius) = g * i * i / (sigma * sigma * sigma);
        sum += g, d_sum += g * i * i / (sigma * sigma * sigma);
    }
    for (int i = 0; i <= 2 * radius; ++i) {
        const double g = kernel.at<double>(i), dg = d_sigma.at<double>(i);
        kernel.at<double>(i) = g / sum;
        d_sigma.at<double>(i) = (dg * sum - g * d_sum) / (sum * sum);
    }
}

class PatternModel {
public:
    PatternModel(const cv::Mat& image, const CameraModel& camera, const cv::Mat& cells,
                 const std::vector<cv::Point2f>& start)
        : n_(cells.rows), padded_(static_cast<std::size_t>((n_ + 2) * (n_ + 2)), 1) {
        for (int r = 0; r < n_; ++r)
            for (int c = 0; c < n_; ++c)
                padded_[static_cast<std::size_t>((r + 1) * (n_ + 2) + c + 1)] = cells.at<std::uint8_t>(r, c) ? 1 : 0;
        std::vector<cv::Point2f> ideal_start;
        cv::undistortPoints(start, ideal_start, camera.matrix, camera.distortion, cv::noArray(), camera.matrix);
        for (int k = 0; k < 4; ++k) start_[2 * k] = ideal_start[k].x, start_[2 * k + 1] = ideal_start[k].y;
        double perimeter = 0;
        for (int k = 0; k < 4; ++k) perimeter += cv::norm(start[(k + 1) % 4] - start[k]);
        cell_ = perimeter / 4 / n_;
        // Sub-samples per pixel side: enough that a sub-sample's footprint stays well under a cell.
        samples_ = cell_ < 8 ? 4 : 2;
        footprint_ = 0.5 / (samples_ * cell_);
        // Blur beyond this would have kept the marker from being detected; it bounds the box.
        sigma_cap_ = std::clamp(0.5 * cell_, 2.0, 4.0);
        pad_ = kernel_radius(sigma_cap_) + 1;

        // The box: the quiet zone's outline through the lens, with room for a corner to move a cell and for the blur.
        const cv::Matx33d to_marker = pixel_to_marker(start_.data(), n_);
        if (!cv::checkRange(cv::Mat(to_marker))) return;
        const cv::Matx33d to_pixel = to_marker.inv();
        std::vector<cv::Point3d> outline;
        const double lo = -kQuietZone - 1, hi = n_ + kQuietZone + 1;
        for (int i = 0; i <= 8; ++i) {
            const double t = lo + (hi - lo) * i / 8;
            for (const cv::Vec2d& m : {cv::Vec2d(t, lo), cv::Vec2d(t, hi), cv::Vec2d(lo, t), cv::Vec2d(hi, t)}) {
                const cv::Vec3d p = to_pixel * cv::Vec3d(m[0], m[1], 1);
                const cv::Vec3d q = camera.matrix.inv() * p;
                outline.emplace_back(q[0] / q[2], q[1] / q[2], 1);
            }
        }
        std::vector<cv::Point2d> outline_px;
        cv::projectPoints(outline, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera.matrix, camera.distortion,
                          outline_px);
        std::vector<cv::Point2f> outline_f(outline_px.begin(), outline_px.end());
        box_ = cv::boundingRect(outline_f);
        box_.x -= pad_, box_.y -= pad_, box_.width += 2 * pad_, box_.height += 2 * pad_;
        if (box_.x < 0 || box_.y < 0 || box_.x + box_.width > image.cols || box_.y + box_.height > image.rows ||
            box_.area() > 4'000'000)
            return;
        image(box_).convertTo(target_, CV_64F);

        std::vector<cv::Point2f> sub;
        sub.reserve(static_cast<std::size_t>(box_.area() * samples_ * samples_));
        for (int y = 0; y < box_.height; ++y)
            for (int x = 0; x < box_.width; ++x)
                for (int j = 0; j < samples_; ++j)
                    for (int i = 0; i < samples_; ++i)
                        sub.emplace_back(static_cast<float>(box_.x + x + (i + 0.5) / samples_ - 0.5),
                                         static_cast<float>(box_.y + y + (j + 0.5) / samples_ - 0.5));
        cv::undistortPoints(sub, ideal_, camera.matrix, camera.distortion, cv::noArray(), camera.matrix);

        // The fitted pixels: those whose centre lies on the marker or its quiet zone at the start.
        std::vector<cv::Point2f> centres;
        for (int y = 0; y < box_.height; ++y)
            for (int x = 0; x < box_.width; ++x) centres.emplace_back(float(box_.x + x), float(box_.y + y));
        std::vector<cv::Point2f> ideal_centres;
        cv::undistortPoints(centres, ideal_centres, camera.matrix, camera.distortion, cv::noArray(), camera.matrix);
        for (std::size_t i = 0; i < centres.size(); ++i) {
            const cv::Vec3d m = to_marker * cv::Vec3d(ideal_centres[i].x, ideal_centres[i].y, 1);
            const double u = m[0] / m[2], v = m[1] / m[2];
            if (u > -kQuietZone && v > -kQuietZone && u < n_ + kQuietZone && v < n_ + kQuietZone)
                pixels_.emplace_back(static_cast<int>(i) % box_.width, static_cast<int>(i) / box_.width);
        }
    }

    bool usable() const { return !target_.empty() && pixels_.size() > kParameters; }
    int residual_count() const { return static_cast<int>(pixels_.size()); }
    const std::array<double, 8>& start() const { return start_; }
    double cell() const { return cell_; }
    double sigma_cap() const { return sigma_cap_; }
    const cv::Mat& target() const { return target_; }
    const std::vector<cv::Point>& pixels() const { return pixels_; }

    // The sharp pattern's white fraction in every pixel of the box for the corners p[0..7] (undistorted pixels) and,
    // if `with_derivatives`, its derivatives by the eight corner coordinates.
    struct Coverage {
        cv::Mat value;
        std::vector<cv::Mat> derivatives;
    };
    Coverage render(const double* p, bool with_derivatives) const {
        const int derivatives = with_derivatives ? 8 : 0;
        Coverage out;
        out.value = cv::Mat::zeros(box_.size(), CV_64F);
        out.derivatives.resize(static_cast<std::size_t>(derivatives));
        for (auto& d : out.derivatives) d = cv::Mat::zeros(box_.size(), CV_64F);
        const cv::Matx33d h = pixel_to_marker(p, n_);
        std::array<cv::Matx33d, 8> h_step;
        for (int k = 0; k < derivatives; ++k) {
            std::array<double, 8> q;
            std::copy(p, p + 8, q.begin());
            q[static_cast<std::size_t>(k)] += kHomographyStep;
            h_step[static_cast<std::size_t>(k)] = pixel_to_marker(q.data(), n_);
        }
        const double per_sample = 1.0 / (samples_ * samples_);
        std::size_t s = 0;
        for (int y = 0; y < box_.height; ++y)
            for (int x = 0; x < box_.width; ++x) {
                double value = 0;
                std::array<double, 8> d_value{};
                for (int k = 0; k < samples_ * samples_; ++k, ++s) {
                    const double px = ideal_[s].x, py = ideal_[s].y;
                    const double w = h(2, 0) * px + h(2, 1) * py + h(2, 2);
                    const double u = (h(0, 0) * px + h(0, 1) * py + h(0, 2)) / w;
                    const double v = (h(1, 0) * px + h(1, 1) * py + h(1, 2)) / w;
                    double du = 0, dv = 0;
                    value += pattern(u, v, derivatives ? &du : nullptr, &dv);
                    if (du == 0 && dv == 0) continue;  // inside one cell: the corners do not move this sample's value
                    for (int j = 0; j < derivatives; ++j) {
                        const cv::Matx33d& g = h_step[static_cast<std::size_t>(j)];
                        const double wj = g(2, 0) * px + g(2, 1) * py + g(2, 2);
                        const double uj = (g(0, 0) * px + g(0, 1) * py + g(0, 2)) / wj;
                        const double vj = (g(1, 0) * px + g(1, 1) * py + g(1, 2)) / wj;
                        d_value[static_cast<std::size_t>(j)] += (du * (uj - u) + dv * (vj - v)) / kHomographyStep;
                    }
                }
                out.value.at<double>(y, x) = value * per_sample;
                for (int j = 0; j < derivatives; ++j)
                    out.derivatives[static_cast<std::size_t>(j)].at<double>(y, x) =
                        d_value[static_cast<std::size_t>(j)] * per_sample;
            }
        return out;
    }

    // Residuals (model - image) at the fitted pixels for parameters p and the pattern `coverage` of its corners and,
    // if `jacobian`, their derivatives by the parameters (by the corners only if `coverage` has its derivatives).
    void evaluate(const double* p, const Coverage& coverage, cv::Mat& residuals, cv::Mat* jacobian) const {
        const double sigma = std::clamp(std::abs(p[kSigma]), 0.05, sigma_cap_);
        cv::Mat kernel, d_kernel;
        gaussian_kernel(sigma, kernel_radius(sigma), kernel, d_kernel);
        cv::Mat blurred, d_blur_a, d_blur_b;
        cv::sepFilter2D(coverage.value, blurred, CV_64F, kernel, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
        if (jacobian) {
            cv::sepFilter2D(coverage.value, d_blur_a, CV_64F, d_kernel, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
            cv::sepFilter2D(coverage.value, d_blur_b, CV_64F, kernel, d_kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
        }
        const int derivatives = jacobian ? static_cast<int>(coverage.derivatives.size()) : 0;
        std::vector<cv::Mat> d_blurred(static_cast<std::size_t>(derivatives));
        for (int j = 0; j < derivatives; ++j)
            cv::sepFilter2D(coverage.derivatives[static_cast<std::size_t>(j)], d_blurred[static_cast<std::size_t>(j)],
                            CV_64F, kernel, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);

        const double dark = p[kDark], contrast = p[kBright] - p[kDark];
        const double sigma_sign = p[kSigma] < 0 ? -1.0 : 1.0;
        const bool sigma_clamped = std::abs(p[kSigma]) != sigma;
        residuals.create(residual_count(), 1, CV_64F);
        if (jacobian) jacobian->create(residual_count(), kParameters, CV_64F), jacobian->setTo(0);
        for (int i = 0; i < residual_count(); ++i) {
            const cv::Point& q = pixels_[static_cast<std::size_t>(i)];
            const double gx = 2.0 * q.x / (box_.width - 1) - 1, gy = 2.0 * q.y / (box_.height - 1) - 1;
            const double light = 1 + p[kGradientX] * gx + p[kGradientY] * gy;
            const double m = blurred.at<double>(q);
            const double model = dark + contrast * m;
            residuals.at<double>(i) = light * model - target_.at<double>(q);
            if (!jacobian) continue;
            double* row = jacobian->ptr<double>(i);
            for (int j = 0; j < derivatives; ++j)
                row[j] = light * contrast * d_blurred[static_cast<std::size_t>(j)].at<double>(q);
            row[kDark] = light * (1 - m);
            row[kBright] = light * m;
            if (!sigma_clamped)
                row[kSigma] = sigma_sign * light * contrast * (d_blur_a.at<double>(q) + d_blur_b.at<double>(q));
            row[kGradientX] = gx * model;
            row[kGradientY] = gy * model;
        }
    }

private:
    // The printed pattern averaged over a sub-sample's footprint (+-footprint_ cells about (u, v)): 1 = white.
    // Outside the marker it is the white quiet zone. With `du`, also its derivatives by u and v.
    double pattern(double u, double v, double* du, double* dv) const {
        const double h = footprint_;
        // Cell indices clamped to the white ring around the marker: everything beyond it is white as well.
        const auto index = [&](double x) { return std::clamp(static_cast<int>(std::floor(x)), -1, n_); };
        const int c0 = index(u - h), c1 = index(u + h), r0 = index(v - h), r1 = index(v + h);
        const auto cell = [&](int r, int c) { return double(padded_[static_cast<std::size_t>((r + 1) * (n_ + 2) + c + 1)]); };
        if (c0 == c1 && r0 == r1) return cell(r0, c0);  // the footprint lies in one cell: no edge, no derivative
        const auto overlap = [](double a0, double a1, int c) {
            return std::max(0.0, std::min(a1, c + 1.0) - std::max(a0, double(c)));
        };
        double sum = 0;
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c)
                sum += cell(r, c) * overlap(u - h, u + h, c) * overlap(v - h, v + h, r);
        const double area = 4 * h * h;
        if (du) {
            double gu = 0, gv = 0;
            for (int r = r0; r <= r1; ++r) gu += (cell(r, c1) - cell(r, c0)) * overlap(v - h, v + h, r);
            for (int c = c0; c <= c1; ++c) gv += (cell(r1, c) - cell(r0, c)) * overlap(u - h, u + h, c);
            *du = gu / area, *dv = gv / area;
        }
        return sum / area;
    }

    int n_;
    std::vector<std::uint8_t> padded_;  // the cells with a ring of white around them, row by row
    std::array<double, 8> start_{};
    double cell_ = 0, footprint_ = 0, sigma_cap_ = 0;
    int samples_ = 4, pad_ = 0;
    cv::Rect box_;
    cv::Mat target_;
    std::vector<cv::Point2f> ideal_;
    std::vector<cv::Point> pixels_;
};

// The solver's view of the model: all parameters, or (corners held fixed) the five after them, whose pattern
// coverage is then rendered once.
class PatternCallback : public cv::LMSolver::Callback {
public:
    PatternCallback(const PatternModel& model, bool corners_free, const std::array<double, 8>& corners)
        : model_(model), corners_free_(corners_free), corners_(corners) {
        if (!corners_free_) fixed_ = model_.render(corners_.data(), false);
    }
    bool compute(cv::InputArray param, cv::OutputArray err, cv::OutputArray jac) const override {
        const std::array<double, kParameters> p = full(param.getMat());
        cv::Mat residuals, jacobian;
        evaluate(p, residuals, jac.needed() ? &jacobian : nullptr);
        residuals.copyTo(err);
        if (jac.needed()) (corners_free_ ? jacobian : jacobian.colRange(8, kParameters)).copyTo(jac);
        return true;
    }
    void evaluate(const std::array<double, kParameters>& p, cv::Mat& residuals, cv::Mat* jacobian) const {
        if (corners_free_)
            model_.evaluate(p.data(), model_.render(p.data(), jacobian != nullptr), residuals, jacobian);
        else
            model_.evaluate(p.data(), fixed_, residuals, jacobian);
    }
    // The full parameter vector from the solver's.
    std::array<double, kParameters> full(const cv::Mat& x) const {
        std::array<double, kParameters> p{};
        std::copy(corners_.begin(), corners_.end(), p.begin());
        const int offset = corners_free_ ? 0 : 8;
        for (int i = 0; i < x.rows * x.cols; ++i) p[static_cast<std::size_t>(offset + i)] = x.at<double>(i);
        return p;
    }

private:
    const PatternModel& model_;
    bool corners_free_;
    std::array<double, 8> corners_;
    PatternModel::Coverage fixed_;
};

std::optional<PatternFit> run_fit(const cv::Mat& linear_gray, const std::vector<cv::Point2f>& corners,
                                  const CameraModel& camera, const cv::Mat& cells, bool corners_free) {
    CV_Assert(linear_gray.type() == CV_32FC1 && corners.size() == 4 && cells.type() == CV_8UC1 &&
              cells.rows == cells.cols && cells.rows >= 3);
    const PatternModel model(linear_gray, camera, cells, corners);
    if (!model.usable()) return std::nullopt;

    // Start: the levels from a straight-line fit of the image against the sharp pattern blurred by kStartSigma.
    std::array<double, kParameters> start{};
    std::copy(model.start().begin(), model.start().end(), start.begin());
    start[kSigma] = kStartSigma, start[kDark] = 0, start[kBright] = 1;
    {
        cv::Mat unit;
        model.evaluate(start.data(), model.render(start.data(), false), unit, nullptr);  // coverage - image
        double sxx = 0, sx = 0, sy = 0, sxy = 0;
        const double count = model.residual_count();
        for (int i = 0; i < model.residual_count(); ++i) {
            const double y = model.target().at<double>(model.pixels()[static_cast<std::size_t>(i)]);
            const double x = unit.at<double>(i) + y;
            sxx += x * x, sx += x, sy += y, sxy += x * y;
        }
        const double slope = (count * sxy - sx * sy) / (count * sxx - sx * sx);
        if (!(slope > 0)) return std::nullopt;
        start[kDark] = (sy - slope * sx) / count;
        start[kBright] = start[kDark] + slope;
    }

    const auto callback = cv::makePtr<PatternCallback>(model, corners_free, model.start());
    const int offset = corners_free ? 0 : 8;
    cv::Mat x(kParameters - offset, 1, CV_64F);
    for (int i = 0; i < x.rows; ++i) x.at<double>(i) = start[static_cast<std::size_t>(offset + i)];
    cv::LMSolver::create(callback, kMaxIterations, kTolerance)->run(x);
    const std::array<double, kParameters> p = callback->full(x);

    cv::Mat residuals, jacobian;
    callback->evaluate(p, residuals, &jacobian);
    const double contrast = p[kBright] - p[kDark];
    const double sigma = std::abs(p[kSigma]);
    if (!(contrast > 0) || !(sigma < model.sigma_cap())) return std::nullopt;
    for (int k = 0; k < 8; ++k)
        if (!std::isfinite(p[static_cast<std::size_t>(k)])) return std::nullopt;
    for (int k = 0; k < 4; ++k)
        if (!(std::hypot(p[2 * k] - model.start()[2 * k], p[2 * k + 1] - model.start()[2 * k + 1]) < model.cell()))
            return std::nullopt;

    PatternFit fit;
    const double ssr = residuals.dot(residuals);
    fit.residual = std::sqrt(ssr / residuals.rows) / contrast;
    fit.blur_sigma_px = sigma, fit.dark = p[kDark], fit.bright = p[kBright];
    if (corners_free) {
        const cv::Mat normal = jacobian.t() * jacobian;
        cv::Mat covariance;
        if (cv::invert(normal, covariance, cv::DECOMP_SVD) > 0) {
            const double variance = ssr / std::max(1, residuals.rows - kParameters);
            double sum = 0;
            for (int k = 0; k < 8; ++k) sum += covariance.at<double>(k, k);
            fit.corner_std_px = std::sqrt(variance * sum / 8);
        }
    }
    // Back through the lens.
    std::vector<cv::Point3d> normalised;
    const cv::Matx33d k_inv = camera.matrix.inv();
    for (int k = 0; k < 4; ++k) {
        const cv::Vec3d n = k_inv * cv::Vec3d(p[2 * k], p[2 * k + 1], 1.0);
        normalised.emplace_back(n[0] / n[2], n[1] / n[2], 1.0);
    }
    std::vector<cv::Point2d> distorted;
    cv::projectPoints(normalised, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera.matrix, camera.distortion, distorted);
    if (corners_free)
        for (const auto& d : distorted) fit.corners.emplace_back(d);
    else
        fit.corners = corners;
    return fit;
}

}  // namespace

std::optional<PatternFit> fit_marker_pattern(const cv::Mat& linear_gray, const std::vector<cv::Point2f>& corners,
                                             const CameraModel& camera, const cv::Mat& cells) {
    return run_fit(linear_gray, corners, camera, cells, true);
}

std::optional<PatternFit> score_marker_corners(const cv::Mat& linear_gray, const std::vector<cv::Point2f>& corners,
                                               const CameraModel& camera, const cv::Mat& cells) {
    return run_fit(linear_gray, corners, camera, cells, false);
}

}  // namespace surfscatter::photo
