#include "surfscatter/study/json_input.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include "surfscatter/core/error.hpp"

namespace surfscatter::study {

nlohmann::json parse_json_input(const std::string& text, const std::string& origin) {
    // Parsed from a stream so that the parser's position (it has just read the token it reports) gives the line of
    // a duplicate key or an overflowing number; lines are counted only for the message.
    std::istringstream stream(text);
    const auto offset = [&] {
        const auto at = stream.rdbuf()->pubseekoff(0, std::ios::cur, std::ios::in);
        return static_cast<std::size_t>(std::max<std::streamoff>(at, 0));
    };
    const auto line_of = [&](std::size_t at) {
        return 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(std::min(at, text.size())), '\n');
    };
    // nlohmann::json keeps one of two equal keys without a word: each open object's keys with their offsets.
    std::vector<std::map<std::string, std::size_t>> open_objects;
    using event_t = nlohmann::json::parse_event_t;
    const auto check = [&](int depth, event_t event, const nlohmann::json& parsed) {
        if ((event == event_t::object_start || event == event_t::array_start) && depth >= kMaxJsonDepth)
            fail("{}: arrays and objects nested more than {} deep", origin, kMaxJsonDepth);
        if (event == event_t::object_start) open_objects.emplace_back();
        else if (event == event_t::object_end) open_objects.pop_back();
        else if (event == event_t::key && !open_objects.empty()) {
            const std::string& key = parsed.get_ref<const std::string&>();
            const auto [it, first] = open_objects.back().emplace(key, offset());
            if (!first)
                fail("{}:{}: key '{}' is given twice in one object (first at line {})", origin, line_of(offset()),
                     printable(key), line_of(it->second));
        }
        return true;
    };
    try {
        return nlohmann::json::parse(stream, check);
    } catch (const nlohmann::json::parse_error& e) {
        fail("{}: not valid JSON: {}", origin, printable(e.what(), 200));
    } catch (const nlohmann::json::out_of_range& e) {
        // 406: a number beyond the double range (1e400), which the parser refuses as it reads it.
        const std::string what = e.what();
        const auto quote = what.find('\'');
        const std::string number = quote == std::string::npos ? what : what.substr(quote + 1, what.rfind('\'') - quote - 1);
        fail("{}:{}: number '{}' is beyond the range of a double (+-1.8e308)", origin, line_of(offset()),
             printable(number));
    } catch (const nlohmann::json::exception& e) {
        fail("{}: not valid JSON: {}", origin, printable(e.what(), 200));
    }
}

std::string quoted_json(const nlohmann::json& value) { return printable(value.dump(), 60); }

}  // namespace surfscatter::study
