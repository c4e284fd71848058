#pragma once
// Tables of doubles cached on disk under cache_directory(), one binary file per key: the file name is a hash of the
// key, the key itself is stored and compared, and a checksum covers the payload. Files are written to a per-process
// temporary name and renamed, so readers never see half a file. The cache is an optimisation: a missing, corrupt or
// unwritable file only costs a rebuild (nothing here throws).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surfscatter {

// While one of these lives (in any thread), save_cached_table writes nothing: a fit (inverse/) builds tables for
// hundreds of one-off parameter sets that no later run asks for again, megabytes each. Reads go on.
class TableCacheWritesPaused {
public:
    TableCacheWritesPaused();
    ~TableCacheWritesPaused();
    TableCacheWritesPaused(const TableCacheWritesPaused&) = delete;
    TableCacheWritesPaused& operator=(const TableCacheWritesPaused&) = delete;
};

// The file for `key` of a table kind (a file-name prefix) at a format version.
std::filesystem::path table_cache_file(const std::string& kind, std::uint32_t version, const std::string& key);
void save_cached_table(const std::filesystem::path& file, std::uint32_t version, const std::string& key,
                       const std::vector<double>& payload);
// The payload saved for exactly this key and version, if the file is intact and every value finite.
std::optional<std::vector<double>> load_cached_table(const std::filesystem::path& file, std::uint32_t version,
                                                     const std::string& key);

}  // namespace surfscatter
