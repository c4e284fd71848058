#include "surfscatter/material/refractiveindex_info.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/material/tabulated_index.hpp"
#include "surfscatter/material/wavelength_check.hpp"

namespace surfscatter::material {

namespace {

constexpr double kNmPerUm = 1000.0;

// Maximum number of coefficients per formula (formulas 1, 2, 3, 5, 6 take pairs after C1).
std::size_t max_coefficients(int formula) {
    switch (formula) {
        case 1: case 2: case 3: case 5: case 6: return 17;
        case 4: return 17;
        case 7: return 6;
        case 8: return 4;
        case 9: return 6;
        default: return 0;
    }
}

}  // namespace

double dispersion_formula_index(int formula, const std::vector<double>& given, double lambda_um) {
    const std::size_t max = max_coefficients(formula);
    if (max == 0) fail("unknown refractiveindex.info dispersion formula {} (known: 1-9)", formula);
    if (given.empty() || given.size() > max)
        fail("formula {} takes 1 to {} coefficients, got {}", formula, max, given.size());
    std::vector<double> c(given);
    c.resize(max, 0.0);  // absent trailing coefficients are zero in the database's definitions
    const double l = lambda_um, l2 = l * l;
    double n = 0;
    switch (formula) {
        case 1: {  // n^2 - 1 = C1 + sum C_i l^2 / (l^2 - C_{i+1}^2)
            double s = 1 + c[0];
            for (std::size_t i = 1; i + 1 < max; i += 2) s += c[i] * l2 / (l2 - c[i + 1] * c[i + 1]);
            n = std::sqrt(s);
            break;
        }
        case 2: {  // n^2 - 1 = C1 + sum C_i l^2 / (l^2 - C_{i+1})
            double s = 1 + c[0];
            for (std::size_t i = 1; i + 1 < max; i += 2) s += c[i] * l2 / (l2 - c[i + 1]);
            n = std::sqrt(s);
            break;
        }
        case 3: {  // n^2 = C1 + sum C_i l^C_{i+1}
            double s = c[0];
            for (std::size_t i = 1; i + 1 < max; i += 2) s += c[i] * std::pow(l, c[i + 1]);
            n = std::sqrt(s);
            break;
        }
        case 4: {  // n^2 = C1 + C2 l^C3/(l^2 - C4^C5) + C6 l^C7/(l^2 - C8^C9) + sum_{i>=10} C_i l^C_{i+1}
            double s = c[0];
            if (c[1] != 0) s += c[1] * std::pow(l, c[2]) / (l2 - std::pow(c[3], c[4]));
            if (c[5] != 0) s += c[5] * std::pow(l, c[6]) / (l2 - std::pow(c[7], c[8]));
            for (std::size_t i = 9; i + 1 < max; i += 2) s += c[i] * std::pow(l, c[i + 1]);
            n = std::sqrt(s);
            break;
        }
        case 5: {  // n = C1 + sum C_i l^C_{i+1}
            n = c[0];
            for (std::size_t i = 1; i + 1 < max; i += 2) n += c[i] * std::pow(l, c[i + 1]);
            break;
        }
        case 6: {  // n - 1 = C1 + sum C_i / (C_{i+1} - l^-2)
            n = 1 + c[0];
            for (std::size_t i = 1; i + 1 < max; i += 2)
                if (c[i] != 0) n += c[i] / (c[i + 1] - 1.0 / l2);
            break;
        }
        case 7: {  // n = C1 + C2/(l^2 - 0.028) + C3/(l^2 - 0.028)^2 + C4 l^2 + C5 l^4 + C6 l^6
            const double d = 1.0 / (l2 - 0.028);
            n = c[0] + c[1] * d + c[2] * d * d + c[3] * l2 + c[4] * l2 * l2 + c[5] * l2 * l2 * l2;
            break;
        }
        case 8: {  // (n^2 - 1)/(n^2 + 2) = C1 + C2 l^2/(l^2 - C3) + C4 l^2
            const double a = c[0] + c[1] * l2 / (l2 - c[2]) + c[3] * l2;
            n = std::sqrt((1 + 2 * a) / (1 - a));
            break;
        }
        case 9: {  // n^2 = C1 + C2/(l^2 - C3) + C4 (l - C5) / ((l - C5)^2 + C6)
            const double d = l - c[4];
            n = std::sqrt(c[0] + c[1] / (l2 - c[2]) + c[3] * d / (d * d + c[5]));
            break;
        }
    }
    if (!(n > 0) || !std::isfinite(n))
        fail("formula {} gives no real positive index at {} um (got {})", formula, lambda_um, n);
    return n;
}

namespace {

// n or k over a wavelength range (nm), from a table or a formula.
struct Curve {
    std::function<double(double)> value;
    double min_nm = 0, max_nm = 0;
};

// The (n, k) source of the whole file: n from `n`, k from `k` (or 0), on the intersection of their ranges.
class CombinedIndex final : public RefractiveIndex {
public:
    CombinedIndex(std::string name, Curve n, std::optional<Curve> k)
        : name_(std::move(name)), n_(std::move(n)), k_(std::move(k)) {
        min_nm_ = k_ ? std::max(n_.min_nm, k_->min_nm) : n_.min_nm;
        max_nm_ = k_ ? std::min(n_.max_nm, k_->max_nm) : n_.max_nm;
        if (!(min_nm_ < max_nm_))
            fail("{}: the wavelength ranges of n ({}-{} nm) and k ({}-{} nm) do not overlap", name_, n_.min_nm,
                 n_.max_nm, k_->min_nm, k_->max_nm);
    }
    std::complex<double> at(double lambda_nm) const override {
        check_wavelength_in_range(lambda_nm, min_nm_, max_nm_, name_);
        return {n_.value(lambda_nm), k_ ? k_->value(lambda_nm) : 0.0};
    }
    double min_wavelength_nm() const override { return min_nm_; }
    double max_wavelength_nm() const override { return max_nm_; }
    std::string name() const override { return name_; }

private:
    std::string name_;
    Curve n_;
    std::optional<Curve> k_;
    double min_nm_, max_nm_;
};

std::vector<double> parse_numbers(const std::string& text, const std::string& where) {
    std::istringstream in(text);
    std::vector<double> values;
    for (std::string word; in >> word;) {
        const std::optional<double> v = to_double(word.front() == '+' ? std::string_view(word).substr(1) : word);
        if (!v || !std::isfinite(*v)) fail("{}: '{}' is not a number", where, printable(word));
        // A subnormal number is a number, but no wavelength, index or coefficient of a real material.
        if (*v != 0 && std::abs(*v) < std::numeric_limits<double>::min())
            fail("{}: '{}' is too small (subnormal, below {:g})", where, printable(word), std::numeric_limits<double>::min());
        values.push_back(*v);
    }
    return values;
}

// Rows of a `data: |` block: the wavelength in um, then the quantities `names` ("n", "k") in that order.
std::vector<std::vector<double>> parse_rows(const YAML::Node& data, std::initializer_list<const char*> names,
                                            const std::string& path) {
    if (!data || !data.IsScalar()) fail("{}: a tabulated DATA entry needs a 'data' block", path);
    const std::size_t columns = names.size() + 1;
    std::istringstream in(data.Scalar());
    std::vector<std::vector<double>> rows;
    // A block scalar starts on the line after its 'data: |' key (yaml-cpp's marks are 0-based).
    int line_number = data.Mark().line + 1;
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        const std::string where = fmt::format("{}:{}", path, line_number);
        auto row = parse_numbers(line, where);
        if (row.empty()) continue;
        if (row.size() != columns) fail("{}: expected {} numbers per row, got {}", where, columns, row.size());
        if (!(row[0] > 0)) fail("{}: wavelength {} um is not positive", where, row[0]);
        std::size_t column = 1;
        for (const char* name : names) check_index_value(row[column++], name, where);
        rows.push_back(std::move(row));
    }
    if (rows.size() < 2) fail("{}: a tabulated DATA entry needs at least two rows, found {}", path, rows.size());
    return rows;
}

// yaml-cpp keeps both of two equal keys and finds the first: a key given twice in any mapping of the file is an
// error naming both lines. Walked without recursion, and at most twice as many nodes as the text has bytes: aliases
// share nodes, and a file of nested aliases would otherwise be walked an exponential number of times.
void refuse_duplicate_keys(const YAML::Node& root, const std::string& path, std::size_t text_bytes) {
    std::vector<YAML::Node> pending = {root};
    for (std::size_t visited = 0; !pending.empty(); ++visited) {
        if (visited > 2 * text_bytes + 64) fail("{}: its aliases expand to more nodes than the file has bytes", path);
        const YAML::Node node = pending.back();
        pending.pop_back();
        if (node.IsSequence()) {
            for (const YAML::Node& item : node) pending.push_back(item);
        } else if (node.IsMap()) {
            std::map<std::string, int> lines;
            for (const auto& item : node) {
                if (item.first.IsScalar()) {
                    const auto [it, first] = lines.emplace(item.first.Scalar(), item.first.Mark().line + 1);
                    if (!first)
                        fail("{}:{}: key '{}' is given twice in one mapping (first at line {})", path,
                             item.first.Mark().line + 1, printable(item.first.Scalar()), it->second);
                }
                pending.push_back(item.second);
            }
        }
    }
}

Curve table_curve(const std::vector<std::vector<double>>& rows, std::size_t column, const std::string& source) {
    std::vector<double> lambda, values;
    for (const auto& r : rows) {
        lambda.push_back(r[0] * kNmPerUm);
        values.push_back(r[column]);
    }
    auto table = std::make_shared<LinearTable>(std::move(lambda), std::move(values), source);
    return {[table](double l) { return (*table)(l); }, table->min_x(), table->max_x()};
}

Curve formula_curve(int formula, const YAML::Node& entry, const std::string& where) {
    const YAML::Node range = entry["wavelength_range"];
    const YAML::Node coefficients = entry["coefficients"];
    if (!range || !range.IsScalar()) fail("{}: formula entry without 'wavelength_range'", where);
    if (!coefficients || !coefficients.IsScalar()) fail("{}: formula entry without 'coefficients'", where);
    const auto limits = parse_numbers(range.Scalar(), where + " wavelength_range");
    if (limits.size() != 2 || !(limits[0] > 0) || !(limits[1] > limits[0]))
        fail("{}: wavelength_range must be two increasing positive numbers (um), got '{}'", where, range.Scalar());
    const auto c = parse_numbers(coefficients.Scalar(), where + " coefficients");
    // Every error, now or when a wavelength is evaluated later, names the file and entry.
    const auto index = [formula, c, where](double lambda_um) {
        try {
            return dispersion_formula_index(formula, c, lambda_um);
        } catch (const Error& e) {
            fail("{}: {}", where, e.what());
        }
    };
    index(limits[0]);  // validates the formula number and coefficient count
    return {[index](double l) { return index(l / kNmPerUm); }, limits[0] * kNmPerUm, limits[1] * kNmPerUm};
}

}  // namespace

