#pragma once
// Bounded little-endian reading of a binary instrument file held in memory, shared by the native binary readers
// (TMD, NMS, OPDx, MNT). Every read is checked against the end of the bytes: a short file is an Error naming the
// file, the byte offset and what was being read, never a read past the end. Not a public interface.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace surfscatter::heightmap::binary {

class Cursor {
public:
    // `bytes` must outlive the cursor; `path` names the file in messages.
    Cursor(std::string_view bytes, std::string path, std::size_t position = 0);

    std::uint8_t u8(const char* what);
    std::uint16_t u16(const char* what);
    std::uint32_t u32(const char* what);
    std::uint64_t u64(const char* what);
    float f32(const char* what);
    double f64(const char* what);
    // The next `count` bytes (Error if fewer are left).
    std::string_view bytes(std::size_t count, const char* what);
    void skip(std::size_t count, const char* what) { bytes(count, what); }
    void seek(std::size_t position, const char* what);

    std::size_t position() const { return position_; }
    std::size_t remaining() const { return bytes_.size() - position_; }
    bool at_end() const { return position_ == bytes_.size(); }
    const std::string& path() const { return path_; }

private:
    std::string_view bytes_;
    std::string path_;
    std::size_t position_;
};

// Little-endian values at a byte offset (the caller has checked the bounds).
std::uint16_t load_u16(const char* p);
std::uint32_t load_u32(const char* p);
std::uint64_t load_u64(const char* p);
float load_f32(const char* p);
double load_f64(const char* p);

// Throws Error "<path>: <what> = <nx> x <ny> is larger than any height map this reads (2^32 samples)" unless the
// grid is at most 2^20 points a side and 2^32 in all (docs/RELIABILITY.md): checked before any allocation.
void require_grid_size(const std::string& path, std::uint64_t nx, std::uint64_t ny, const char* what);

}  // namespace surfscatter::heightmap::binary
