#include "surfscatter/heightmap/hfm.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/heightmap/parse.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr std::string_view kHfmFirstLine = "X;Y;valid";

// The fields of a ';'-separated line.
std::vector<std::string_view> fields(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = line.find(';', start);
        out.push_back(parse::trim(line.substr(start, end == std::string_view::npos ? end : end - start)));
        if (end == std::string_view::npos) return out;
        start = end + 1;
    }
}

// Micrometres per unit of "[mm]".
double bracketed_unit(const std::string& path, std::string_view field, const char* what) {
    if (field.size() < 2 || field.front() != '[' || field.back() != ']')
        fail("{}:2: the unit of {} '{}' is not of the form [mm]", path, what, printable(field));
    const auto um = parse::length_unit_in_um(field.substr(1, field.size() - 2));
    if (!um) fail("{}:2: the unit of {} '{}' is not a length unit (m, mm, um, nm or pm)", path, what, printable(field));
    return *um;
}

}  // namespace

bool is_hfm(std::string_view head) {
    const std::size_t end = head.find('\n');
    return end != std::string_view::npos && parse::trim(head.substr(0, end)) == kHfmFirstLine;
}

LineScan read_hfm(const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::string bytes = parse::file_bytes(path);
    if (!is_hfm(bytes)) fail("{}: not an HFM file (first line is not 'X;Y;valid')", path);

    LineScan scan;
    scan.origin = path;
    double x_unit = 0.0, z_unit = 0.0;
    std::vector<double> x;
    std::vector<int> x_line;
    bool any_invalid = false;
    std::size_t line_start = 0;
    for (int number = 1; line_start < bytes.size(); ++number) {
        std::size_t line_end = bytes.find('\n', line_start);
        if (line_end == std::string::npos) line_end = bytes.size();
        const std::string_view line = parse::trim(std::string_view(bytes).substr(line_start, line_end - line_start));
        line_start = line_end + 1;
        if (number == 1) continue;
        if (line.empty()) continue;
        const std::vector<std::string_view> f = fields(line);
        if (f.size() != 3) fail("{}:{}: {} fields separated by ';', expected 3 (x;height;valid)", path, number, f.size());
        if (number == 2) {
            x_unit = bracketed_unit(path, f[0], "x");
            z_unit = bracketed_unit(path, f[1], "the heights");
            if (f[2] != "[1/0]") fail("{}:2: the third column's unit is '{}', expected [1/0]", path, printable(f[2]));
            continue;
        }
        const auto xv = to_double(f[0]);
        const auto zv = to_double(f[1]);
        if (!xv || !std::isfinite(*xv)) fail("{}:{}: x '{}' is not a finite number", path, number, printable(f[0]));
        if (!zv || !std::isfinite(*zv)) fail("{}:{}: height '{}' is not a finite number", path, number, printable(f[1]));
        if (f[2] != "1" && f[2] != "0") fail("{}:{}: valid flag '{}' is neither 1 nor 0", path, number, printable(f[2]));
        const bool valid = f[2] == "1";
        any_invalid = any_invalid || !valid;
        x.push_back(*xv);
        x_line.push_back(number);
        scan.heights_um.push_back(valid ? *zv * z_unit : 0.0);
        scan.validity.push_back(valid ? 1 : 0);
    }
    if (x_unit == 0.0) fail("{}: no unit line ('[mm];[mm];[1/0]') after the first line", path);
    if (x.size() < 2) fail("{}: {} points: a profile needs at least 2", path, x.size());
    // A uniform step, to 1 % of it (x is printed to a few digits: 0.0005 mm steps to 1e-6 mm).
    const double step = (x.back() - x.front()) / static_cast<double>(x.size() - 1);
    if (!(step > 0.0)) fail("{}: x does not increase (first {}, last {})", path, x.front(), x.back());
    for (std::size_t i = 1; i < x.size(); ++i)
        if (std::abs(x[i] - x[i - 1] - step) > 0.01 * step)
            fail("{}:{}: x step {:.6g} differs from the mean step {:.6g} by more than 1 %: not a uniformly spaced profile",
                 path, x_line[i], x[i] - x[i - 1], step);
    scan.spacing_um = step * x_unit;
    if (!any_invalid) scan.validity.clear();
    if (scan.valid_count() == 0) fail("{}: every point is marked invalid", path);
    scan.source.format = "HFM profile export (.hfm)";
    scan.source.reader = "native:hfm";
    scan.source.height_unit_um = z_unit;
    return scan;
}

}  // namespace surfscatter::heightmap
