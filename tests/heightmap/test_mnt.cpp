// The MountainsMap reader (heightmap/mnt.hpp) and the compound files it opens (heightmap/compound_file.hpp):
// documents written here entry by entry (so the reader is covered in a plain clone), damaged ones (each one Error
// naming the file and the entry), and the real mnt-1.mnt of ../shared/data/realdata/heightmaps against its own
// header and independent figures, skipped with a message where the shared data are absent.
#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "height_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/compound_file.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/mnt.hpp"

namespace hm = surfscatter::heightmap;
namespace fs = std::filesystem;

namespace {

using surfscatter::heightmap::test::error_of;
using surfscatter::heightmap::test::write_bytes;

// Little-endian encoders.
std::string le(std::uint64_t v, int bytes) {
    std::string s;
    for (int i = 0; i < bytes; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
    return s;
}
std::string u8(std::uint8_t v) { return le(v, 1); }
std::string u32(std::uint32_t v) { return le(v, 4); }
std::string u64(std::uint64_t v) { return le(v, 8); }
std::string i32(std::int32_t v) { return le(static_cast<std::uint32_t>(v), 4); }
std::string f64(double v) { return le(std::bit_cast<std::uint64_t>(v), 8); }
std::string utf16(const std::string& ascii) {
    std::string s;
    for (char c : ascii) s += std::string{c, '\0'};
    return s;
}

// ---------------------------------------------------------------- a compound file ([MS-CFB], version 3)

// One stream in the root storage: in 512-byte sectors, or in the mini stream's 64-byte sectors below 4096 bytes.
// Sectors: 0 the FAT, 1 the directory, 2 the mini FAT (mini streams only), then the data.
std::string compound_file(const std::string& name, const std::string& stream) {
    constexpr std::uint32_t kFree = 0xffffffff, kEnd = 0xfffffffe, kFatSector = 0xfffffffd;
    const bool mini = stream.size() < 4096;
    std::string data = stream;
    const std::uint32_t mini_sectors = static_cast<std::uint32_t>((stream.size() + 63) / 64);
    if (mini) data.resize(64 * mini_sectors, '\0');
    const std::size_t mini_stream_size = data.size();
    data.resize((data.size() + 511) / 512 * 512, '\0');
    const std::uint32_t data_sectors = static_cast<std::uint32_t>(data.size() / 512);
    const std::uint32_t first = mini ? 3 : 2;

    std::string header("\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1", 8);
    header += std::string(16, '\0') + le(0x3e, 2) + le(3, 2) + le(0xfffe, 2) + le(9, 2) + le(6, 2) + std::string(6, '\0');
    header += u32(0) + u32(1) + u32(1) + u32(0) + u32(4096) + u32(mini ? 2 : kEnd) + u32(mini ? 1 : 0) + u32(kEnd) + u32(0);
    header += u32(0);  // the FAT in sector 0
    while (header.size() < 512) header += u32(kFree);

    std::vector<std::uint32_t> fat(128, kFree);
    fat[0] = kFatSector;
    fat[1] = kEnd;
    if (mini) fat[2] = kEnd;
    for (std::uint32_t i = 0; i < data_sectors; ++i) fat[first + i] = i + 1 < data_sectors ? first + i + 1 : kEnd;
    std::string fat_sector;
    for (std::uint32_t v : fat) fat_sector += u32(v);

    auto entry = [](const std::string& entry_name, std::uint8_t type, std::uint32_t child, std::uint32_t start,
                    std::uint64_t size) {
        std::string e = utf16(entry_name);
        e.resize(64, '\0');
        e += le(entry_name.empty() ? 0 : 2 * entry_name.size() + 2, 2) + u8(type) + u8(1);
        e += u32(kFree) + u32(kFree) + u32(child) + std::string(36, '\0') + u32(start) + u64(size);
        return e;
    };
    std::string directory = entry("Root Entry", 5, 1, mini ? first : kEnd, mini ? mini_stream_size : 0) +
                            entry(name, 2, kFree, mini ? 0 : first, stream.size());
    directory += entry("", 0, kFree, 0, 0) + entry("", 0, kFree, 0, 0);

    std::string mini_fat;
    if (mini) {
        for (std::uint32_t i = 0; i < 128; ++i) mini_fat += u32(i + 1 < mini_sectors ? i + 1 : i + 1 == mini_sectors ? kEnd : kFree);
    }
    return header + fat_sector + directory + mini_fat + data;
}

// ---------------------------------------------------------------- a MountainsMap document

std::string tlv(std::uint16_t tag, const std::string& data) { return le(tag, 2) + u64(data.size()) + data; }
std::string text(const std::string& ascii) { return std::string(1, '\x04').append(utf16(ascii)); }
std::string object(std::uint32_t class_number, const std::string& body) {
    return tlv(1, tlv(1, u32(class_number))) + (body.empty() ? "" : tlv(2, body));
}

// An axis scale: index (1 x, 2 y, 3 heights), step in `unit`, origin in `display` (`ratio` of them).
std::string scale(std::uint32_t index, double step, const std::string& unit, const std::string& display, double ratio,
                  double origin) {
    return tlv(0xffff, tlv(1, u32(index)) + tlv(2, text(index == 1 ? "X" : index == 2 ? "Y" : "Z"))) + tlv(1, f64(step)) +
           tlv(2, text(unit)) + tlv(3, text(display)) + tlv(4, f64(ratio)) + tlv(5, f64(origin)) + tlv(6, u32(1));
}

// An array in zlib blocks of `per_block` elements, written last block first (the real file's are out of order too).
std::string block_array(const std::string& bytes, std::size_t element, std::size_t per_block, bool drop_one = false) {
    std::vector<std::string> blocks;
    const std::size_t count = bytes.size() / element;
    for (std::size_t first = 0; first < count; first += per_block) {
        const std::size_t n = std::min(per_block, count - first);
        uLongf size = compressBound(static_cast<uLong>(n * element));
        std::string z(size, '\0');
        compress2(reinterpret_cast<Bytef*>(z.data()), &size, reinterpret_cast<const Bytef*>(bytes.data() + first * element),
                  static_cast<uLong>(n * element), 6);
        z.resize(size);
        blocks.push_back(u64(first) + u32(static_cast<std::uint32_t>(n)) + u32(static_cast<std::uint32_t>(size)) + z);
    }
    if (drop_one) blocks.erase(blocks.begin() + 1);
    std::string out = u64(bytes.size());
    for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) out += *it;
    return out;
}

std::string array_object(std::uint32_t class_number, std::size_t count, const std::string& blocks) {
    return object(class_number, tlv(1, u32(static_cast<std::uint32_t>(count))) + tlv(2, blocks));
}

struct Document {
    std::uint32_t nx = 40, ny = 30;
    double dx_um = 0.25, dy_um = 0.5;        // stated in um, origins in mm
    double x0_mm = 1.5, y0_mm = -2.0;
    double step_nm = 0.5, z0_um = 3.0;       // heights: count * step_nm (nm) + z0_um (um)
    std::vector<std::int32_t> counts;        // nx * ny
    std::vector<std::uint8_t> mask;          // nx * ny of 9 / 22, empty: none
    std::int32_t lowest = 0, highest = 0;    // the height axis's range (set from counts unless overridden)
    double z_ratio = 1000.0;                 // um per nm as the axis states it
    bool drop_block = false;
    bool with_surface = true;

