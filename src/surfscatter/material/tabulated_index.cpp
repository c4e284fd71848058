#include "surfscatter/material/tabulated_index.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/material/wavelength_check.hpp"

namespace surfscatter::material {

LinearTable::LinearTable(std::vector<double> x, std::vector<double> y, const std::string& source)
    : x_(std::move(x)), y_(std::move(y)) {
    if (x_.empty() || x_.size() != y_.size()) fail("{}: empty table or columns of different lengths", source);
    for (std::size_t i = 0; i < x_.size(); ++i) {
        if (!std::isfinite(x_[i]) || !std::isfinite(y_[i])) fail("{}: row {} is not finite", source, i + 1);
        if (i > 0 && !(x_[i] > x_[i - 1]))
            fail("{}: wavelengths must increase strictly, but row {} ({}) follows {}", source, i + 1, x_[i], x_[i - 1]);
    }
}

double LinearTable::operator()(double x) const {
    if (x <= x_.front()) return y_.front();
    if (x >= x_.back()) return y_.back();
    const auto upper = std::upper_bound(x_.begin(), x_.end(), x);
    const auto i = static_cast<std::size_t>(upper - x_.begin());
    const double t = (x - x_[i - 1]) / (x_[i] - x_[i - 1]);
    return y_[i - 1] + t * (y_[i] - y_[i - 1]);
}

void check_index_value(double value, const char* name, const std::string& where) {
    if (!std::isfinite(value)) fail("{}: {} = {} is not a finite number", where, name, value);
    if (value < 0) fail("{}: {} = {} is negative (N = n + i k needs n >= 0 and k >= 0)", where, name, value);
}

TabulatedIndex::TabulatedIndex(std::string name, std::vector<double> lambda_nm, std::vector<double> n,
                               std::vector<double> k)
    : name_(std::move(name)) {
    for (std::size_t i = 0; i < lambda_nm.size(); ++i) {
        if (!(lambda_nm[i] > 0)) fail("{}: row {}: wavelength {} nm is not positive", name_, i + 1, lambda_nm[i]);
        const std::string row = fmt::format("{}: row {}", name_, i + 1);
        if (i < n.size()) check_index_value(n[i], "n", row);
        if (i < k.size()) check_index_value(k[i], "k", row);
    }
    n_ = LinearTable(lambda_nm, std::move(n), name_);
    k_ = LinearTable(std::move(lambda_nm), std::move(k), name_);
}

std::complex<double> TabulatedIndex::at(double lambda_nm) const {
    check_wavelength_in_range(lambda_nm, min_wavelength_nm(), max_wavelength_nm(), name_);
    return {n_(lambda_nm), k_(lambda_nm)};
}

namespace {

bool parse_double(std::string_view text, double& value) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    const auto parsed = to_double(text);
    if (parsed) value = *parsed;
    return parsed.has_value();
}

std::vector<std::string_view> split_commas(std::string_view line) {
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

}  // namespace

std::shared_ptr<const RefractiveIndex> load_csv_refractive_index(const std::string& path) {
    return parse_csv_refractive_index(read_input_file(path, "refractive index file"), path);
}

std::shared_ptr<const RefractiveIndex> parse_csv_refractive_index(const std::string& text, const std::string& path) {
    std::vector<double> lambda, n, k;
    bool header_allowed = true;
    for_each_data_line(text, [&](std::string_view line, int line_number) {
        const auto fields = split_commas(line);
        double values[3];
        const bool numeric = fields.size() == 3 && parse_double(fields[0], values[0]) &&
                             parse_double(fields[1], values[1]) && parse_double(fields[2], values[2]);
        if (!numeric) {
            if (header_allowed && fields.size() == 3 && !parse_double(fields[0], values[0])) {
                header_allowed = false;
                return;
            }
            fail("{}:{}: expected 'wavelength_nm,n,k' with three numbers, got '{}'", path, line_number, printable(line));
        }
        header_allowed = false;
        if (!(values[0] > 0) || !std::isfinite(values[0]))
            fail("{}:{}: wavelength {} nm is not positive", path, line_number, values[0]);
        const std::string where = fmt::format("{}:{}", path, line_number);
        check_index_value(values[1], "n", where);
        check_index_value(values[2], "k", where);
        if (!lambda.empty() && !(values[0] > lambda.back()))
            fail("{}:{}: wavelength {} nm does not increase (previous row {} nm)", path, line_number, values[0],
                 lambda.back());
        lambda.push_back(values[0]);
        n.push_back(values[1]);
        k.push_back(values[2]);
    });
    if (lambda.size() < 2) fail("{}: needs at least two rows 'wavelength_nm,n,k', found {}", path, lambda.size());
    return std::make_shared<TabulatedIndex>(path, std::move(lambda), std::move(n), std::move(k));
}

}  // namespace surfscatter::material
