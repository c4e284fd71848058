#include "surfscatter/photo/color_checker.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/optim.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/mcc.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {

ChartReference read_chart_reference(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) fail("chart reference '{}' could not be opened (Debian package argyll-ref)", path.string());
    ChartReference ref;
    std::array<bool, kChartPatches> seen{};
    std::vector<std::string> fields;
    enum class Section { Header, Format, Data } section = Section::Header;
    std::string line;
    for (int line_number = 1; std::getline(in, line); ++line_number) {
        std::istringstream words(line);
        std::string first;
        if (!(words >> first)) continue;
        if (first == "BEGIN_DATA_FORMAT") { section = Section::Format; continue; }
        if (first == "END_DATA_FORMAT" || first == "END_DATA") { section = Section::Header; continue; }
        if (first == "BEGIN_DATA") { section = Section::Data; continue; }
        if (section == Section::Format) {
            fields.push_back(first);
            for (std::string f; words >> f;) fields.push_back(f);
        } else if (section == Section::Data) {
            std::vector<std::string> values{first};
            for (std::string v; words >> v;) values.push_back(v);
            if (values.size() != fields.size())
                fail("{}:{}: {} values for {} fields", path.string(), line_number, values.size(), fields.size());
            std::string id;
            Lab lab;
            int found = 0;
            for (std::size_t i = 0; i < fields.size(); ++i) {
                try {
                    if (fields[i] == "SAMPLE_ID") id = values[i], ++found;
                    else if (fields[i] == "LAB_L") lab.L = std::stod(values[i]), ++found;
                    else if (fields[i] == "LAB_A") lab.a = std::stod(values[i]), ++found;
                    else if (fields[i] == "LAB_B") lab.b = std::stod(values[i]), ++found;
                } catch (const std::exception&) {
                    fail("{}:{}: '{}' is not a number", path.string(), line_number, values[i]);
                }
            }
            if (found != 4) fail("{}:{}: needs SAMPLE_ID, LAB_L, LAB_A and LAB_B fields", path.string(), line_number);
            const int row = id.empty() ? -1 : id[0] - 'A';
            const int col = id.size() == 3 ? std::atoi(id.c_str() + 1) - 1 : -1;
            if (row < 0 || row >= kChartRows || col < 0 || col >= kChartColumns)
                fail("{}:{}: sample id '{}' is not one of A01..D06", path.string(), line_number, id);
            const auto index = static_cast<std::size_t>(row * kChartColumns + col);
            ref.lab_d50[index] = lab;
            seen[index] = true;
        }
    }
    for (std::size_t i = 0; i < seen.size(); ++i)
        if (!seen[i]) fail("chart reference '{}' has no value for patch {}", path.string(), i + 1);
    const Vec3d d65 = white_d65();
    for (std::size_t i = 0; i < seen.size(); ++i) {
        const Vec3d xyz_d65 = bradford_adapt(lab_to_xyz(ref.lab_d50[i], kWhiteD50), kWhiteD50, d65);
        ref.lab_d65[i] = xyz_to_lab(xyz_d65, d65);
        ref.linear_srgb[i] = xyz_to_linear_srgb(xyz_d65);
    }
    return ref;
}

namespace {
// Homography from chart coordinates (u in [0, 6] along the rows, v in [0, 4] down) to the image.
cv::Matx33d chart_homography(const std::array<cv::Point2f, 4>& corners) {
    const std::vector<cv::Point2f> chart{{0.0f, 0.0f}, {6.0f, 0.0f}, {6.0f, 4.0f}, {0.0f, 4.0f}};
    const std::vector<cv::Point2f> image(corners.begin(), corners.end());
    return cv::Matx33d(cv::getPerspectiveTransform(chart, image));
}

}  // namespace

std::array<Vec3d, kChartPatches> sample_patches(const cv::Mat& linear_rgb, const std::array<cv::Point2f, 4>& corners) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    const cv::Matx33d h = chart_homography(corners);
    std::array<Vec3d, kChartPatches> means{};
    cv::Mat mask(linear_rgb.size(), CV_8UC1);
    for (int row = 0; row < kChartRows; ++row)
        for (int col = 0; col < kChartColumns; ++col) {
            std::vector<cv::Point2d> square{{col + 0.25, row + 0.25}, {col + 0.75, row + 0.25},
                                            {col + 0.75, row + 0.75}, {col + 0.25, row + 0.75}};
            std::vector<cv::Point2d> projected;
            cv::perspectiveTransform(square, projected, h);
            std::vector<cv::Point> polygon;
            for (const auto& p : projected) {
                if (p.x < 0 || p.y < 0 || p.x > linear_rgb.cols - 1 || p.y > linear_rgb.rows - 1)
                    fail("chart patch {} lies outside the image (check the chart corners)",
                         row * kChartColumns + col + 1);
                polygon.emplace_back(cvRound(p.x), cvRound(p.y));
            }
            mask.setTo(0);
            cv::fillConvexPoly(mask, polygon, cv::Scalar(255));
            if (cv::countNonZero(mask) == 0)
                fail("chart patch {} covers no pixel (chart too small in the image)", row * kChartColumns + col + 1);
            const cv::Scalar m = cv::mean(linear_rgb, mask);
            means[static_cast<std::size_t>(row * kChartColumns + col)] = {m[0], m[1], m[2]};
        }
    return means;
}

