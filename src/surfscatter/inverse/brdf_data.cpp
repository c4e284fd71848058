#include "surfscatter/inverse/brdf_data.hpp"

#include <cmath>
#include <set>
#include <tuple>
#include <utility>

#include "surfscatter/bsdf/rgl_measured.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"

namespace surfscatter::inverse {

namespace {

constexpr std::string_view kHeader = "wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,brdf";

std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> items;
    for (std::size_t start = 0;;) {
        const auto comma = line.find(',', start);
        items.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (comma == std::string_view::npos) return items;
        start = comma + 1;
    }
}

}  // namespace

BrdfData parse_brdf_csv(std::string_view text, const std::string& source) {
    BrdfData data;
    data.source = source;
    bool header_seen = false, with_errors = false;
    for_each_data_line(text, [&](std::string_view line, int number) {
        if (!header_seen) {
            with_errors = line == std::string(kHeader) + ",brdf_stderr";
            if (line != kHeader && !with_errors)
                fail("{}:{}: expected the header '{}' (optionally ',brdf_stderr'), got '{}'", source, number, kHeader,
                     printable(line));
            header_seen = true;
            return;
        }
        const auto items = split(line);
        const std::size_t columns = with_errors ? 7 : 6;
        if (items.size() != columns)
            fail("{}:{}: expected {} comma-separated numbers, got {} in '{}'", source, number, columns, items.size(),
                 printable(line));
        std::vector<double> values;
        for (std::size_t c = 0; c < columns; ++c) {
            const auto v = to_double(items[c]);
            if (!v) fail("{}:{}: column {} is not a number: '{}'", source, number, c + 1, printable(items[c]));
            values.push_back(*v);
        }
        data.wavelength_nm.push_back(values[0]);
        data.theta_i_deg.push_back(values[1]);
        data.phi_i_deg.push_back(values[2]);
        data.theta_o_deg.push_back(values[3]);
        data.phi_o_deg.push_back(values[4]);
        data.brdf.push_back(values[5]);
        if (with_errors) data.brdf_stderr.push_back(values[6]);
        data.line.push_back(number);
    });
    if (!header_seen) fail("{}: no header '{}'", source, kHeader);
    validate(data);
    return data;
}

BrdfData read_brdf_csv(const std::string& path) {
    return parse_brdf_csv(read_input_file(path, "BRDF data file"), path);
}

BrdfData read_brdf_rgl(const std::string& path, const std::vector<double>& wavelengths_nm,
                       std::size_t max_directions) {
    const bsdf::RglData d = bsdf::read_rgl(path);
    const bsdf::RglMeasuredBsdf file(d);
    for (double l : wavelengths_nm)
        if (!(l >= file.wavelengths().front() && l <= file.wavelengths().back()))
            fail("wavelength {} nm is outside the file {} ({}-{} nm)", l, printable(path, kShownPathChars),
                 file.wavelengths().front(), file.wavelengths().back());
    const Marginal2D vndf(d.vndf, d.vndf_cols, d.vndf_rows, {d.phi_i, d.theta_i}, true);
    std::vector<std::pair<double, double>> incidences;  // (theta_i, phi_i)
    for (double phi : d.phi_i)
        if (d.isotropic() || phi < kPi - 1e-6 || d.phi_i.front() > -kPi + 1e-6)
            for (double theta : d.theta_i)
                if (theta < 89 * kDegree) incidences.push_back({theta, d.isotropic() ? 0.0 : phi});
    if (incidences.empty()) fail("RGL file {}: no incidence below 89 degrees", printable(path, kShownPathChars));
    const std::size_t per_incidence = std::max<std::size_t>(4, max_directions / incidences.size());
    std::size_t stride = 1;
    while ((d.rows + stride - 1) / stride * ((d.cols + stride - 1) / stride) > per_incidence) ++stride;
    BrdfData data;
    data.source = path;
    for (const auto& [theta_i, phi_i] : incidences) {
        const Vec3 wi = spherical_direction(theta_i, phi_i);
        const double params[2] = {phi_i, theta_i};
        for (std::size_t y = 0; y < d.rows; y += stride)
            for (std::size_t x = 0; x < d.cols; x += stride) {
                const Vec2 node{double(x) / double(d.cols - 1), double(y) / double(d.rows - 1)};
                const Vec2 u_m = vndf.sample(node, params).first;
                const Vec3 m = spherical_direction(bsdf::rgl_u_to_theta(u_m.x),
                                                   bsdf::rgl_u_to_phi(u_m.y) + (d.isotropic() ? phi_i : 0.0));
                const Vec3 wo = normalize(m * (2 * dot(wi, m)) - wi);
                if (dot(wi, m) <= 0 || wo.z <= std::cos(89 * kDegree)) continue;
                for (double l : wavelengths_nm) {
                    const double f = file.eval(wi, wo, l);
                    if (!(f > 0)) continue;
                    data.wavelength_nm.push_back(l);
                    data.theta_i_deg.push_back(theta_i / kDegree);
                    data.phi_i_deg.push_back(phi_i / kDegree);
                    data.theta_o_deg.push_back(bsdf::rgl_elevation(wo) / kDegree);
                    data.phi_o_deg.push_back(std::atan2(wo.y, wo.x) / kDegree);
                    data.brdf.push_back(f);
                    data.line.push_back(static_cast<int>(data.brdf.size()));
                }
            }
    }
    validate(data);
    return data;
}

