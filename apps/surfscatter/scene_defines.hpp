#pragma once
// The -D name=value scene parameters of `render` and `compare-models`.
#include <map>
#include <string>
#include <vector>

namespace surfscatter::cli {

// "name=value" items -> map. A name must be what $name in a scene can refer to (letters, digits, '_'); a name
// given twice is an error (which value was meant?).
std::map<std::string, std::string> parse_defines(const std::vector<std::string>& items);

}  // namespace surfscatter::cli
