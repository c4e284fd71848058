#include "surfscatter/photo/color_checker.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/optim.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/mcc.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {

ChartReference read_chart_reference(const std::filesystem::path& path) {
    const bool argyll = path == kArgyllColorChecker;
    std::istringstream in(read_input_file(path, argyll ? "chart reference (Debian package argyll-ref)" : "chart reference"));
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
                double* const coordinate = fields[i] == "LAB_L" ? &lab.L
                                           : fields[i] == "LAB_A" ? &lab.a
                                           : fields[i] == "LAB_B" ? &lab.b
                                                                  : nullptr;
                if (fields[i] == "SAMPLE_ID") {
                    id = values[i];
                    ++found;
                } else if (coordinate) {
                    const auto value = to_double(values[i]);
                    if (!value || !std::isfinite(*value))
                        fail("{}:{}: {} '{}' is not a finite number", path.string(), line_number, fields[i],
                             printable(values[i]));
                    *coordinate = *value;
                    ++found;
                }
            }
            if (found != 4) fail("{}:{}: needs SAMPLE_ID, LAB_L, LAB_A and LAB_B fields", path.string(), line_number);
            const bool well_formed = id.size() == 3 && id[0] >= 'A' && id[0] < 'A' + kChartRows &&
                                     std::isdigit(static_cast<unsigned char>(id[1])) &&
                                     std::isdigit(static_cast<unsigned char>(id[2]));
            const int col = well_formed ? (id[1] - '0') * 10 + (id[2] - '0') - 1 : -1;
            if (col < 0 || col >= kChartColumns)
                fail("{}:{}: sample id '{}' is not one of A01..D06", path.string(), line_number, printable(id));
            const auto index = static_cast<std::size_t>((id[0] - 'A') * kChartColumns + col);
            if (seen[index]) fail("{}:{}: sample {} is given twice", path.string(), line_number, id);
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

namespace {
double median(std::vector<double> v) {
    const auto mid = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}
}  // namespace

