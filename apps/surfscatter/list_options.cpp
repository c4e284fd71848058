#include "list_options.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

namespace {

// The first name of a CLI11 option spec ("-o,--output" -> "-o") is how messages name the option.
std::string display_name(const std::string& spec) { return spec.substr(0, spec.find(',')); }

}  // namespace

std::vector<std::string> parse_string_list(const std::string& text, const std::string& option) {
    std::vector<std::string> items;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const auto first = item.find_first_not_of(" \t"), last = item.find_last_not_of(" \t");
        item = first == std::string::npos ? std::string() : item.substr(first, last - first + 1);
        if (item.empty()) fail("{}: item {} of '{}' is empty", option, items.size() + 1, printable(text));
        // A line break or another control character is no name, label or number (it broke compare's CSV rows).
        if (std::any_of(item.begin(), item.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
            fail("{}: item {} '{}' holds a control character (a line break, a tab, ...)", option, items.size() + 1,
                 printable(item));
        items.push_back(std::move(item));
        if (items.size() > kMaxListItems) fail("{}: more than {} items", option, kMaxListItems);
        if (comma == std::string::npos) return items;
        start = comma + 1;
    }
}

std::vector<double> parse_number_list(const std::string& text, const std::string& option) {
    std::vector<double> values;
    for (const std::string& item : parse_string_list(text, option)) {
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(item.c_str(), &end);
        if (end != item.c_str() + item.size())
            fail("{}: '{}' is not a number (expected a comma-separated list)", option, printable(item));
        // Underflow to a denormal or zero is the nearest double; overflow and nan/inf are not accepted.
        if (!std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0))
            fail("{}: '{}' is not a finite number", option, printable(item));
        values.push_back(v);
    }
    return values;
}

namespace {

// Every occurrence of the option is parsed by `parse` and appended to `values`.
template <typename T, typename Parse>
CLI::Option* add_list(CLI::App* cmd, const std::string& name, std::vector<T>& values, const std::string& help, Parse parse) {
    const std::string shown = display_name(name);
    return cmd->add_option_function<std::vector<std::string>>(
        name,
        [&values, shown, parse](const std::vector<std::string>& texts) {
            values.clear();
            for (const std::string& text : texts) {
                const std::vector<T> items = parse(text, shown);
                values.insert(values.end(), items.begin(), items.end());
                if (values.size() > kMaxListItems) fail("{}: more than {} items", shown, kMaxListItems);
            }
        },
        help);
}

}  // namespace

void check_integer_ranges(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        if (option->get_items_expected_max() == 0) continue;  // a flag
        const std::string type = option->get_type_name();
        const bool is_unsigned = type.rfind("UINT", 0) == 0;
        if (!is_unsigned && type.rfind("INT", 0) != 0) continue;
        option->check(CLI::Validator(
            [is_unsigned](std::string& value) {
                const char* text = value.c_str();
                while (*text == ' ' || *text == '\t') ++text;
                if (is_unsigned && *text == '-') return fmt::format("'{}' is negative (must be >= 0)", printable(value));
                char* end = nullptr;
                errno = 0;
                if (is_unsigned) std::strtoull(text, &end, 0);
                else std::strtoll(text, &end, 0);
                if (errno == ERANGE)
                    return fmt::format("'{}' is beyond the 64-bit integer range", printable(value));
                return std::string();  // a well-formed integer in range, or text that CLI11 refuses itself
            },
            ""));
    }
    for (CLI::App* sub : app.get_subcommands({})) check_integer_ranges(*sub);
}

CLI::Option* add_number_list(CLI::App* cmd, const std::string& name, std::vector<double>& values,
                             const std::string& help) {
    return add_list(cmd, name, values, help, parse_number_list);
}

CLI::Option* add_string_list(CLI::App* cmd, const std::string& name, std::vector<std::string>& values,
                             const std::string& help) {
    return add_list(cmd, name, values, help, parse_string_list);
}

}  // namespace surfscatter::cli