std::string row_name(const BrdfData& data, std::size_t j) {
    return data.line.empty() || j >= data.line.size() ? fmt::format("{} row {}", data.source, j + 1)
                                                      : fmt::format("{}:{}", data.source, data.line[j]);
}

void validate(const BrdfData& data) {
    const std::size_t n = data.brdf.size();
    for (const auto& [column, name] :
         {std::pair{&data.wavelength_nm, "wavelength_nm"}, std::pair{&data.theta_i_deg, "theta_i_deg"},
          std::pair{&data.phi_i_deg, "phi_i_deg"}, std::pair{&data.theta_o_deg, "theta_o_deg"},
          std::pair{&data.phi_o_deg, "phi_o_deg"}})
        if (column->size() != n) fail("{}: {} has {} values but brdf has {}", data.source, name, column->size(), n);
    const bool errors = !data.brdf_stderr.empty();
    if (errors && data.brdf_stderr.size() != n)
        fail("{}: brdf_stderr has {} values but brdf has {}", data.source, data.brdf_stderr.size(), n);
    if (!data.line.empty() && data.line.size() != n) fail("{}: line numbers do not match the rows", data.source);
    std::set<std::tuple<double, double, double, double>> directions;
    for (std::size_t j = 0; j < n; ++j) {
        const std::string row = row_name(data, j);
        if (!(std::isfinite(data.wavelength_nm[j]) && data.wavelength_nm[j] > 0))
            fail("{}: wavelength_nm must be finite and > 0, got {}", row, data.wavelength_nm[j]);
        if (!(data.theta_i_deg[j] >= 0 && data.theta_i_deg[j] < 90))
            fail("{}: theta_i_deg must be in [0, 90) (the light above the horizon), got {}", row, data.theta_i_deg[j]);
        if (!(data.theta_o_deg[j] >= 0 && data.theta_o_deg[j] < 90))
            fail("{}: theta_o_deg must be in [0, 90) (the viewer above the horizon), got {}", row, data.theta_o_deg[j]);
        if (!std::isfinite(data.phi_i_deg[j])) fail("{}: phi_i_deg must be finite, got {}", row, data.phi_i_deg[j]);
        if (!std::isfinite(data.phi_o_deg[j])) fail("{}: phi_o_deg must be finite, got {}", row, data.phi_o_deg[j]);
        if (!(std::isfinite(data.brdf[j]) && data.brdf[j] >= 0))
            fail("{}: brdf must be finite and >= 0 (1/sr), got {}", row, data.brdf[j]);
        if (errors && !(std::isfinite(data.brdf_stderr[j]) && data.brdf_stderr[j] > 0))
            fail("{}: brdf_stderr must be finite and > 0, got {}", row, data.brdf_stderr[j]);
        if (!errors && !(data.brdf[j] > 0))
            fail("{}: brdf is 0, which a relative residual cannot weigh: give a brdf_stderr column or leave the row "
                 "out", row);
        directions.emplace(data.theta_i_deg[j], data.phi_i_deg[j], data.theta_o_deg[j], data.phi_o_deg[j]);
    }
    if (n == 0) fail("{}: no data rows", data.source);
    if (directions.size() < 2)
        fail("{}: all {} rows are one direction (theta_i {}, phi_i {}, theta_o {}, phi_o {}): a fit needs several",
             data.source, n, data.theta_i_deg[0], data.phi_i_deg[0], data.theta_o_deg[0], data.phi_o_deg[0]);
}

}  // namespace surfscatter::inverse
