#include "surfscatter/heightmap/compound_file.hpp"

#include <algorithm>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/binary.hpp"
#include "surfscatter/heightmap/parse.hpp"

namespace surfscatter::heightmap {

namespace {
constexpr std::string_view kSignature("\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1", 8);
constexpr std::size_t kHeaderBytes = 512, kHeaderDifat = 109, kEntryBytes = 128, kMiniSectorBytes = 64;
constexpr std::uint32_t kEndOfChain = 0xfffffffe, kNoStream = 0xffffffff, kMaxRegular = 0xfffffffa;
constexpr unsigned kStream = 2, kRoot = 5;
}  // namespace

bool is_compound_file(std::string_view head) { return head.substr(0, kSignature.size()) == kSignature; }

CompoundFile::CompoundFile(std::string_view bytes, std::string path) : bytes_(bytes), path_(std::move(path)) {
    if (!is_compound_file(bytes_) || bytes_.size() < kHeaderBytes)
        fail("{}: not a compound file (no CFB signature and 512-byte header)", path_);
    const char* h = bytes_.data();
    sector_shift_ = binary::load_u16(h + 30);
    if (sector_shift_ != 9 && sector_shift_ != 12)
        fail("{}: compound file sector size 2^{} is neither 512 nor 4096 bytes", path_, sector_shift_);
    if (binary::load_u16(h + 32) != 6) fail("{}: compound file mini sector size 2^{} is not 64 bytes", path_, binary::load_u16(h + 32));
    const std::uint32_t fat_sectors = binary::load_u32(h + 44);
    const std::uint32_t directory_start = binary::load_u32(h + 48);
    mini_cutoff_ = binary::load_u32(h + 56);
    const std::uint32_t mini_fat_start = binary::load_u32(h + 60);
    std::uint32_t difat_sector = binary::load_u32(h + 68);
    const std::size_t sector_bytes = std::size_t{1} << sector_shift_;
    const std::size_t sectors = bytes_.size() / sector_bytes;  // an upper bound on every count and chain
    if (fat_sectors > sectors) fail("{}: compound file header states {} FAT sectors, the file has {}", path_, fat_sectors, sectors);

    // The FAT sectors: 109 in the header, the rest in a chain of DIFAT sectors (the last word of each links on).
    std::vector<std::uint32_t> fat_list;
    for (std::size_t i = 0; i < kHeaderDifat && fat_list.size() < fat_sectors; ++i)
        fat_list.push_back(binary::load_u32(h + 76 + 4 * i));
    const std::size_t per_difat = sector_bytes / 4 - 1;
    for (std::size_t hops = 0; fat_list.size() < fat_sectors; ++hops) {
        if (hops > sectors) fail("{}: compound file DIFAT chain does not end", path_);
        const std::string_view s = sector(difat_sector, "a DIFAT sector");
        for (std::size_t i = 0; i < per_difat && fat_list.size() < fat_sectors; ++i)
            fat_list.push_back(binary::load_u32(s.data() + 4 * i));
        difat_sector = binary::load_u32(s.data() + 4 * per_difat);
    }
    fat_.reserve(fat_list.size() * (sector_bytes / 4));
    for (std::uint32_t s : fat_list) {
        const std::string_view fat_sector = sector(s, "a FAT sector");
        for (std::size_t i = 0; i < sector_bytes / 4; ++i) fat_.push_back(binary::load_u32(fat_sector.data() + 4 * i));
    }

    const std::vector<std::uint32_t> directory_sectors = chain(directory_start, fat_, "the directory");
    for (std::uint32_t s : directory_sectors) {
        const std::string_view d = sector(s, "a directory sector");
        for (std::size_t at = 0; at + kEntryBytes <= d.size(); at += kEntryBytes) {
            const char* e = d.data() + at;
            DirectoryEntry entry;
            const std::size_t name_bytes = binary::load_u16(e + 64);
            entry.type = static_cast<unsigned char>(e[66]);
            if (name_bytes >= 2 && name_bytes <= 64)
                entry.name = parse::utf16le_to_utf8(std::string_view(e, name_bytes - 2), path_ + ": a directory entry's name");
            entry.left = binary::load_u32(e + 68);
            entry.right = binary::load_u32(e + 72);
            entry.child = binary::load_u32(e + 76);
            entry.start = binary::load_u32(e + 116);
            entry.size = binary::load_u64(e + 120);
            if (sector_shift_ == 9) entry.size &= 0xffffffffu;  // version 3 files: the high word may be garbage
            directory_.push_back(std::move(entry));
        }
    }
    if (directory_.empty() || directory_[0].type != kRoot) fail("{}: compound file has no root directory entry", path_);
    if (mini_fat_start < kMaxRegular) {
        for (std::uint32_t s : chain(mini_fat_start, fat_, "the mini FAT")) {
            const std::string_view m = sector(s, "a mini FAT sector");
            for (std::size_t i = 0; i < sector_bytes / 4; ++i) mini_fat_.push_back(binary::load_u32(m.data() + 4 * i));
        }
        mini_stream_ = read_chain(directory_[0].start, directory_[0].size, "the mini stream");
    }
}

std::string_view CompoundFile::sector(std::uint32_t index, const char* what) const {
    const std::uint64_t offset = (std::uint64_t{index} + 1) << sector_shift_;
    const std::size_t size = std::size_t{1} << sector_shift_;
    if (index >= kMaxRegular || offset + size > bytes_.size())
        fail("{}: compound file: {} is sector {}, beyond the end of the file ({} bytes)", path_, what, index, bytes_.size());
    return bytes_.substr(offset, size);
}

std::vector<std::uint32_t> CompoundFile::chain(std::uint32_t start, const std::vector<std::uint32_t>& table,
                                               const char* what) const {
    std::vector<std::uint32_t> out;
    for (std::uint32_t s = start; s != kEndOfChain;) {
        if (s >= table.size())
            fail("{}: compound file: the chain of {} reaches sector {}, outside its table of {}", path_, what, s, table.size());
        if (out.size() >= table.size()) fail("{}: compound file: the chain of {} does not end (a cycle)", path_, what);
        out.push_back(s);
        s = table[s];
    }
    return out;
}

std::string CompoundFile::read_chain(std::uint32_t start, std::uint64_t size, const char* what) const {
    std::string out;
    if (size == 0) return out;
    const std::vector<std::uint32_t> sectors = chain(start, fat_, what);
    const std::uint64_t available = std::uint64_t{sectors.size()} << sector_shift_;
    if (size > available)
        fail("{}: compound file: {} states {} bytes, its chain holds {}", path_, what, size, available);
    out.reserve(size);
    for (std::uint32_t s : sectors) out.append(sector(s, what));
    out.resize(size);
    return out;
}

std::vector<const CompoundFile::DirectoryEntry*> CompoundFile::root_children() const {
    std::vector<const DirectoryEntry*> out;
    std::vector<std::uint32_t> pending{directory_[0].child};
    std::vector<char> seen(directory_.size(), 0);
    while (!pending.empty()) {
        const std::uint32_t id = pending.back();
        pending.pop_back();
        if (id == kNoStream) continue;
        if (id >= directory_.size()) fail("{}: compound file: directory entry {} does not exist", path_, id);
        if (seen[id]) fail("{}: compound file: directory entry {} is reached twice (a cycle)", path_, id);
        seen[id] = 1;
        out.push_back(&directory_[id]);
        pending.push_back(directory_[id].left);
        pending.push_back(directory_[id].right);
    }
    return out;
}

std::vector<std::string> CompoundFile::stream_names() const {
    std::vector<std::string> names;
    for (const DirectoryEntry* e : root_children())
        if (e->type == kStream) names.push_back(e->name);
    std::sort(names.begin(), names.end());
    return names;
}

std::optional<std::string> CompoundFile::stream(std::string_view name) const {
    for (const DirectoryEntry* e : root_children()) {
        if (e->type != kStream || e->name != name) continue;
        if (e->size >= mini_cutoff_) return read_chain(e->start, e->size, "a stream");
        // A small stream lives in 64-byte sectors of the mini stream.
        std::string out;
        for (std::uint32_t s : chain(e->start, mini_fat_, "a mini stream chain")) {
            if ((std::uint64_t{s} + 1) * kMiniSectorBytes > mini_stream_.size())
                fail("{}: compound file: mini sector {} lies beyond the mini stream ({} bytes)", path_, s, mini_stream_.size());
            out.append(mini_stream_, std::size_t{s} * kMiniSectorBytes, kMiniSectorBytes);
        }
        if (e->size > out.size())
            fail("{}: compound file: stream '{}' states {} bytes, its mini chain holds {}", path_, printable(name), e->size, out.size());
        out.resize(e->size);
        return out;
    }
    return std::nullopt;
}

}  // namespace surfscatter::heightmap
