#include "surfscatter/reference/kirchhoff_map.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/parallel_jobs.hpp"
#include "surfscatter/heightmap/fftw_planner.hpp"

namespace surfscatter::reference {

namespace {

using Complex = std::complex<double>;

constexpr double kRemainderTolerance = 1e-10;  // of sum W dx dy, per direction (header)
constexpr double kMaxBandPhase = 4.0;          // delta r: the terms then sum to at most e^4 = 55 times the result
constexpr std::size_t kMinSubareaPixels = 16;
constexpr double kMaxAliasedFraction = 1e-3;
constexpr double kMinLobeSteps = 3.0;

struct Direction {
    long mx, my;
    double ox, oy, qz, prefactor;  // prefactor: f_r per |I|^2 / A_W
};

struct Tile {
    std::size_t x0, y0;
};

// Highest Taylor power N with e^rho rho^(N+1) / (N+1)! <= kRemainderTolerance.
std::size_t taylor_order(double rho) {
    double next = rho;  // rho^(N+1) / (N+1)! for N = 0
    std::size_t order = 0;
    while (std::exp(rho) * next > kRemainderTolerance) {
        ++order;
        next *= rho / static_cast<double>(order + 1);
    }
    return order;
}

std::vector<double> hann_window(std::size_t n) {
    std::vector<double> w(n);
    for (std::size_t j = 0; j < n; ++j) {
        const double s = std::sin(kPi * (static_cast<double>(j) + 0.5) / static_cast<double>(n));
        w[j] = s * s;
    }
    return w;
}

// One thread's FFT arrays and plan (a complex n_y x n_x transform with the + sign, out of place: the input stays).
class TileFft {
public:
    TileFft(std::size_t nx, std::size_t ny) : size_(nx * ny) {
        in_ = fftw_alloc_complex(size_);
        out_ = fftw_alloc_complex(size_);
        if (in_ == nullptr || out_ == nullptr) {
            release();
            fail("cannot allocate the Kirchhoff FFT arrays ({} points)", size_);
        }
        std::lock_guard<std::mutex> lock(heightmap::fftw_planner_mutex());
        plan_ = fftw_plan_dft_2d(static_cast<int>(ny), static_cast<int>(nx), in_, out_, FFTW_BACKWARD, FFTW_ESTIMATE);
        if (plan_ == nullptr) {
            release();
            fail("FFTW could not plan a {} x {} transform", nx, ny);
        }
    }
    ~TileFft() { release(); }
    TileFft(const TileFft&) = delete;
    TileFft& operator=(const TileFft&) = delete;
    Complex* input() { return reinterpret_cast<Complex*>(in_); }
    const Complex* output() const { return reinterpret_cast<const Complex*>(out_); }
    void execute() { fftw_execute(plan_); }

private:
    void release() {
        std::lock_guard<std::mutex> lock(heightmap::fftw_planner_mutex());
        if (plan_ != nullptr) fftw_destroy_plan(plan_);
        fftw_free(in_);
        fftw_free(out_);
        plan_ = nullptr;
        in_ = out_ = nullptr;
    }
    std::size_t size_;
    fftw_complex* in_ = nullptr;
    fftw_complex* out_ = nullptr;
    fftw_plan plan_ = nullptr;
};

struct Geometry {
    std::size_t nx = 0, ny = 0;  // sub-area pixels
    double dx = 0, dy = 0;
    double k = 0;
    std::vector<double> window;  // n_y x n_x, row-major
    double window_area = 0;      // A_W = sum W^2 dx dy
    std::vector<Direction> directions;
    double qz_min = 0, qz_max = 0;
};

// The amplitudes I(q) of every direction for one sub-area (header: bands of q_z, Taylor terms within a band).
std::vector<Complex> tile_amplitudes(const heightmap::HeightMap& map, const Tile& tile, const Geometry& g, TileFft& fft,
                                     std::size_t& fft_count, std::size_t& band_count) {
    const std::size_t n = g.nx * g.ny;
    std::vector<double> u(n);
    double mean = 0;
    for (std::size_t y = 0; y < g.ny; ++y)
        for (std::size_t x = 0; x < g.nx; ++x) mean += map(tile.x0 + x, tile.y0 + y);
    mean /= static_cast<double>(n);
    double reach = 0;
    for (std::size_t y = 0; y < g.ny; ++y)
        for (std::size_t x = 0; x < g.nx; ++x) {
            const double v = map(tile.x0 + x, tile.y0 + y) - mean;
            u[y * g.nx + x] = v;
            reach = std::max(reach, std::abs(v));
        }
    const double range = g.qz_max - g.qz_min;
    // The band count with the fewest FFTs (bands x terms) among those with delta r <= kMaxBandPhase.
    const double spread = range * reach / 2;  // delta r of a single band
    std::size_t bands = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(spread / kMaxBandPhase)));
    for (std::size_t b = bands + 1, cost = bands * (taylor_order(spread / static_cast<double>(bands)) + 1);
         b < 4 * bands + 4; ++b) {
        const std::size_t c = b * (taylor_order(spread / static_cast<double>(b)) + 1);
        if (c < cost) {
            cost = c;
            bands = b;
        }
    }
    const double half_width = range / (2 * static_cast<double>(bands));
    const std::size_t order = taylor_order(half_width * reach);
    band_count = bands;

