#include "surfscatter/study/manifest.hpp"

#include <chrono>
#include <ctime>
#include <fstream>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/study/json_input.hpp"

namespace surfscatter::study {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "surfscatter study manifest 1";

std::string utc_now() {
    const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    gmtime_r(&t, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

}  // namespace

std::optional<Fingerprint> fingerprint(const std::filesystem::path& file) {
    // Only a regular file has one: a manifest naming /dev/zero or a FIFO (a hand-edited "path") is out of date, not
    // read forever.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;
    std::uint64_t h = 14695981039346656037ULL;
    std::uintmax_t bytes = 0;
    char buffer[1 << 16];
    while (in) {
        in.read(buffer, sizeof buffer);
        const std::streamsize n = in.gcount();
        for (std::streamsize i = 0; i < n; ++i) {
            h ^= static_cast<unsigned char>(buffer[i]);
            h *= 1099511628211ULL;
        }
        bytes += static_cast<std::uintmax_t>(n);
    }
    return Fingerprint{bytes, fmt::format("{:016x}", h)};
}

Manifest::Manifest(std::filesystem::path file, const std::vector<Job>& jobs, const std::filesystem::path& folder)
    : file_(std::move(file)), folder_(folder), jobs_(jobs) {
    if (!std::filesystem::exists(file_)) return;
    const std::string text = read_input_file(file_, "study manifest");
    json document;
    try {
        document = parse_json_input(text, printable(file_.string(), kShownPathChars));
    } catch (const Error& e) {
        fail("{}; move it away to start the study afresh", e.what());
    }
    if (!document.is_object() || !document.contains("format") || document["format"] != kFormat ||
        !document.contains("jobs") || !document["jobs"].is_array())
        fail("{}: not a surfscatter study manifest; move it away to start the study afresh",
             printable(file_.string(), kShownPathChars));
    std::map<std::string, json> recorded;
    for (const json& entry : document["jobs"])
        if (entry.is_object() && entry.contains("id") && entry["id"].is_string()) recorded[entry["id"]] = entry;
    for (const Job& job : jobs_)
        if (auto it = recorded.find(job.id); it != recorded.end()) entries_[job.id] = it->second;
}

bool Manifest::up_to_date(const Job& job) const {
    const auto it = entries_.find(job.id);
    if (it == entries_.end()) return false;
    const json& e = it->second;
    // Compared as JSON values: a hand-edited entry of the wrong type is out of date, not an exception.
    if (!e.contains("status") || e["status"] != "done" || !e.contains("parameters") || e["parameters"] != job.parameters)
        return false;
    const auto matches = [&](const char* list, bool check_size) {
        if (!e.contains(list)) return true;
        if (!e[list].is_array()) return false;
        for (const json& f : e[list]) {
            if (!f.is_object() || !f.contains("path") || !f["path"].is_string()) return false;
            const auto now = fingerprint(folder_ / f["path"].get<std::string>());
            if (!now || !f.contains("fnv1a") || f["fnv1a"] != now->fnv1a) return false;
            if (check_size && (!f.contains("bytes") || f["bytes"] != now->bytes)) return false;
        }
        return true;
    };
    // Every output the job makes must be on record (a study that now wants more of a job reruns it).
    if (!e.contains("outputs") || e["outputs"].size() != job.outputs.size()) return false;
    return matches("outputs", true) && matches("inputs", false);
}

void Manifest::record(const Job& job, json report, int rank) {
    json entry = {{"id", job.id}, {"kind", to_string(job.kind)}, {"parameters", job.parameters}};
    json needs = json::array();
    for (const int d : job.dependencies) needs.push_back(jobs_.at(static_cast<std::size_t>(d)).id);
    entry["needs"] = needs;
    for (auto& [key, value] : report.items()) entry[key] = std::move(value);
    entry["rank"] = rank;
    entry["finished"] = utc_now();
    entries_[job.id] = std::move(entry);
    save();
}

void Manifest::save() const {
    json list = json::array();
    for (const Job& job : jobs_)
        if (auto it = entries_.find(job.id); it != entries_.end()) list.push_back(it->second);
    const json document = {{"format", kFormat}, {"updated", utc_now()}, {"jobs", list}};
    write_file_atomically(file_, document.dump(1) + "\n");
}

}  // namespace surfscatter::study
