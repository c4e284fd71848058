#include "surfscatter/inverse/brdf_data.hpp"

#include <cmath>
#include <set>
#include <tuple>
#include <utility>

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
        const std::string row = data.line.empty() ? fmt::format("{} row {}", data.source, j + 1)
                                                  : fmt::format("{}:{}", data.source, data.line[j]);
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