std::array<Vec3d, kChartPatches> sample_patches(const cv::Mat& image, const std::array<cv::Point2f, 4>& corners,
                                                std::array<int, kChartPatches>* rejected) {
    CV_Assert(image.type() == CV_32FC3);
    const cv::Matx33d h = chart_homography(corners);
    std::array<Vec3d, kChartPatches> means{};
    cv::Mat mask(image.size(), CV_8UC1);
    for (int row = 0; row < kChartRows; ++row)
        for (int col = 0; col < kChartColumns; ++col) {
            const int patch = row * kChartColumns + col;
            std::vector<cv::Point2d> square{{col + 0.25, row + 0.25}, {col + 0.75, row + 0.25},
                                            {col + 0.75, row + 0.75}, {col + 0.25, row + 0.75}};
            std::vector<cv::Point2d> projected;
            cv::perspectiveTransform(square, projected, h);
            std::vector<cv::Point> polygon;
            for (const auto& p : projected) {
                if (p.x < 0 || p.y < 0 || p.x > image.cols - 1 || p.y > image.rows - 1)
                    fail("chart patch {} lies outside the image (check the chart corners)", patch + 1);
                polygon.emplace_back(cvRound(p.x), cvRound(p.y));
            }
            mask.setTo(0);
            cv::fillConvexPoly(mask, polygon, cv::Scalar(255));
            std::vector<cv::Point> pixels;
            cv::findNonZero(mask, pixels);
            if (pixels.empty())
                fail("chart patch {} covers no pixel (chart too small in the image)", patch + 1);
            std::array<std::vector<double>, 3> channel;
            for (const auto& q : pixels)
                for (int c = 0; c < 3; ++c) channel[static_cast<std::size_t>(c)].push_back(image.at<cv::Vec3f>(q)[c]);
            std::array<double, 3> centre{}, limit{};
            for (std::size_t c = 0; c < 3; ++c) {
                centre[c] = median(channel[c]);
                std::vector<double> deviation;
                for (double v : channel[c]) deviation.push_back(std::abs(v - centre[c]));
                limit[c] = std::max(kPatchOutlierSigmas * 1.4826 * median(deviation), kPatchOutlierFloor);
            }
            Vec3d sum{0, 0, 0};
            int used = 0;
            for (std::size_t i = 0; i < pixels.size(); ++i) {
                bool inlier = true;
                for (std::size_t c = 0; c < 3; ++c) inlier = inlier && std::abs(channel[c][i] - centre[c]) <= limit[c];
                if (!inlier) continue;
                for (std::size_t c = 0; c < 3; ++c) sum[c] += channel[c][i];
                ++used;
            }
            for (std::size_t c = 0; c < 3; ++c) means[static_cast<std::size_t>(patch)][c] = sum[c] / used;
            if (rejected) (*rejected)[static_cast<std::size_t>(patch)] = static_cast<int>(pixels.size()) - used;
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
// Nelder-Mead (cv::DownhillSolver) from `x` with initial steps `step`, restarted from its result until that stops
// helping (it can stall on a non-smooth objective such as the mean CIEDE2000).
void minimize(const cv::Ptr<cv::MinProblemSolver::Function>& f, cv::Mat& x, const cv::Mat& step) {
    auto solver = cv::DownhillSolver::create(
        f, step, cv::TermCriteria(cv::TermCriteria::MAX_ITER + cv::TermCriteria::EPS, 20000, 1e-10));
    double best = f->calc(x.ptr<double>());
    for (int restart = 0; restart < 10; ++restart) {
        cv::Mat trial = x.clone();
        const double value = solver->minimize(trial);
        if (!(value < best - 1e-9)) break;
        best = value, x = trial;
    }
}
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
    // Steps of 0.05 in the matrix entries (the least-squares matrix is near the optimum, entries of order 1).
    cv::Mat x = cv::Mat::zeros(1, dims, CV_64F);
    minimize(problem, x, cv::Mat(1, dims, CV_64F, cv::Scalar(0.05)));
    return problem->matrix(x.ptr<double>());
}

namespace {
// The neutral row's linear fit of ln(reference) on the family's basis in L = ln(code), with a free offset (the
// scale); returns the coefficients of the basis and adds the squared residuals to `sum_squares`.
std::vector<double> neutral_row_fit(const std::array<Vec3d, kChartPatches>& codes, const ChartReference& reference,
                                    Linearization family, std::size_t channel, double& sum_squares) {
    constexpr int kFirstNeutral = 18;
    const int terms = family == Linearization::Gamma ? 1 : family == Linearization::Poly ? 3 : 0;
    cv::Mat a(kChartPatches - kFirstNeutral, terms + 1, CV_64F), b(kChartPatches - kFirstNeutral, 1, CV_64F);
    for (int i = kFirstNeutral; i < kChartPatches; ++i) {
        const double code = codes[static_cast<std::size_t>(i)][channel];
        const double target = reference.linear_srgb[static_cast<std::size_t>(i)][channel];
        if (!(code > 0) || !(target > 0))
            fail("chart patch {} has code {} in channel {}: a tone curve needs the neutral row above black (is the "
                 "photo under-exposed?)", i + 1, code, "RGB"[channel]);
        const double l = std::log(code);
        const int row = i - kFirstNeutral;
        double fixed = 0;
        if (family == Linearization::Linear) fixed = l;
        if (family == Linearization::Srgb) fixed = std::log(ToneCurve(Linearization::Srgb)(0, code));
        double power = l;
        for (int k = 0; k < terms; ++k, power *= l) a.at<double>(row, k) = power;
        a.at<double>(row, terms) = 1.0;
        b.at<double>(row) = std::log(target) - fixed;
    }
    cv::Mat x;
    cv::solve(a, b, x, cv::DECOMP_SVD);
    const cv::Mat r = a * x - b;
    sum_squares += r.dot(r);
    return std::vector<double>(x.begin<double>(), x.begin<double>() + terms);
}

// The log-code range of the chart's patches, per channel (where a poly curve's cubic applies).
std::array<std::array<double, 2>, 3> log_code_range(const std::array<Vec3d, kChartPatches>& codes) {
    std::array<std::array<double, 2>, 3> range;
    for (std::size_t c = 0; c < 3; ++c) {
        double low = 1, high = 0;
        for (const auto& v : codes) low = std::min(low, v[c]), high = std::max(high, v[c]);
        if (!(low > 0)) fail("a chart patch has code {} in channel {}: a tone curve needs every patch above black", low,
                             "RGB"[c]);
        range[c] = {std::log(low), std::log(high)};
    }
    return range;
}

ToneCurve neutral_row_curve(const std::array<Vec3d, kChartPatches>& codes, const ChartReference& reference,
                            Linearization family) {
    if (family == Linearization::Linear || family == Linearization::Srgb) return ToneCurve(family);
    ToneCurve::Coefficients coefficients{};
    double ignored = 0;
    for (std::size_t c = 0; c < 3; ++c) {
        const auto fit = neutral_row_fit(codes, reference, family, c, ignored);
        for (std::size_t k = 0; k < fit.size(); ++k) coefficients[c][k] = fit[k];
    }
    return ToneCurve(family, coefficients, family == Linearization::Poly ? log_code_range(codes)
                                                                         : std::array<std::array<double, 2>, 3>{});
}

double objective_value(const std::array<Vec3d, kChartPatches>& corrected, const ChartReference& reference,
                       CcmObjective objective) {
    if (objective == CcmObjective::Ciede2000) return chart_delta_e(corrected, reference).mean;
    double sum = 0;
    for (std::size_t i = 0; i < corrected.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) sum += std::pow(corrected[i][c] - reference.linear_srgb[i][c], 2);
    return sum;
}

// The curve's free coefficients as the solver's variables; the objective of the least-squares matrix they give.
class CurveObjective : public cv::MinProblemSolver::Function {
public:
    CurveObjective(const std::array<Vec3d, kChartPatches>& codes, const ChartReference& reference,
                   const ToneCurve& start, CcmConstraint constraint, CcmObjective objective,
                   const std::array<Vec3d, kChartPatches>* flat_codes)
        : codes_(codes), reference_(reference), start_(start), constraint_(constraint), objective_(objective),
          flat_codes_(flat_codes) {}
    int getDims() const override { return 3 * start_.free_coefficients(); }
    double calc(const double* x) const override {
        const ToneCurve curve = this->curve(x);
        if (!curve.increasing()) return 1e6;  // not a tone curve: outside the search space
        try {
            const auto linear = linearize_patches(codes_, curve, flat_codes_);
            const cv::Matx33d m = fit_ccm(linear, reference_, constraint_, CcmObjective::LeastSquares);
            const double value = objective_value(apply_ccm(linear, m), reference_, objective_);
            return std::isfinite(value) ? value : 1e6;
        } catch (const Error&) {
            return 1e6;  // degenerate patches for this curve
        }
    }
    ToneCurve curve(const double* x) const {
        ToneCurve::Coefficients c{};
        const int k = start_.free_coefficients();
        for (int ch = 0; ch < 3; ++ch)
            for (int j = 0; j < k; ++j) c[static_cast<std::size_t>(ch)][static_cast<std::size_t>(j)] = x[ch * k + j];
        return ToneCurve(start_.family(), c, start_.log_range());
    }

private:
    const std::array<Vec3d, kChartPatches>& codes_;
    const ChartReference& reference_;
    ToneCurve start_;
    CcmConstraint constraint_;
    CcmObjective objective_;
    const std::array<Vec3d, kChartPatches>* flat_codes_;
};

}  // namespace

LinearizationChoice choose_linearization(const std::array<Vec3d, kChartPatches>& codes,
                                         const ChartReference& reference) {
    LinearizationChoice choice;
    const std::array<Linearization, 4> families{Linearization::Linear, Linearization::Srgb, Linearization::Gamma,
                                                Linearization::Poly};
    for (std::size_t f = 0; f < families.size(); ++f) {
        double sum = 0;
        for (std::size_t c = 0; c < 3; ++c) neutral_row_fit(codes, reference, families[f], c, sum);
        choice.neutral_row_log_rms[f] = std::sqrt(sum / (3.0 * (kChartPatches - 18)));
    }
    const double best = *std::min_element(choice.neutral_row_log_rms.begin(), choice.neutral_row_log_rms.end());
    for (std::size_t f = 0; f < families.size(); ++f)
        if (choice.neutral_row_log_rms[f] <= best + kAutoLinearizationTolerance) {
            choice.family = families[f];
            break;
        }
    return choice;
}

std::array<Vec3d, kChartPatches> linearize_patches(const std::array<Vec3d, kChartPatches>& codes,
                                                   const ToneCurve& curve,
                                                   const std::array<Vec3d, kChartPatches>* flat_codes) {
    std::array<Vec3d, kChartPatches> linear;
    for (std::size_t i = 0; i < codes.size(); ++i) linear[i] = curve(codes[i]);
    if (!flat_codes) return linear;
    std::array<Vec3d, kChartPatches> flat;
    for (std::size_t i = 0; i < codes.size(); ++i) flat[i] = curve((*flat_codes)[i]);
    return flatten_patches(linear, flat);
}

ColourCorrection fit_colour_correction(const std::array<Vec3d, kChartPatches>& codes, const ChartReference& reference,
                                       Linearization family, CcmConstraint constraint, CcmObjective objective,
                                       const std::array<Vec3d, kChartPatches>* flat_codes) {
    CV_Assert(family != Linearization::Auto);
    ColourCorrection out;
    out.curve = neutral_row_curve(codes, reference, family);
    if (const int k = out.curve.free_coefficients(); k > 0) {
        const auto problem =
            cv::makePtr<CurveObjective>(codes, reference, out.curve, constraint, objective, flat_codes);
        cv::Mat x(1, 3 * k, CV_64F), step(1, 3 * k, CV_64F);
        for (int ch = 0; ch < 3; ++ch)
            for (int j = 0; j < k; ++j) {
                x.at<double>(ch * k + j) = out.curve.coefficients()[static_cast<std::size_t>(ch)][static_cast<std::size_t>(j)];
                step.at<double>(ch * k + j) = j == 0 ? 0.05 : 0.02;  // the exponent, then the bends
            }
        minimize(problem, x, step);
        out.curve = problem->curve(x.ptr<double>());
    }
    out.ccm = fit_ccm(linearize_patches(codes, out.curve, flat_codes), reference, constraint, objective);
    return out;
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