std::shared_ptr<const RefractiveIndex> load_refractiveindex_info_yaml(const std::string& path) {
    return parse_refractiveindex_info_yaml(read_input_file(path, "refractive index file"), path);
}

std::shared_ptr<const RefractiveIndex> parse_refractiveindex_info_yaml(const std::string& text, const std::string& path) {
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        fail("{}:{}: malformed YAML: {}", path, e.mark.line + 1, printable(e.msg));
    }
    refuse_duplicate_keys(root, path, text.size());
    const YAML::Node data = root.IsMap() ? root["DATA"] : YAML::Node();
    if (!data || !data.IsSequence() || data.size() == 0)
        fail("{}: no DATA list (not a refractiveindex.info material file)", path);
    std::optional<Curve> n, k;
    for (std::size_t i = 0; i < data.size(); ++i) {
        const YAML::Node entry = data[i];
        const std::string where = fmt::format("{}: DATA entry {}", path, i + 1);
        const YAML::Node type_node = entry.IsMap() ? entry["type"] : YAML::Node();
        if (!type_node || !type_node.IsScalar()) fail("{} has no 'type'", where);
        const std::string type = type_node.Scalar();
        const auto set = [&](std::optional<Curve>& slot, Curve curve, const char* what) {
            if (slot) fail("{}: {} is given twice", where, what);
            slot = std::move(curve);
        };
        if (type == "tabulated nk") {
            const auto rows = parse_rows(entry["data"], {"n", "k"}, path);
            set(n, table_curve(rows, 1, path), "n");
            set(k, table_curve(rows, 2, path), "k");
        } else if (type == "tabulated n") {
            set(n, table_curve(parse_rows(entry["data"], {"n"}, path), 1, path), "n");
        } else if (type == "tabulated k") {
            set(k, table_curve(parse_rows(entry["data"], {"k"}, path), 1, path), "k");
        } else if (type.rfind("formula ", 0) == 0) {
            int formula = 0;
            try {
                formula = std::stoi(type.substr(8));
            } catch (const std::exception&) {
                fail("{}: unknown type '{}'", where, printable(type));
            }
            set(n, formula_curve(formula, entry, where), "n");
        } else {
            fail("{}: unknown type '{}' (tabulated nk, tabulated n, tabulated k, formula 1-9)", where, printable(type));
        }
    }
    if (!n) fail("{}: DATA has k but no n", path);
    return std::make_shared<CombinedIndex>(path, std::move(*n), std::move(k));
}

}  // namespace surfscatter::material
