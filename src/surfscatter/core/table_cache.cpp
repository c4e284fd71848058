#include "surfscatter/core/table_cache.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "surfscatter/core/paths.hpp"

namespace surfscatter {

namespace {

constexpr std::uint64_t kMagic = 0x5353524144544231ULL;  // "SSRADTB1"

std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t h = 1469598103934665603ULL) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
    return h;
}

}  // namespace

std::filesystem::path table_cache_file(const std::string& kind, std::uint32_t version, const std::string& key) {
    return cache_directory() / fmt::format("{}-v{}-{:016x}.bin", kind, version, fnv1a(key.data(), key.size()));
}

void save_cached_table(const std::filesystem::path& file, std::uint32_t version, const std::string& key,
                       const std::vector<double>& payload) {
    // Several processes (MPI ranks, on one host or on many sharing the cache folder) may build the same table at
    // once: each writes its own temporary file (temporary_beside: host and process in the name) and renames it into
    // place, so a reader sees a whole file or none, and the last rename wins with identical contents.
    std::filesystem::path tmp;
    try {
        tmp = temporary_beside(file);
        {
            std::ofstream out(tmp, std::ios::binary);
            const std::uint64_t key_size = key.size(), count = payload.size();
            const std::uint64_t checksum = fnv1a(payload.data(), payload.size() * sizeof(double));
            out.write(reinterpret_cast<const char*>(&kMagic), sizeof kMagic);
            out.write(reinterpret_cast<const char*>(&version), sizeof version);
            out.write(reinterpret_cast<const char*>(&key_size), sizeof key_size);
            out.write(key.data(), static_cast<std::streamsize>(key.size()));
            out.write(reinterpret_cast<const char*>(&count), sizeof count);
            out.write(reinterpret_cast<const char*>(payload.data()), static_cast<std::streamsize>(count * sizeof(double)));
            out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
            out.close();
            if (!out) throw std::runtime_error("write failed");
        }
        std::filesystem::rename(tmp, file);
    } catch (const std::exception&) {
        // An unwritable cache directory only costs rebuilding next time.
        std::error_code ec;
        if (!tmp.empty()) std::filesystem::remove(tmp, ec);
    }
}

std::optional<std::vector<double>> load_cached_table(const std::filesystem::path& file, std::uint32_t version,
                                                     const std::string& key) {
    try {
        std::ifstream in(file, std::ios::binary);
        if (!in) return std::nullopt;
        std::uint64_t magic = 0, key_size = 0, count = 0, checksum = 0;
        std::uint32_t stored_version = 0;
        in.read(reinterpret_cast<char*>(&magic), sizeof magic);
        in.read(reinterpret_cast<char*>(&stored_version), sizeof stored_version);
        in.read(reinterpret_cast<char*>(&key_size), sizeof key_size);
        if (!in || magic != kMagic || stored_version != version || key_size != key.size()) return std::nullopt;
        std::string stored_key(key_size, '\0');
        in.read(stored_key.data(), static_cast<std::streamsize>(key_size));
        in.read(reinterpret_cast<char*>(&count), sizeof count);
        if (!in || stored_key != key || count > (1ULL << 28)) return std::nullopt;
        std::vector<double> payload(count);
        in.read(reinterpret_cast<char*>(payload.data()), static_cast<std::streamsize>(count * sizeof(double)));
        in.read(reinterpret_cast<char*>(&checksum), sizeof checksum);
        if (!in || checksum != fnv1a(payload.data(), payload.size() * sizeof(double))) return std::nullopt;
        for (double v : payload)
            if (!std::isfinite(v)) return std::nullopt;
        return payload;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

}  // namespace surfscatter