    std::vector<std::vector<std::size_t>> members(bands);
    for (std::size_t d = 0; d < g.directions.size(); ++d) {
        const double position = range > 0 ? (g.directions[d].qz - g.qz_min) / (2 * half_width) : 0.0;
        members[std::min(bands - 1, static_cast<std::size_t>(position))].push_back(d);
    }
    std::vector<Complex> amplitude(g.directions.size(), 0.0);
    std::vector<Complex> power(g.directions.size());  // (q_z - q_c)^n per direction
    std::vector<Complex> term(n);
    const double cell = g.dx * g.dy;
    for (std::size_t b = 0; b < bands; ++b) {
        if (members[b].empty()) continue;
        const double centre = g.qz_min + (2 * static_cast<double>(b) + 1) * half_width;
        for (std::size_t j = 0; j < n; ++j) term[j] = g.window[j] * cell * std::polar(1.0, centre * u[j]);
        for (std::size_t d : members[b]) power[d] = 1.0;
        for (std::size_t p = 0; p <= order; ++p) {
            if (p > 0)
                for (std::size_t j = 0; j < n; ++j) term[j] *= Complex(0.0, u[j] / static_cast<double>(p));
            std::copy(term.begin(), term.end(), fft.input());
            fft.execute();
            ++fft_count;
            const Complex* out = fft.output();
            for (std::size_t d : members[b]) {
                const Direction& dir = g.directions[d];
                const std::size_t kx = static_cast<std::size_t>(dir.mx < 0 ? dir.mx + static_cast<long>(g.nx) : dir.mx);
                const std::size_t ky = static_cast<std::size_t>(dir.my < 0 ? dir.my + static_cast<long>(g.ny) : dir.my);
                amplitude[d] += power[d] * out[ky * g.nx + kx];
                power[d] *= dir.qz - centre;
            }
        }
    }
    for (std::size_t d = 0; d < g.directions.size(); ++d)
        amplitude[d] *= std::polar(1.0, g.directions[d].qz * mean);
    return amplitude;
}

void check_options(const KirchhoffOptions& o) {
    require_positive(o.lambda_nm, o.option_names.wavelength.c_str());
    require_finite(o.theta_i_rad, "theta_i");
    if (o.theta_i_rad < 0 || o.theta_i_rad >= kPi / 2)
        fail("theta_i must be in [0, 90) degrees, got {}", o.theta_i_rad / kDegree);
    require_finite(o.phi_i_rad, "phi_i");
    require_positive(o.subarea_um, o.option_names.subarea.c_str());
    require_finite(o.max_theta_o_rad, "max theta_o");
    if (o.max_theta_o_rad <= 0 || o.max_theta_o_rad >= kPi / 2)
        fail("max theta_o must be in (0, 90) degrees, got {}", o.max_theta_o_rad / kDegree);
    require_thread_count(o.threads, o.option_names.threads.c_str());
}