    explicit Document(std::uint32_t nx_ = 40, std::uint32_t ny_ = 30) : nx(nx_), ny(ny_) {
        for (std::uint32_t i = 0; i < nx * ny; ++i)
            counts.push_back(static_cast<std::int32_t>((i * 2654435761u) % 200001u) - 100000);  // spread, both signs
        lowest = *std::min_element(counts.begin(), counts.end());
        highest = *std::max_element(counts.begin(), counts.end());
    }

    std::string bytes() const {
        std::string raw;
        for (std::int32_t c : counts) raw += i32(c);
        std::string grid = tlv(0xffff, tlv(0xffff, tlv(1, text("Channel A")))) +
                           tlv(1, tlv(0xffff, tlv(0xffff, scale(1, dx_um, "\xb5m", "mm", 1000.0, x0_mm)) + tlv(1, u32(nx)) +
                                                  tlv(2, u32(0)) + tlv(3, u32(nx - 1)))) +
                           tlv(2, tlv(0xffff, tlv(0xffff, scale(2, dy_um, "\xb5m", "mm", 1000.0, y0_mm)) + tlv(1, u32(ny)) +
                                                  tlv(2, u32(0)) + tlv(3, u32(ny - 1))));
        if (mask.empty()) {
            grid += tlv(3, object(0, ""));
        } else {
            std::string m((nx + 2) * (ny + 2), static_cast<char>(22));
            for (std::uint32_t iy = 0; iy < ny; ++iy)
                for (std::uint32_t ix = 0; ix < nx; ++ix) m[(iy + 1) * (nx + 2) + ix + 1] = static_cast<char>(mask[iy * nx + ix]);
            grid += tlv(3, object(9056, tlv(1, u32(nx)) + tlv(2, u32(ny)) +
                                            tlv(5, array_object(9048, m.size(), block_array(m, 1, 500)))));
        }
        const std::string measurement =
            tlv(0xffff, tlv(0xffff, grid) + tlv(1, array_object(9049, counts.size(), block_array(raw, 4, 333, drop_block))) +
                            tlv(2, tlv(0xffff, scale(3, step_nm, "nm", "\xb5m", z_ratio, z0_um)) + tlv(1, i32(lowest)) +
                                       tlv(2, i32(highest))));
        const std::string surface = tlv(0xffff, tlv(4, text("1 : Channel A"))) + tlv(1, object(9062, measurement));
        // A study object first (class 9300 here), then the surface, each preceded by its entry's size.
        std::string list;
        for (const std::string& o : {tlv(1, object(9300, tlv(1, u32(7)))), tlv(1, object(with_surface ? 9012 : 9301, surface))})
            list += u64(o.size()) + o;
        const std::string scoped = tlv(1, tlv(0xc8, tlv(1, u32(9))) + tlv(0x02bd, tlv(1, u8(2)) + tlv(2, tlv(1, list))));
        return compound_file("ScopedContents", u64(scoped.size()) + scoped);
    }
};

fs::path file_with(const std::string& name, const std::string& bytes) {
    const fs::path path = surfscatter::heightmap::test::temp_path("surfscatter_test_mnt", name);
    write_bytes(path, bytes);
    return path;
}

// Heights, spacing, origins and names as the document states them; read_height_map finds it by content.
TEST(Mnt, WrittenDocumentAsItStates) {
    const Document doc;
    const fs::path path = file_with("doc.mnt", doc.bytes());
    ASSERT_GT(doc.bytes().size(), 4096u + 512u);  // ScopedContents in regular sectors
    const hm::HeightMap map = hm::read_height_map(path, std::nullopt);
    ASSERT_EQ(map.nx(), 40u);
    ASSERT_EQ(map.ny(), 30u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 0.25);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 0.5);
    EXPECT_DOUBLE_EQ(map.offset_x, 1500.0);
    EXPECT_DOUBLE_EQ(map.offset_y, -2000.0);
    EXPECT_FALSE(map.has_invalid());
    for (std::size_t i = 0; i < map.size(); ++i) ASSERT_DOUBLE_EQ(map.heights()[i], doc.counts[i] * 0.5e-3 + 3.0) << i;
    EXPECT_EQ(map.title, "1 : Channel A");
    EXPECT_EQ(map.source.channel, "Channel A");
    EXPECT_EQ(map.source.reader, "native:mnt");
    EXPECT_DOUBLE_EQ(map.source.height_unit_um, 1e-3);
    // The stated spacing may be repeated, not contradicted.
    EXPECT_NO_THROW(hm::read_height_map(path, std::nullopt, 1e-3));
    EXPECT_NE(error_of([&] { hm::read_height_map(path, 0.3); }).find("--spacing 0.3 um contradicts the file"),
              std::string::npos);
}

