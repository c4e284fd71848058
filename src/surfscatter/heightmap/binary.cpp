#include "surfscatter/heightmap/binary.hpp"

#include <bit>
#include <cstring>
#include <utility>

#include "surfscatter/core/error.hpp"

namespace surfscatter::heightmap::binary {

std::uint16_t load_u16(const char* p) {
    unsigned char b[2];
    std::memcpy(b, p, 2);
    return static_cast<std::uint16_t>(b[0] | b[1] << 8);
}

std::uint32_t load_u32(const char* p) {
    unsigned char b[4];
    std::memcpy(b, p, 4);
    return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
           static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

std::uint64_t load_u64(const char* p) {
    return static_cast<std::uint64_t>(load_u32(p)) | static_cast<std::uint64_t>(load_u32(p + 4)) << 32;
}

float load_f32(const char* p) { return std::bit_cast<float>(load_u32(p)); }
double load_f64(const char* p) { return std::bit_cast<double>(load_u64(p)); }

Cursor::Cursor(std::string_view bytes, std::string path, std::size_t position)
    : bytes_(bytes), path_(std::move(path)), position_(position) {
    if (position_ > bytes_.size()) fail("{}: file truncated: {} bytes, data expected at byte {}", path_, bytes_.size(), position_);
}

std::string_view Cursor::bytes(std::size_t count, const char* what) {
    if (count > remaining())
        fail("{}: file truncated at byte {} reading {} ({} bytes needed, {} left)", path_, position_, what, count,
             remaining());
    const std::string_view out = bytes_.substr(position_, count);
    position_ += count;
    return out;
}

void Cursor::seek(std::size_t position, const char* what) {
    if (position > bytes_.size())
        fail("{}: {} at byte {} lies beyond the end of the file ({} bytes)", path_, what, position, bytes_.size());
    position_ = position;
}

std::uint8_t Cursor::u8(const char* what) { return static_cast<std::uint8_t>(bytes(1, what)[0]); }
std::uint16_t Cursor::u16(const char* what) { return load_u16(bytes(2, what).data()); }
std::uint32_t Cursor::u32(const char* what) { return load_u32(bytes(4, what).data()); }
std::uint64_t Cursor::u64(const char* what) { return load_u64(bytes(8, what).data()); }
float Cursor::f32(const char* what) { return load_f32(bytes(4, what).data()); }
double Cursor::f64(const char* what) { return load_f64(bytes(8, what).data()); }

void require_grid_size(const std::string& path, std::uint64_t nx, std::uint64_t ny, const char* what) {
    constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20;
    if (nx == 0 || ny == 0) fail("{}: {} = {} x {} holds no points", path, what, nx, ny);
    if (nx > kMaxSide || ny > kMaxSide || nx * ny > (std::uint64_t{1} << 32))
        fail("{}: {} = {} x {} is larger than any height map this reads (2^32 samples)", path, what, nx, ny);
}

}  // namespace surfscatter::heightmap::binary