std::size_t subarea_pixels(double side_um, double spacing_um, std::size_t map_pixels, char axis,
                           const std::string& name) {
    const double pixels = std::round(side_um / spacing_um);
    if (pixels < static_cast<double>(kMinSubareaPixels))
        fail("{} {} um is {} pixels of {} um along {}: at least {} are needed", name, side_um, pixels, spacing_um,
             axis, kMinSubareaPixels);
    if (pixels > static_cast<double>(map_pixels))
        fail("{} {} um is larger than the map along {} ({} pixels of {} um)", name, side_um, axis, map_pixels,
             spacing_um);
    return static_cast<std::size_t>(pixels);
}

// The lattice directions kept and their prefactors (header).
void lattice_directions(Geometry& g, const material::Conductor& conductor, const KirchhoffOptions& o,
                        std::vector<std::string>& warnings) {
    const double ix = std::sin(o.theta_i_rad) * std::cos(o.phi_i_rad);
    const double iy = std::sin(o.theta_i_rad) * std::sin(o.phi_i_rad);
    const double cos_i = std::cos(o.theta_i_rad);
    const double sin_max = std::sin(o.max_theta_o_rad);
    const double step_x = kTwoPi / (static_cast<double>(g.nx) * g.dx * g.k);
    const double step_y = kTwoPi / (static_cast<double>(g.ny) * g.dy * g.k);
    const long half_x = static_cast<long>(g.nx / 2), half_y = static_cast<long>(g.ny / 2);
    // The Nyquist bins m = n/2 are ambiguous in sign: only |m| < n/2 is used.
    if (std::abs(ix) + sin_max >= static_cast<double>(half_x) * step_x ||
        std::abs(iy) + sin_max >= static_cast<double>(half_y) * step_y)
        warnings.push_back(fmt::format(
            "the pixel ({} x {} um) resolves |o_x + i_x| < {:.4g} and |o_y + i_y| < {:.4g} only: directions beyond "
            "are not computed",
            g.dx, g.dy, static_cast<double>(half_x) * step_x, static_cast<double>(half_y) * step_y));
    g.qz_min = 1e300;
    g.qz_max = -1e300;
    for (long my = -half_y + 1; my < half_y; ++my)
        for (long mx = -half_x + 1; mx < half_x; ++mx) {
            const double ox = static_cast<double>(mx) * step_x - ix;
            const double oy = static_cast<double>(my) * step_y - iy;
            const double sin2 = ox * ox + oy * oy;
            if (sin2 > sin_max * sin_max) continue;
            const double cos_o = std::sqrt(1.0 - sin2);
            const double qx = g.k * (ix + ox), qy = g.k * (iy + oy), qz = g.k * (cos_i + cos_o);
            const double q2 = qx * qx + qy * qy + qz * qz;
            const double cos_d = std::min(1.0, std::sqrt(q2) / (2 * g.k));
            const double fresnel = conductor.reflectance(cos_d, o.lambda_nm);
            const double prefactor = fresnel * q2 * q2 / (16 * kPi * kPi * qz * qz * cos_i * cos_o);
            g.directions.push_back({mx, my, ox, oy, qz, prefactor});
            g.qz_min = std::min(g.qz_min, qz);
            g.qz_max = std::max(g.qz_max, qz);
        }
    if (g.directions.empty()) fail("no lattice direction lies within theta_o <= {} deg", o.max_theta_o_rad / kDegree);
}

// Fraction of neighbouring pixel pairs inside the tiles whose phase step q_z,max |dh| exceeds pi.
double aliased_fraction(const heightmap::HeightMap& map, const std::vector<Tile>& tiles, const Geometry& g) {
    std::size_t pairs = 0, aliased = 0;
    for (const Tile& t : tiles)
        for (std::size_t y = 0; y < g.ny; ++y)
            for (std::size_t x = 0; x < g.nx; ++x) {
                const double h = map(t.x0 + x, t.y0 + y);
                if (x + 1 < g.nx) {
                    ++pairs;
                    aliased += g.qz_max * std::abs(map(t.x0 + x + 1, t.y0 + y) - h) > kPi;
                }
                if (y + 1 < g.ny) {
                    ++pairs;
                    aliased += g.qz_max * std::abs(map(t.x0 + x, t.y0 + y + 1) - h) > kPi;
                }
            }
    return static_cast<double>(aliased) / static_cast<double>(pairs);
}

