#include "surfscatter/spectrum/cie.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"

namespace surfscatter::spectrum {

namespace {

std::vector<std::string> split_whitespace(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

double parse_number(const std::string& text, const std::string& where) {
    const auto value = to_double(text);
    if (!value || !std::isfinite(*value)) fail("{}: '{}' is not a number", where, printable(text));
    return *value;
}

std::string upper(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return s;
}

}  // namespace

CgatsSpectra read_cgats_spectra(const std::string& path) {
    std::ifstream in(path);
    if (!in) fail("cannot open CGATS spectral file '{}'", path);
    std::map<std::string, std::string> keywords;
    std::size_t field_count = 0;
    CgatsSpectra result;
    enum class Section { header, format, data, done } section = Section::header;
    int line_number = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string where = fmt::format("{}:{}", path, line_number);
        const auto words = split_whitespace(line);
        if (words.empty() || words[0][0] == '#') continue;
        if (words[0] == "BEGIN_DATA_FORMAT") { section = Section::format; continue; }
        if (words[0] == "END_DATA_FORMAT") { section = Section::header; continue; }
        if (words[0] == "BEGIN_DATA") { section = Section::data; continue; }
        if (words[0] == "END_DATA") { section = Section::done; continue; }
        switch (section) {
            case Section::header:
                if (words.size() >= 2) keywords[words[0]] = words[1];
                break;
            case Section::format:
                for (const auto& name : words)
                    if (name.rfind("SPEC_", 0) != 0) fail("{}: unexpected field '{}' (expected SPEC_<nm>)", where, name);
                field_count += words.size();
                break;
            case Section::data: {
                if (words.size() != field_count)
                    fail("{}: {} values in a data row, expected {} (one per SPEC_ field)", where, words.size(),
                         field_count);
                std::vector<double> values;
                for (const auto& w : words) values.push_back(parse_number(w, where));
                result.sets.push_back(std::move(values));
                break;
            }
            case Section::done: break;
        }
    }
    if (field_count < 2) fail("{}: no BEGIN_DATA_FORMAT block with at least two SPEC_ fields", path);
    if (result.sets.empty() || section != Section::done) fail("{}: no complete BEGIN_DATA ... END_DATA block", path);
    // The grid comes from the keywords: colord's field names are not always in nm (CIE-A.sp has SPEC_300000).
    const auto keyword = [&](const char* name) {
        const auto it = keywords.find(name);
        if (it == keywords.end()) fail("{}: keyword {} is missing", path, name);
        return parse_number(it->second, path + " " + name);
    };
    result.start_nm = keyword("SPECTRAL_START_NM");
    const double end_nm = keyword("SPECTRAL_END_NM");
    if (keywords.count("SPECTRAL_BANDS") && keyword("SPECTRAL_BANDS") != static_cast<double>(field_count))
        fail("{}: SPECTRAL_BANDS is {} but there are {} SPEC_ fields", path, keywords["SPECTRAL_BANDS"], field_count);
    result.step_nm = (end_nm - result.start_nm) / static_cast<double>(field_count - 1);
    if (!(result.step_nm > 0)) fail("{}: SPECTRAL_END_NM {} is not above SPECTRAL_START_NM {}", path, end_nm, result.start_nm);
    return result;
}

RegularSpectrum::RegularSpectrum(double start_nm, double step_nm, std::vector<double> values)
    : start_nm_(start_nm), step_nm_(step_nm), inv_step_(1.0 / step_nm), values_(std::move(values)) {
    if (values_.size() < 2 || !(step_nm > 0)) fail("a regular spectrum needs >= 2 values and a positive step");
}

CieTable::CieTable(RegularSpectrum x, RegularSpectrum y, RegularSpectrum z)
    : x_(std::move(x)), y_(std::move(y)), z_(std::move(z)) {}

CieTable CieTable::load(const std::string& cmf_path) {
    CgatsSpectra s = read_cgats_spectra(cmf_path);
    if (s.sets.size() != 3) fail("{}: {} data rows, expected 3 (xbar, ybar, zbar)", cmf_path, s.sets.size());
    return CieTable(RegularSpectrum(s.start_nm, s.step_nm, std::move(s.sets[0])),
                    RegularSpectrum(s.start_nm, s.step_nm, std::move(s.sets[1])),
                    RegularSpectrum(s.start_nm, s.step_nm, std::move(s.sets[2])));
}

const CieTable& cie1931() {
    static const CieTable table = CieTable::load(kCie1931CmfPath);
    return table;
}

std::vector<std::string> cie_illuminant_names() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(kCieIlluminantDirectory, ec)) {
        const std::string file = entry.path().filename().string();
        if (file.rfind("CIE-", 0) == 0 && entry.path().extension() == ".sp")
            names.push_back(file.substr(4, file.size() - 7));
    }
    std::sort(names.begin(), names.end());
    return names;
}

const RegularSpectrum& cie_illuminant(const std::string& name) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<RegularSpectrum>> cache;
    const std::string key = upper(name);
    std::lock_guard lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return *it->second;
    const auto names = cie_illuminant_names();
    if (std::find(names.begin(), names.end(), key) == names.end())
        fail("unknown CIE illuminant '{}' (known: {})", name, fmt::join(names, ", "));
    CgatsSpectra s = read_cgats_spectra(fmt::format("{}/CIE-{}.sp", kCieIlluminantDirectory, key));
    if (s.sets.size() != 1) fail("illuminant file CIE-{}.sp: {} data rows, expected 1", key, s.sets.size());
    auto spectrum = std::make_unique<RegularSpectrum>(s.start_nm, s.step_nm, std::move(s.sets[0]));
    return *cache.emplace(key, std::move(spectrum)).first->second;
}

}  // namespace surfscatter::spectrum
