#pragma once
// Microsoft Compound File Binary files (the "OLE2 structured storage" of [MS-CFB], Microsoft's published
// specification): a FAT file system inside one file, whose streams the MountainsMap reader (mnt.hpp) needs. Only
// what reading a stream of the root storage takes: the header, the FAT (with DIFAT sectors), the directory and the
// mini stream. Every sector number, chain and size is checked against the file, so a damaged file is an Error
// naming it, never a read past its end or an endless chain. Not a public interface.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace surfscatter::heightmap {

// True if `head` starts with the CFB signature D0 CF 11 E0 A1 B1 1A E1.
bool is_compound_file(std::string_view head);

class CompoundFile {
public:
    // `bytes` (the whole file) must outlive the object; `path` names it in messages.
    CompoundFile(std::string_view bytes, std::string path);

    // The names (UTF-8) of the root storage's streams.
    std::vector<std::string> stream_names() const;
    // The stream of the root storage called `name` (UTF-8, compared exactly), or nullopt if there is none.
    std::optional<std::string> stream(std::string_view name) const;

private:
    struct DirectoryEntry {
        std::string name;
        unsigned type = 0;  // 1 storage, 2 stream, 5 root
        std::uint32_t left = 0, right = 0, child = 0, start = 0;
        std::uint64_t size = 0;
    };
    std::string_view sector(std::uint32_t index, const char* what) const;
    // The sectors of the chain starting at `start` (FAT or mini FAT), checked for cycles and range.
    std::vector<std::uint32_t> chain(std::uint32_t start, const std::vector<std::uint32_t>& table, const char* what) const;
    std::string read_chain(std::uint32_t start, std::uint64_t size, const char* what) const;
    // The entries of the root storage (the red-black tree under the root's child).
    std::vector<const DirectoryEntry*> root_children() const;

    std::string_view bytes_;
    std::string path_;
    unsigned sector_shift_ = 9;
    std::uint32_t mini_cutoff_ = 4096;
    std::vector<std::uint32_t> fat_, mini_fat_;
    std::vector<DirectoryEntry> directory_;
    std::string mini_stream_;
};

}  // namespace surfscatter::heightmap