// A small document's ScopedContents lives in the compound file's mini stream; its mask marks invalid points.
TEST(Mnt, MaskAndMiniStream) {
    Document doc(9, 8);
    doc.mask.assign(9 * 8, 9);
    doc.mask[0] = doc.mask[10] = doc.mask[71] = 22;
    doc.counts[10] = doc.highest + 5;  // a non-measured point's count may be anything
    const std::string bytes = doc.bytes();
    ASSERT_LT(bytes.size(), 4096u);
    const hm::HeightMap map = hm::read_mnt(file_with("mini.mnt", bytes));
    EXPECT_EQ(map.valid_count(), 9u * 8u - 3u);
    EXPECT_FALSE(map.valid(0, 0));
    EXPECT_FALSE(map.valid(1, 1));
    EXPECT_FALSE(map.valid(8, 7));
    EXPECT_TRUE(map.valid(2, 1));
    EXPECT_DOUBLE_EQ(map(2, 1), doc.counts[11] * 0.5e-3 + 3.0);
}

TEST(Mnt, DamagedDocumentsNameTheEntry) {
    auto error = [](const std::string& name, const Document& doc) {
        const fs::path path = file_with(name, doc.bytes());
        return error_of([&] { hm::read_mnt(path); });
    };
    Document gap;
    gap.drop_block = true;
    EXPECT_NE(error("gap.mnt", gap).find("the heights (entry '0001/02bd/0002/0001/0001/0002/0001/0002/ffff/0001/0002/0002'): "
                                         "its blocks leave out elements 333 to 666"),
              std::string::npos)
        << error("gap.mnt", gap);
    Document range;
    range.highest -= 1;
    EXPECT_NE(error("range.mnt", range).find("lies outside the range"), std::string::npos);
    Document ratio;
    ratio.z_ratio = 1.0;
    EXPECT_NE(error("ratio.mnt", ratio).find("the height axis states 1 nm per um, the units' names 1000"),
              std::string::npos)
        << error("ratio.mnt", ratio);
    Document mask(9, 8);
    mask.mask.assign(9 * 8, 9);
    mask.mask[5] = 3;
    EXPECT_NE(error("mask.mnt", mask).find("mask value 3 at column 5, row 0 is neither 9 (measured) nor 22"),
              std::string::npos);
    Document none;
    none.with_surface = false;
    EXPECT_NE(error("none.mnt", none).find("a MountainsMap document without a measured surface (object class 9012); "
                                           "its objects are of classes 9300, 9301"),
              std::string::npos);
    // Cut short: the compound file's chains leave the file.
    const std::string whole = Document().bytes();
    const fs::path cut = file_with("cut.mnt", whole.substr(0, whole.size() - 1024));
    EXPECT_NE(error_of([&] { hm::read_mnt(cut); }).find("cut.mnt: compound file: a stream is sector"), std::string::npos);
    // A compound file without the stream.
    const fs::path other = file_with("other.mnt", compound_file("Workbook", std::string(5000, 'x')));
    EXPECT_EQ(error_of([&] { hm::read_mnt(other); }),
              other.string() + ": a compound file without a ScopedContents stream (it holds Workbook): not a "
                               "MountainsMap document");
}

