#include "surfscatter/core/table_cache.hpp"

#include <atomic>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"

namespace surfscatter {

namespace {

constexpr std::uint64_t kMagic = 0x5353524144544231ULL;  // "SSRADTB1"

std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t h = 1469598103934665603ULL) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
    return h;
}

std::atomic<int> writes_paused{0};

}  // namespace

TableCacheWritesPaused::TableCacheWritesPaused() { ++writes_paused; }
TableCacheWritesPaused::~TableCacheWritesPaused() { --writes_paused; }

std::filesystem::path table_cache_file(const std::string& kind, std::uint32_t version, const std::string& key) {
    return cache_directory() / fmt::format("{}-v{}-{:016x}.bin", kind, version, fnv1a(key.data(), key.size()));
}

void save_cached_table(const std::filesystem::path& file, std::uint32_t version, const std::string& key,
                       const std::vector<double>& payload) {
    if (writes_paused.load() > 0) return;
    std::string bytes;
    auto append = [&bytes](const void* data, std::size_t size) { bytes.append(static_cast<const char*>(data), size); };
    const std::uint64_t key_size = key.size(), count = payload.size();
    const std::uint64_t checksum = fnv1a(payload.data(), payload.size() * sizeof(double));
    append(&kMagic, sizeof kMagic);
    append(&version, sizeof version);
    append(&key_size, sizeof key_size);
    append(key.data(), key.size());
    append(&count, sizeof count);
    append(payload.data(), count * sizeof(double));
    append(&checksum, sizeof checksum);
    // Several processes (MPI ranks, on one host or on many sharing the cache folder) may build the same table at
    // once: the atomic write lets a reader see a whole file or none, and the last rename wins with identical contents.
    try {
        write_file_atomically(file, bytes);
    } catch (const std::exception&) {
        // An unwritable cache directory only costs rebuilding next time.
    }
}

std::optional<std::vector<double>> load_cached_table(const std::filesystem::path& file, std::uint32_t version,
                                                     const std::string& key) {
    try {
        // Only a regular file is read: a FIFO in its place blocked the open forever, a device fed it garbage. The
        // table is rebuilt and saved over it.
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
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
