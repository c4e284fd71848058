#include "surfscatter/study/json_input.hpp"

#include "surfscatter/core/error.hpp"

namespace surfscatter::study {

nlohmann::json parse_json_input(const std::string& text, const std::string& origin) {
    const auto bounded = [&](int depth, nlohmann::json::parse_event_t event, const nlohmann::json&) {
        if ((event == nlohmann::json::parse_event_t::object_start || event == nlohmann::json::parse_event_t::array_start) &&
            depth >= kMaxJsonDepth)
            fail("{}: arrays and objects nested more than {} deep", origin, kMaxJsonDepth);
        return true;
    };
    try {
        return nlohmann::json::parse(text, bounded);
    } catch (const nlohmann::json::parse_error& e) {
        fail("{}: not valid JSON: {}", origin, printable(e.what(), 200));
    }
}

std::string quoted_json(const nlohmann::json& value) { return printable(value.dump(), 60); }

}  // namespace surfscatter::study