std::array<cv::Point2f, 4> detect_chart(const cv::Mat& linear_rgb, const ChartReference& reference) {
    const cv::Mat bgr8 = to_display_bgr8(linear_rgb);
    auto detector = cv::mcc::CCheckerDetector::create();
    if (!detector->process(bgr8, cv::mcc::MCC24, 1)) fail("no ColorChecker chart found in the image");
    const std::vector<cv::Point2f> box = detector->getBestColorChecker()->getBox();
    if (box.size() != 4) fail("no ColorChecker chart found in the image");

    // mcc's box starts at an arbitrary corner (and its per-patch profile is not usable in OpenCV 4.6): take the
    // corner order, of the eight a quadrilateral admits, whose patches a 3x3 matrix maps best onto the reference.
    std::array<cv::Point2f, 4> best{};
    double best_error = std::numeric_limits<double>::infinity();
    for (int direction : {1, -1})
        for (int start = 0; start < 4; ++start) {
            std::array<cv::Point2f, 4> corners;
            for (int k = 0; k < 4; ++k)
                corners[static_cast<std::size_t>(k)] = box[static_cast<std::size_t>((start + direction * k + 4) % 4)];
            std::array<Vec3d, kChartPatches> patches;
            try {
                patches = sample_patches(linear_rgb, corners);
                const cv::Matx33d ccm = fit_ccm(patches, reference, CcmConstraint::None);
                const double error = chart_delta_e(apply_ccm(patches, ccm), reference).mean;
                if (error < best_error) best_error = error, best = corners;
            } catch (const Error&) {
                continue;  // this corner order puts patches outside the image or is degenerate
            }
        }
    if (!std::isfinite(best_error)) fail("ColorChecker found but its patches lie outside the image");
    return best;
}

namespace {
cv::Matx33d least_squares_ccm(const std::array<Vec3d, kChartPatches>& measured, const ChartReference& reference,
                              CcmConstraint constraint) {
    // Each row m_r of M solves min |A m_r - b_r|^2 with A = measured (24x3), b_r = reference channel r.
    cv::Matx33d ata = cv::Matx33d::zeros();
    cv::Matx33d atb = cv::Matx33d::zeros();  // column r = A^T b_r
    for (std::size_t i = 0; i < measured.size(); ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) {
                ata(j, k) += measured[i][j] * measured[i][k];
                atb(j, k) += measured[i][j] * reference.linear_srgb[i][k];
            }
    if (std::abs(cv::determinant(ata)) < 1e-18) fail("chart patches are degenerate (all the same colour?)");
    const cv::Matx33d ata_inv = ata.inv(cv::DECOMP_CHOLESKY);
    cv::Matx33d m;
    const Vec3d& w_in = measured[kWhitePatch];
    const Vec3d& w_ref = reference.linear_srgb[kWhitePatch];
    const cv::Vec3d w(w_in[0], w_in[1], w_in[2]);
    const cv::Vec3d ata_inv_w = ata_inv * w;
    const double w_ata_inv_w = w.dot(ata_inv_w);
    for (int r = 0; r < 3; ++r) {
        cv::Vec3d row = ata_inv * cv::Vec3d(atb(0, r), atb(1, r), atb(2, r));
        if (constraint == CcmConstraint::PreserveWhite) {
            // Lagrange multiplier for the equality w . m_r = w_ref[r].
            const double lambda = (w.dot(row) - w_ref[static_cast<std::size_t>(r)]) / w_ata_inv_w;
            row -= lambda * ata_inv_w;
        }
        for (int c = 0; c < 3; ++c) m(r, c) = row[c];
    }
    return m;
}

// M = start + sum_k x_k B_k over a basis B_k of the allowed changes: every entry, or (white preserved) per row the
// two directions orthogonal to the measured white.
class MeanDeltaE : public cv::MinProblemSolver::Function {
public:
    MeanDeltaE(const std::array<Vec3d, kChartPatches>& measured, const ChartReference& reference, cv::Matx33d start,
               CcmConstraint constraint)
        : measured_(measured), reference_(reference), start_(start) {
        if (constraint == CcmConstraint::None) {
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) {
                    cv::Matx33d b = cv::Matx33d::zeros();
                    b(r, c) = 1;
                    basis_.push_back(b);
                }
            return;
        }
        const Vec3d& white = measured[kWhitePatch];
        const cv::Vec3d w = cv::normalize(cv::Vec3d(white[0], white[1], white[2]));
        cv::Vec3d u = w.cross(cv::Vec3d(0, 0, 1));
        if (cv::norm(u) < 1e-6) u = w.cross(cv::Vec3d(1, 0, 0));
        u = cv::normalize(u);
        const cv::Vec3d v = w.cross(u);
        for (int r = 0; r < 3; ++r)
            for (const cv::Vec3d& d : {u, v}) {
                cv::Matx33d b = cv::Matx33d::zeros();
                for (int c = 0; c < 3; ++c) b(r, c) = d[c];
                basis_.push_back(b);
            }
    }
    int getDims() const override { return static_cast<int>(basis_.size()); }
    double calc(const double* x) const override { return chart_delta_e(apply_ccm(measured_, matrix(x)), reference_).mean; }
    cv::Matx33d matrix(const double* x) const {
        cv::Matx33d m = start_;
        for (std::size_t k = 0; k < basis_.size(); ++k) m += x[k] * basis_[k];
        return m;
    }

private:
    const std::array<Vec3d, kChartPatches>& measured_;
    const ChartReference& reference_;
    cv::Matx33d start_;
    std::vector<cv::Matx33d> basis_;
};
}  // namespace