std::vector<Tile> usable_tiles(const heightmap::HeightMap& map, const Geometry& g, std::vector<std::string>& warnings) {
    const std::size_t tx = map.nx() / g.nx, ty = map.ny() / g.ny;
    const std::size_t margin_x = (map.nx() - tx * g.nx) / 2, margin_y = (map.ny() - ty * g.ny) / 2;
    std::vector<Tile> tiles;
    for (std::size_t b = 0; b < ty; ++b)
        for (std::size_t a = 0; a < tx; ++a) {
            const Tile t{margin_x + a * g.nx, margin_y + b * g.ny};
            bool valid = true;
            for (std::size_t y = 0; y < g.ny && valid; ++y)
                for (std::size_t x = 0; x < g.nx && valid; ++x) valid = map.valid(t.x0 + x, t.y0 + y);
            if (valid) tiles.push_back(t);
        }
    if (tiles.size() < tx * ty)
        warnings.push_back(fmt::format("{} of {} sub-areas hold invalid points and are skipped", tx * ty - tiles.size(),
                                       tx * ty));
    if (tiles.size() < 2)
        fail("{}: {} usable sub-area(s) of {} x {} pixels: at least 2 are needed (a standard error); use smaller "
             "sub-areas",
             map.origin(), tiles.size(), g.nx, g.ny);
    return tiles;
}

// Mean, standard error and coherent part over the sub-areas done; the diffuse lobe's width check.
void reduce(const Geometry& g, const std::vector<std::vector<Complex>>& amplitudes, const std::vector<char>& done,
            const KirchhoffOptions& o, KirchhoffResult& out) {
    std::vector<const std::vector<Complex>*> completed;
    for (std::size_t t = 0; t < amplitudes.size(); ++t)
        if (done[t]) completed.push_back(&amplitudes[t]);
    out.subareas_done = completed.size();
    const std::size_t m = g.directions.size();
    out.o_x.resize(m);
    out.o_y.resize(m);
    for (std::size_t d = 0; d < m; ++d) {
        out.o_x[d] = g.directions[d].ox;
        out.o_y[d] = g.directions[d].oy;
    }
    out.brdf.assign(m, 0.0);
    out.standard_error.assign(m, 0.0);
    out.coherent.assign(m, 0.0);
    if (completed.empty()) return;
    const double count = static_cast<double>(completed.size());
    const double cell = out.step_x * out.step_y;
    std::vector<double> tile_albedo(completed.size(), 0.0);
    for (std::size_t d = 0; d < m; ++d) {
        const double scale = g.directions[d].prefactor / g.window_area;
        Complex mean = 0.0;
        double sum = 0.0, sum2 = 0.0;
        for (std::size_t t = 0; t < completed.size(); ++t) {
            const Complex a = (*completed[t])[d];
            const double f = scale * std::norm(a);
            mean += a;
            sum += f;
            sum2 += f * f;
            tile_albedo[t] += f * cell;
        }
        mean /= count;
        out.brdf[d] = sum / count;
        out.coherent[d] = std::min(out.brdf[d], scale * std::norm(mean));
        if (completed.size() > 1)
            out.standard_error[d] =
                std::sqrt(std::max(0.0, (sum2 - sum * sum / count) / (count - 1)) / count);
        out.albedo += out.brdf[d] * cell;
        out.coherent_albedo += out.coherent[d] * cell;
    }
    if (completed.size() > 1) {
        double var = 0;
        for (double a : tile_albedo) var += (a - out.albedo) * (a - out.albedo);
        out.albedo_standard_error = std::sqrt(var / (count - 1) / count);
    } else {
        out.warnings.push_back("only 1 sub-area evaluated: the standard errors are not known (written as 0)");
    }
    // Width of the diffuse part about the specular direction, in lattice steps.
    const double sx = -std::sin(o.theta_i_rad) * std::cos(o.phi_i_rad);
    const double sy = -std::sin(o.theta_i_rad) * std::sin(o.phi_i_rad);
    double weight = 0, moment = 0;
    for (std::size_t d = 0; d < m; ++d) {
        const double diffuse = out.brdf[d] - out.coherent[d];
        const double ex = (out.o_x[d] - sx) / out.step_x, ey = (out.o_y[d] - sy) / out.step_y;
        weight += diffuse;
        moment += diffuse * (ex * ex + ey * ey);
    }
    if (weight * cell > 1e-3 * out.albedo && std::sqrt(moment / weight) < kMinLobeSteps) {
        out.lobe_unresolved = fmt::format("the diffuse lobe is {:.3g} lattice steps wide (rms): sub-areas of {} x {} "
                                          "pixels are too small to resolve it",
                                          std::sqrt(moment / weight), g.nx, g.ny);
        out.warnings.push_back(out.lobe_unresolved);
    }
}

}  // namespace