// ---------------------------------------------------------------- the real file

fs::path real_file(const std::string& name) {
    return fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / name;
}

// mnt-1.mnt (MountainsMap 9.2, a 10x objective) against its own header: the x and y axes state 960 and 600 points
// 1.8533931178310741 and 1.8545542570951588 um apart (origins 10.3595 and 156.152 mm), no mask (the mask object has
// class 0); the height axis states 0.0001 nm per count, origin 50.631545534551144 um, counts from -12629352 to
// 9608235, which the decoded counts reach exactly (the reader requires them inside). The same grid, spacing, range and
// origin are what SurfaceTopography's test_mnt.py asserts. The rms heights are scripts/height-format-figures's, which
// decodes the counts with Python's zlib without surfscatter: 2.456021067968e+01 nm, 2.436724891279e+01 nm after a
// plane.
TEST(Mnt, RealFileAsItsHeaderStates) {
    const fs::path path = real_file("mnt-1.mnt");
    if (!fs::exists(path)) GTEST_SKIP() << path << " is absent (../shared/data/realdata): the real-file check is skipped";
    const hm::HeightMap map = hm::read_height_map(path, std::nullopt);
    EXPECT_EQ(map.nx(), 960u);
    EXPECT_EQ(map.ny(), 600u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 1.8533931178310741);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 1.8545542570951588);
    EXPECT_NEAR(map.offset_x, 10359.5, 1e-9);
    EXPECT_NEAR(map.offset_y, 156152.0, 1e-8);
    EXPECT_FALSE(map.has_invalid());
    const auto [lo, hi] = std::minmax_element(map.heights().begin(), map.heights().end());
    EXPECT_NEAR(*lo, 50.631545534551144 - 12629352e-7, 1e-12);
    EXPECT_NEAR(*hi, 50.631545534551144 + 9608235e-7, 1e-12);
    EXPECT_NEAR(hm::rms_height(map, hm::Form::none), 2.456021067968e-02, 1e-14);
    EXPECT_NEAR(hm::rms_height(map, hm::Form::plane), 2.436724891279e-02, 1e-14);
    EXPECT_EQ(map.title, "1 : A48_10x_P1");
    EXPECT_EQ(map.source.channel, "A48_10x_P1");
    EXPECT_DOUBLE_EQ(map.source.height_unit_um, 1e-3);
    EXPECT_TRUE(map.source.warnings.empty());
}

}  // namespace