CcmObjective ccm_objective_by_name(const std::string& name) {
    if (name == "ciede2000") return CcmObjective::Ciede2000;
    if (name == "least-squares") return CcmObjective::LeastSquares;
    fail("unknown colour-correction fit '{}' (expected ciede2000 or least-squares)", name);
}

cv::Matx33d fit_ccm(const std::array<Vec3d, kChartPatches>& measured, const ChartReference& reference,
                    CcmConstraint constraint, CcmObjective objective) {
    const cv::Matx33d start = least_squares_ccm(measured, reference, constraint);
    if (objective == CcmObjective::LeastSquares) return start;
    const auto problem = cv::makePtr<MeanDeltaE>(measured, reference, start, constraint);
    const int dims = problem->getDims();
    // Steps of 0.05 in the matrix entries (the least-squares matrix is near the optimum, entries of order 1);
    // Nelder-Mead can stall on a non-smooth objective, so it restarts from its result until that stops helping.
    auto solver = cv::DownhillSolver::create(problem, cv::Mat(1, dims, CV_64F, cv::Scalar(0.05)),
                                             cv::TermCriteria(cv::TermCriteria::MAX_ITER + cv::TermCriteria::EPS,
                                                              20000, 1e-10));
    cv::Mat x = cv::Mat::zeros(1, dims, CV_64F);
    double best = problem->calc(x.ptr<double>());
    for (int restart = 0; restart < 10; ++restart) {
        cv::Mat trial = x.clone();
        const double value = solver->minimize(trial);
        if (!(value < best - 1e-9)) break;
        best = value, x = trial;
    }
    return problem->matrix(x.ptr<double>());
}

std::array<Vec3d, kChartPatches> flatten_patches(const std::array<Vec3d, kChartPatches>& measured,
                                                 const std::array<Vec3d, kChartPatches>& flat) {
    Vec3d mean{0, 0, 0};
    for (std::size_t i = 0; i < flat.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            if (!(flat[i][c] > 0) || !std::isfinite(flat[i][c]))
                fail("the flat field is not positive at patch {} (channel {}: {}): is the grey card in the chart's place?",
                     i + 1, "RGB"[c], flat[i][c]);
            mean[c] += flat[i][c] / kChartPatches;
        }
    std::array<Vec3d, kChartPatches> out;
    for (std::size_t i = 0; i < flat.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) out[i][c] = measured[i][c] * mean[c] / flat[i][c];
    return out;
}

Lab linear_srgb_to_lab(const Vec3d& rgb) {
    static const Vec3d white = white_d65();
    return xyz_to_lab(linear_srgb_to_xyz(rgb), white);
}

DeltaEStats chart_delta_e(const std::array<Vec3d, kChartPatches>& rgb, const ChartReference& reference) {
    DeltaEStats stats;
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        const double de = ciede2000(reference.lab_d65[i], linear_srgb_to_lab(rgb[i]));
        stats.per_patch[i] = de;
        stats.mean += de / kChartPatches;
        stats.max = std::max(stats.max, de);
    }
    return stats;
}

std::array<Vec3d, kChartPatches> apply_ccm(const std::array<Vec3d, kChartPatches>& rgb, const cv::Matx33d& ccm) {
    std::array<Vec3d, kChartPatches> out;
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        const cv::Vec3d v = ccm * cv::Vec3d(rgb[i][0], rgb[i][1], rgb[i][2]);
        out[i] = {v[0], v[1], v[2]};
    }
    return out;
}

cv::Mat apply_ccm(const cv::Mat& linear_rgb, const cv::Matx33d& ccm) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    cv::Mat out;
    cv::transform(linear_rgb, out, cv::Matx33f(ccm));
    return out;
}

}  // namespace surfscatter::photo