void require_kirchhoff_subarea(const heightmap::HeightMap& map, const KirchhoffOptions& o) {
    require_positive(o.subarea_um, o.option_names.subarea.c_str());
    subarea_pixels(o.subarea_um, map.spacing_x(), map.nx(), 'x', o.option_names.subarea);
    subarea_pixels(o.subarea_um, map.spacing_y(), map.ny(), 'y', o.option_names.subarea);
}

KirchhoffResult kirchhoff_brdf(const heightmap::HeightMap& map, const material::Conductor& conductor,
                               const KirchhoffOptions& o) {
    check_options(o);
    KirchhoffResult out;
    Geometry g;
    g.dx = map.spacing_x();
    g.dy = map.spacing_y();
    g.k = kTwoPi / (o.lambda_nm * 1e-3);
    g.nx = subarea_pixels(o.subarea_um, g.dx, map.nx(), 'x', o.option_names.subarea);
    g.ny = subarea_pixels(o.subarea_um, g.dy, map.ny(), 'y', o.option_names.subarea);
    const std::vector<double> wx = hann_window(g.nx), wy = hann_window(g.ny);
    g.window.resize(g.nx * g.ny);
    double window_square = 0;
    for (std::size_t y = 0; y < g.ny; ++y)
        for (std::size_t x = 0; x < g.nx; ++x) {
            const double w = wx[x] * wy[y];
            g.window[y * g.nx + x] = w;
            window_square += w * w;
        }
    g.window_area = window_square * g.dx * g.dy;
    lattice_directions(g, conductor, o, out.warnings);
    const std::vector<Tile> tiles = usable_tiles(map, g, out.warnings);
    out.subarea_nx = g.nx;
    out.subarea_ny = g.ny;
    out.step_x = kTwoPi / (static_cast<double>(g.nx) * g.dx * g.k);
    out.step_y = kTwoPi / (static_cast<double>(g.ny) * g.dy * g.k);
    out.subareas = tiles.size();
    out.aliased_fraction = aliased_fraction(map, tiles, g);
    if (out.aliased_fraction > kMaxAliasedFraction)
        fail("{}: sampling too coarse for {} nm: {:.3g} % of neighbouring pixels differ in height by more than "
             "lambda / (2 (cos i + cos o_max)) (a phase step above pi; at most {} % can be trusted): use a finer map "
             "or a longer wavelength",
             map.origin(), o.lambda_nm, 100 * out.aliased_fraction, 100 * kMaxAliasedFraction);
    if (out.aliased_fraction > 0)
        out.warnings.push_back(fmt::format("{:.3g} % of neighbouring pixel pairs have a phase step above pi: that "
                                           "much energy may be aliased",
                                           100 * out.aliased_fraction));
    require_memory(static_cast<double>(tiles.size()) * static_cast<double>(g.directions.size()) * sizeof(Complex),
                   "the Kirchhoff amplitudes");

    std::vector<std::vector<Complex>> amplitudes(tiles.size());
    std::vector<std::size_t> ffts(tiles.size(), 0), bands(tiles.size(), 0);
    const std::vector<char> done =
        run_parallel_jobs(tiles.size(), o.threads, "kirchhoff sub-areas", o.progress, [&] {
            auto fft = std::make_shared<TileFft>(g.nx, g.ny);  // one plan per thread
            return [&, fft](std::size_t t) {
                amplitudes[t] = tile_amplitudes(map, tiles[t], g, *fft, ffts[t], bands[t]);
            };
        });
    out.fft_count = *std::max_element(ffts.begin(), ffts.end());
    out.band_count = *std::max_element(bands.begin(), bands.end());
    reduce(g, amplitudes, done, o, out);
    return out;
}

}  // namespace surfscatter::reference
