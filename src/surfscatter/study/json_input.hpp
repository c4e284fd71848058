#pragma once
// JSON from the user's files (study files, manifests), parsed defensively: nesting is bounded before the document is
// built, since nlohmann::json prints and compares nested values recursively (a file of 100 000 opening brackets
// would exhaust the stack), and syntax errors are a surfscatter::Error naming the file.
#include <string>

#include <nlohmann/json.hpp>

namespace surfscatter::study {

inline constexpr int kMaxJsonDepth = 64;  // nesting of arrays and objects (docs/RELIABILITY.md)

// `origin` names the text in messages ("study.json: not valid JSON: ...", "study.json: nested more than 64 deep").
nlohmann::json parse_json_input(const std::string& text, const std::string& origin);

// A value quoted in a one-line message: its JSON text, at most a few dozen characters.
std::string quoted_json(const nlohmann::json& value);

}  // namespace surfscatter::study
