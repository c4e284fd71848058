// The native readers of TMD, NMS, OPDx and HFM files (heightmap/tmd, nms, opdx, hfm): small files written here byte
// by byte (so the parsers are covered without the shared data), bad files (each one Error naming the file and what
// is wrong), and the real files in ../shared/data/realdata/heightmaps against their own headers, SurfaceTopography's
// test-suite figures and rms heights computed from the raw bytes by scripts/height-format-figures (numpy).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "height_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/hfm.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/nms.hpp"
#include "surfscatter/heightmap/opdx.hpp"
#include "surfscatter/heightmap/tmd.hpp"

namespace hm = surfscatter::heightmap;
namespace fs = std::filesystem;

namespace {

using surfscatter::heightmap::test::error_of;
using surfscatter::heightmap::test::write_bytes;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

fs::path temp_path(const std::string& name) {
    return surfscatter::heightmap::test::temp_path("surfscatter_test_height_formats", name);
}

fs::path real_file(const std::string& name) {
    return fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / name;
}

// Little-endian encoders.
void put_u16(std::string& s, std::uint16_t v) {
    for (int i = 0; i < 2; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}
void put_u32(std::string& s, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}
void put_u64(std::string& s, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}
void put_f32(std::string& s, float v) { put_u32(s, std::bit_cast<std::uint32_t>(v)); }
void put_f64(std::string& s, double v) { put_u64(s, std::bit_cast<std::uint64_t>(v)); }

// Writes `bytes` to a scratch file and returns its path.
fs::path file_with(const std::string& name, const std::string& bytes) {
    const fs::path path = temp_path(name);
    write_bytes(path, bytes);
    return path;
}

// The mean-removed rms of a profile's valid heights (computed here, not by the library).
double profile_rms(const hm::LineScan& scan) {
    double sum = 0.0, sum2 = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < scan.size(); ++i)
        if (scan.validity.empty() || scan.validity[i]) sum += scan.heights_um[i], ++n;
    const double mean = sum / static_cast<double>(n);
    for (std::size_t i = 0; i < scan.size(); ++i)
        if (scan.validity.empty() || scan.validity[i]) sum2 += (scan.heights_um[i] - mean) * (scan.heights_um[i] - mean);
    return std::sqrt(sum2 / static_cast<double>(n));
}

// ---------------------------------------------------------------- TMD

// A TMD file: lengths in mm, heights (mm) row by row.
std::string tmd_bytes(std::uint32_t nx, std::uint32_t ny, float length_x, float length_y,
                      const std::vector<float>& heights, const std::string& comment = "Created by TrueMap v6\r\n") {
    std::string s("Binary TrueMap Data File v2.0\r\n\0", 32);
    s += comment;
    s += '\0';
    put_u32(s, nx);
    put_u32(s, ny);
    put_f32(s, length_x);
    put_f32(s, length_y);
    put_f32(s, 0.5f);
    put_f32(s, -0.25f);
    for (float h : heights) put_f32(s, h);
    return s;
}

std::vector<float> ramp(std::size_t n, float scale) {
    std::vector<float> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = scale * static_cast<float>((i * 7919) % 101) - 0.3f;
    return v;
}

TEST(HeightFormats, TmdSyntheticFileReadsInMillimetres) {
    std::vector<float> heights = ramp(12 * 9, 1e-3f);
    heights[13] = std::numeric_limits<float>::quiet_NaN();
    const fs::path path = file_with("a.tmd", tmd_bytes(12, 9, 2.4f, 0.9f, heights));
    const hm::HeightMap map = hm::read_height_map(path, std::nullopt);
    EXPECT_EQ(map.nx(), 12u);
    EXPECT_EQ(map.ny(), 9u);
    EXPECT_NEAR(map.spacing_x(), 2400.0 / 12, 1e-4);  // float32 2.4 mm
    EXPECT_NEAR(map.spacing_y(), 900.0 / 9, 1e-4);
    EXPECT_NEAR(map.offset_x, 500.0, 1e-9);
    EXPECT_NEAR(map.offset_y, -250.0, 1e-9);
    EXPECT_EQ(map.valid_count(), 12u * 9u - 1u);
    EXPECT_FALSE(map.valid(1, 1));
    EXPECT_DOUBLE_EQ(map(5, 3), static_cast<double>(heights[3 * 12 + 5]) * 1e3);
    EXPECT_EQ(map.source.reader, "native:tmd");
    EXPECT_EQ(map.source.height_unit_um, 1e3);
    EXPECT_EQ(map.title, "Created by TrueMap v6");
    // An empty comment (GelSight's writer) is a comment too.
    EXPECT_EQ(hm::read_height_map(file_with("b.tmd", tmd_bytes(12, 9, 2.4f, 0.9f, heights, "")), std::nullopt).nx(), 12u);
}

TEST(HeightFormats, TmdBadFilesNameWhatIsWrong) {
    const std::string good = tmd_bytes(12, 9, 2.4f, 0.9f, ramp(12 * 9, 1e-3f));
    const fs::path truncated = file_with("truncated.tmd", good.substr(0, good.size() - 3));
    EXPECT_NE(error_of([&] { hm::read_height_map(truncated, std::nullopt); }).find(truncated.string() + ": TMD columns x rows = 12 x 9 needs 432 bytes"),
              std::string::npos);
    EXPECT_NE(error_of([&] { hm::read_height_map(truncated, std::nullopt); }).find("(truncated)"), std::string::npos);
    const fs::path header_only = file_with("header.tmd", good.substr(0, 58));
    EXPECT_NE(error_of([&] { hm::read_height_map(header_only, std::nullopt); }).find("file truncated at byte 56 reading the number of columns"),
              std::string::npos);
    const fs::path huge = file_with("huge.tmd", tmd_bytes(1u << 20, 1u << 20, 1.0f, 1.0f, {}));
    EXPECT_NE(error_of([&] { hm::read_height_map(huge, std::nullopt); }).find("larger than any height map this reads"),
              std::string::npos);
    const fs::path negative = file_with("negative.tmd", tmd_bytes(12, 9, -2.4f, 0.9f, ramp(12 * 9, 1e-3f)));
    EXPECT_NE(error_of([&] { hm::read_height_map(negative, std::nullopt); }).find("lengths -2.4"), std::string::npos);
    std::vector<float> infinite = ramp(12 * 9, 1e-3f);
    infinite[20] = std::numeric_limits<float>::infinity();
    const fs::path inf = file_with("inf.tmd", tmd_bytes(12, 9, 2.4f, 0.9f, infinite));
    EXPECT_NE(error_of([&] { hm::read_height_map(inf, std::nullopt); }).find("height 20 (column 8, row 1) is infinite"),
              std::string::npos);
    std::string no_nul = good.substr(0, 32) + std::string(400, 'x');
    const fs::path garbage = file_with("garbage.tmd", no_nul);
    EXPECT_NE(error_of([&] { hm::read_height_map(garbage, std::nullopt); }).find("comment after the first line is not NUL-terminated"),
              std::string::npos);
    // The stated spacing may be repeated, not contradicted.
    const fs::path path = file_with("ok.tmd", good);
    EXPECT_NE(error_of([&] { hm::read_height_map(path, 1.0); }).find("--spacing 1 um contradicts the file"), std::string::npos);
}

// ---------------------------------------------------------------- NMS

std::string nms_bytes(std::uint32_t nx, std::uint32_t ny, double zmin, double zmax, double dx_nm, double dy_nm,
                      const std::vector<std::uint16_t>& q, bool intensity, std::uint32_t bytes_per_height = 2,
                      const std::string& name = "OM_MS_2.0") {
    constexpr std::size_t kHeader = 3468;
    std::string s(kHeader, '\0');
    auto at = [&](std::size_t offset, const std::string& field) { s.replace(offset, field.size(), field); };
    std::string f;
    put_f64(f, zmin);
    put_f64(f, zmax);
    at(16, f);
    at(32, name);
    at(52, "Confocal Height Image");
    f.clear();
    put_u32(f, kHeader);
    put_u32(f, bytes_per_height);
    at(1352, f);
    f.clear();
    put_u32(f, nx);
    put_u32(f, ny);
    put_f64(f, dx_nm);
    put_f64(f, dy_nm);
    at(1368, f);
    for (std::uint16_t v : q) put_u16(s, v);
    if (intensity) s += std::string(q.size(), '\x80');
    return s;
}

std::vector<std::uint16_t> codes(std::size_t n) {
    std::vector<std::uint16_t> q(n);
    for (std::size_t i = 0; i < n; ++i) q[i] = static_cast<std::uint16_t>((i * 40503u) % 65536u);
    q[0] = 0;
    q[n - 1] = 65535;
    return q;
}

TEST(HeightFormats, NmsSyntheticFileScalesCodesToTheStatedRange) {
    const std::vector<std::uint16_t> q = codes(10 * 16);
    for (bool intensity : {false, true}) {
        const fs::path path = file_with(intensity ? "b.nms" : "a.nms", nms_bytes(10, 16, -1.5, 2.5, 250.0, 500.0, q, intensity));
        const hm::HeightMap map = hm::read_height_map(path, std::nullopt);
        EXPECT_EQ(map.nx(), 10u);
        EXPECT_EQ(map.ny(), 16u);
        EXPECT_DOUBLE_EQ(map.spacing_x(), 0.25);  // nm -> um
        EXPECT_DOUBLE_EQ(map.spacing_y(), 0.5);
        EXPECT_DOUBLE_EQ(map(0, 0), -1.5);
        EXPECT_DOUBLE_EQ(map(9, 15), 2.5);
        EXPECT_NEAR(map(3, 2), -1.5 + 4.0 * q[23] / 65535.0, 1e-15);
        EXPECT_FALSE(map.has_invalid());
        EXPECT_EQ(map.source.reader, "native:nms");
        EXPECT_EQ(map.title, "Confocal Height Image");
        EXPECT_EQ(map.source.channel, "Confocal Height Image");
    }
}

TEST(HeightFormats, NmsBadFilesNameWhatIsWrong) {
    const std::vector<std::uint16_t> q = codes(10 * 16);
    const std::string good = nms_bytes(10, 16, -1.5, 2.5, 250.0, 500.0, q, true);
    const fs::path truncated = file_with("truncated.nms", good.substr(0, good.size() - 1));
    EXPECT_NE(error_of([&] { hm::read_height_map(truncated, std::nullopt); })
                  .find(truncated.string() + ": NMS nx x ny = 10 x 16 at byte 3468 needs 3788 bytes (heights) or 3948"),
              std::string::npos);
    const fs::path short_header = file_with("header.nms", good.substr(0, 1000));
    EXPECT_NE(error_of([&] { hm::read_height_map(short_header, std::nullopt); }).find("NMS header truncated: 1000 bytes"),
              std::string::npos);
    const fs::path wide = file_with("wide.nms", nms_bytes(10, 16, -1.5, 2.5, 250.0, 500.0, q, true, 4));
    EXPECT_NE(error_of([&] { hm::read_height_map(wide, std::nullopt); }).find("heights of 4 bytes are not supported"),
              std::string::npos);
    const fs::path version = file_with("version.nms", nms_bytes(10, 16, -1.5, 2.5, 250.0, 500.0, q, true, 2, "OM_MS_3.1"));
    EXPECT_NE(error_of([&] { hm::read_height_map(version, std::nullopt); }).find("NMS format 'OM_MS_3.1' is not supported"),
              std::string::npos);
    const fs::path spacing = file_with("spacing.nms", nms_bytes(10, 16, -1.5, 2.5, 0.0, 500.0, q, true));
    EXPECT_NE(error_of([&] { hm::read_height_map(spacing, std::nullopt); }).find("dx = 0 nm"), std::string::npos);
    const fs::path range = file_with("range.nms", nms_bytes(10, 16, 2.5, kNaN, 250.0, 500.0, q, true));
    EXPECT_NE(error_of([&] { hm::read_height_map(range, std::nullopt); }).find("is not a range"), std::string::npos);
    const fs::path huge = file_with("huge.nms", nms_bytes(1u << 17, 1u << 17, 0.0, 1.0, 1.0, 1.0, {}, false));
    EXPECT_NE(error_of([&] { hm::read_height_map(huge, std::nullopt); }).find("larger than any height map this reads"),
              std::string::npos);
}

// ---------------------------------------------------------------- OPDx

// Items of an OPDx file: a 4-byte-length name, a type byte, the payload.
std::string name_of(const std::string& name) {
    std::string s;
    put_u32(s, static_cast<std::uint32_t>(name.size()));
    return s + name;
}
std::string varlen(std::size_t n) {
    std::string s;
    if (n < 256) {
        s += '\x01';
        s += static_cast<char>(n);
    } else {
        s += '\x04';
        put_u32(s, static_cast<std::uint32_t>(n));
    }
    return s;
}
std::string container(const std::string& name, const std::string& items) {
    const std::string body = items + name_of("") + '\x7f' + std::string(2, '\0');
    return name_of(name) + '\x7d' + varlen(body.size()) + body;
}
std::string string_item(const std::string& name, const std::string& value) {
    return name_of(name) + '\x12' + varlen(value.size()) + value;
}
std::string uint32_item(const std::string& name, std::uint32_t value) {
    std::string s = name_of(name) + '\x07';
    put_u32(s, value);
    return s;
}
std::string quantity(const std::string& name, double value, const std::string& symbol) {
    std::string body;
    put_f64(body, value);
    body += name_of("Length") + name_of(symbol);
    return name_of(name) + '\x13' + varlen(body.size()) + body;
}
std::string string_list(const std::string& name, const std::vector<std::string>& values) {
    std::string body;
    for (const auto& v : values) body += name_of(v);
    return name_of(name) + '\x42' + name_of("StringList") + varlen(body.size()) + body;
}
std::string double_array(const std::string& name, const std::vector<double>& values) {
    std::string body(5, '\0');
    for (double v : values) put_f64(body, v);
    return name_of(name) + '\x40' + name_of("DoubleArray") + varlen(body.size()) + body;
}
std::string matrix(const std::string& name, std::uint32_t rows, std::uint32_t columns, const std::vector<float>& values) {
    std::string s = name_of(name) + '\x00' + name_of("Matrix");
    put_u32(s, 1);
    s += name_of("Height");
    std::string body;
    put_u32(body, rows);
    put_u32(body, columns);
    for (float v : values) put_f32(body, v);
    return s + varlen(body.size()) + body;
}
const std::string kOpdxMagic("VCA DATA\x01\x00\x00\x55", 12);

std::string opdx_map(std::uint32_t nx, std::uint32_t ny, const std::vector<float>& values, std::uint32_t matrix_rows) {
    return kOpdxMagic +
           container("2D_Data", container("Raw", uint32_item("Dimension1Points", ny) + uint32_item("Dimension2Points", nx) +
                                                     quantity("Dimension1Extent", 0.05, "mm") +
                                                     quantity("Dimension2Extent", 60.0, "\xc2\xb5m") +
                                                     quantity("DataScale", 2.0, "nm") +
                                                     matrix("Matrix", matrix_rows, nx, values))) +
           container("MetaData", string_item("DataKind", "Surface Height") + string_item("PrimaryData2D", "Raw"));
}

std::string opdx_profile(const std::vector<double>& values, std::uint32_t points) {
    return kOpdxMagic +
           container("1D_Data", container("Raw", uint32_item("NumPoints", points) + quantity("Extent", 100.0, "um") +
                                                     quantity("DataScale", 0.5, "um") + double_array("Array", values))) +
           container("MetaData", string_item("DataKind", "Surface Profile") +
                                     container("1D_Channels", string_list("Height", {"Raw"})));
}

TEST(HeightFormats, OpdxSyntheticAreaMapAndProfile) {
    std::vector<float> values = ramp(12 * 10, 1.0f);
    values[7] = std::numeric_limits<float>::quiet_NaN();
    const fs::path map_path = file_with("map.opdx", opdx_map(12, 10, values, 10));
    const hm::HeightMap map = hm::read_height_map(map_path, std::nullopt);
    EXPECT_EQ(map.nx(), 12u);
    EXPECT_EQ(map.ny(), 10u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 5.0);  // 60 um / 12
    EXPECT_DOUBLE_EQ(map.spacing_y(), 5.0);  // 0.05 mm / 10
    EXPECT_DOUBLE_EQ(map(3, 2), static_cast<double>(values[27]) * 2e-3);
    EXPECT_FALSE(map.valid(7, 0));
    EXPECT_EQ(map.valid_count(), 119u);
    EXPECT_EQ(map.source.reader, "native:opdx");
    EXPECT_EQ(map.source.channel, "Raw");
    EXPECT_DOUBLE_EQ(map.source.height_unit_um, 2e-3);

    std::vector<double> profile(41);
    for (std::size_t i = 0; i < profile.size(); ++i) profile[i] = std::sin(0.3 * static_cast<double>(i));
    const fs::path profile_path = file_with("profile.opdx", opdx_profile(profile, 41));
    const auto data = hm::read_opdx(profile_path);
    ASSERT_TRUE(std::holds_alternative<hm::LineScan>(data));
    const auto& scan = std::get<hm::LineScan>(data);
    EXPECT_EQ(scan.size(), 41u);
    EXPECT_DOUBLE_EQ(scan.spacing_um, 2.5);  // Extent 100 um from the first point to the last
    EXPECT_DOUBLE_EQ(scan.heights_um[5], 0.5 * std::sin(1.5));
    EXPECT_EQ(error_of([&] { hm::read_height_map(profile_path, std::nullopt); }),
              profile_path.string() +
                  ": a profile (Bruker OPDx (.opdx), stylus profile: one line of 41 points 2.5 um apart, 100 um long, "
                  "100 % valid), not a height map: the scattering models need heights over an area (x and y)");
}

TEST(HeightFormats, OpdxBadFilesNameWhatIsWrong) {
    const std::vector<float> values = ramp(12 * 10, 1.0f);
    const fs::path rows = file_with("rows.opdx", opdx_map(12, 10, values, 11));
    EXPECT_NE(error_of([&] { hm::read_height_map(rows, std::nullopt); })
                  .find("OPDx /2D_Data/Raw/Matrix holds 12 x 11 points in 480 bytes, the channel states 12 x 10"),
              std::string::npos);
    const std::string good = opdx_map(12, 10, values, 10);
    const fs::path truncated = file_with("truncated.opdx", good.substr(0, good.size() / 2));
    EXPECT_NE(error_of([&] { hm::read_height_map(truncated, std::nullopt); }).find("runs past the end of the file"),
              std::string::npos);
    const fs::path unknown = file_with("unknown.opdx", kOpdxMagic + name_of("Odd") + '\x33' + std::string(8, '\0'));
    EXPECT_NE(error_of([&] { hm::read_height_map(unknown, std::nullopt); }).find("OPDx item '/Odd' at byte 19 has unknown type 0x33"),
              std::string::npos);
    const fs::path no_kind = file_with("nokind.opdx", kOpdxMagic + container("MetaData", string_item("Other", "x")));
    EXPECT_NE(error_of([&] { hm::read_height_map(no_kind, std::nullopt); }).find("OPDx item '/MetaData/DataKind' is missing"),
              std::string::npos);
    const fs::path points = file_with("points.opdx", opdx_profile(std::vector<double>(40, 1.0), 41));
    EXPECT_NE(error_of([&] { hm::read_height_map(points, std::nullopt); }).find("Array holds 325 bytes, NumPoints = 41 needs 333"),
              std::string::npos);
    std::string deep = string_item("DataKind", "Surface Height");
    for (int i = 0; i < 40; ++i) deep = container("c", deep);
    const fs::path nested = file_with("nested.opdx", kOpdxMagic + deep);
    EXPECT_NE(error_of([&] { hm::read_height_map(nested, std::nullopt); }).find("nested deeper than 32"), std::string::npos);
    const fs::path length_size = file_with("varlen.opdx", kOpdxMagic + name_of("S") + '\x12' + '\x03' + std::string(8, 'a'));
    EXPECT_NE(error_of([&] { hm::read_height_map(length_size, std::nullopt); }).find("a length of 3 bytes (1, 2 or 4 expected)"),
              std::string::npos);
}

// ---------------------------------------------------------------- HFM

TEST(HeightFormats, HfmSyntheticProfileIsReadAndRefusedAsAMap) {
    const fs::path path = file_with("a.hfm", "X;Y;valid\r\n[mm];[um];[1/0]\r\n1.0000;0.5;1\r\n1.0010;0.7;1\r\n"
                                             "1.0020;9.9;0\r\n1.0030;0.1;1\r\n");
    const hm::LineScan scan = hm::read_hfm(path);
    EXPECT_EQ(scan.size(), 4u);
    EXPECT_NEAR(scan.spacing_um, 1.0, 1e-9);
    EXPECT_DOUBLE_EQ(scan.heights_um[1], 0.7);
    EXPECT_EQ(scan.valid_count(), 3u);
    EXPECT_EQ(scan.heights_um[2], 0.0);
    EXPECT_EQ(scan.source.height_unit_um, 1.0);
    EXPECT_EQ(error_of([&] { hm::read_height_map(path, std::nullopt); }),
              path.string() + ": a profile (HFM profile export (.hfm): one line of 4 points 1 um apart, 3 um long, 75 % "
                              "valid), not a height map: the scattering models need heights over an area (x and y)");
}

TEST(HeightFormats, HfmBadFilesNameTheLine) {
    auto error = [](const std::string& name, const std::string& text) {
        const fs::path path = file_with(name, text);
        return error_of([&] { hm::read_hfm(path); });
    };
    EXPECT_NE(error("step.hfm", "X;Y;valid\n[mm];[mm];[1/0]\n1.0;0;1\n1.1;0;1\n1.3;0;1\n")
                  .find("step.hfm:4: x step 0.1 differs from the mean step 0.15 by more than 1 %"),
              std::string::npos);
    EXPECT_NE(error("unit.hfm", "X;Y;valid\n[in];[mm];[1/0]\n1.0;0;1\n").find("unit.hfm:2: the unit of x '[in]' is not a length unit"),
              std::string::npos);
    EXPECT_NE(error("flag.hfm", "X;Y;valid\n[mm];[mm];[1/0]\n1.0;0;1\n1.1;0;yes\n").find("flag.hfm:4: valid flag 'yes'"),
              std::string::npos);
    EXPECT_NE(error("ragged.hfm", "X;Y;valid\n[mm];[mm];[1/0]\n1.0;0;1\n1.1;0\n").find("ragged.hfm:4: 2 fields"),
              std::string::npos);
    EXPECT_NE(error("number.hfm", "X;Y;valid\n[mm];[mm];[1/0]\n1.0;0;1\n1.1;nan;1\n").find("number.hfm:4: height 'nan' is not a finite number"),
              std::string::npos);
    EXPECT_NE(error("empty.hfm", "X;Y;valid\n[mm];[mm];[1/0]\n").find("0 points: a profile needs at least 2"), std::string::npos);
}

// ---------------------------------------------------------------- the real files

// tmd-1.tmd: its header states 300 x 300 points over 18.9566 x 18.9566 mm (float32: 18.956600189208984), the figure
// SurfaceTopography's test_tmd.py asserts to 1e-3; heights from 0 to below 1 mm as it asserts. The rms heights are
// scripts/height-format-figures's from the raw bytes (numpy): 7.434134067352e+01 um, 7.434087951791e+01 um after a
// plane.
TEST(HeightFormats, RealTmdFileAsItsHeaderStates) {
    const hm::HeightMap map = hm::read_height_map(real_file("tmd-1.tmd"), std::nullopt);
    EXPECT_EQ(map.nx(), 300u);
    EXPECT_EQ(map.ny(), 300u);
    EXPECT_DOUBLE_EQ(map.width(), 18956.600189208984);
    EXPECT_DOUBLE_EQ(map.height(), 18956.600189208984);
    EXPECT_FALSE(map.has_invalid());
    EXPECT_NEAR(hm::rms_height(map, hm::Form::none), 74.34134067352, 1e-9);
    EXPECT_NEAR(hm::rms_height(map, hm::Form::plane), 74.34087951791, 1e-9);
    double lo = 1e300, hi = -1e300;
    for (double h : map.heights()) lo = std::min(lo, h), hi = std::max(hi, h);
    EXPECT_GE(lo, 0.0);
    EXPECT_LT(hi, 1000.0);
    EXPECT_EQ(map.source.reader, "native:tmd");
}

// nms-1.nms: 512 x 512 points (SurfaceTopography's test_nms.py), 312.49999 nm apart (a 160 um confocal field),
// heights 2.689 to 6.007 um; rms from scripts/height-format-figures: 7.187076315e-01 um (a tilted
// sample), 3.351440318e-02 um after a plane (7.187076314682e-01 and 3.351440318403e-02 to 13 digits).
TEST(HeightFormats, RealNmsFileAsItsHeaderStates) {
    const hm::HeightMap map = hm::read_height_map(real_file("nms-1.nms"), std::nullopt);
    EXPECT_EQ(map.nx(), 512u);
    EXPECT_EQ(map.ny(), 512u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 0.3124999911618964);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 0.3124999911618964);
    EXPECT_FALSE(map.has_invalid());
    EXPECT_NEAR(hm::rms_height(map, hm::Form::none), 7.187076314682e-01, 1e-12);
    EXPECT_NEAR(hm::rms_height(map, hm::Form::plane), 3.351440318403e-02, 1e-13);
    EXPECT_EQ(map.source.reader, "native:nms");
}

// opdx-3.opdx: a Dektak stylus profile of 3001 points; SurfaceTopography's test_opdx.py compares it with
// opdx-3.txt, whose first and last heights are 1.3718306e-09 m and 1.4412931e-08 m, and whose x runs from 0 to
// 4.9966689e-05 m in steps of 1.6655563e-08 m. Its rms height, 5.307508577130e-03 um, is
// scripts/height-format-figures's from the raw doubles times DataScale (numpy).
TEST(HeightFormats, RealOpdxFileIsAProfile) {
    const auto data = hm::read_opdx(real_file("opdx-3.opdx"));
    ASSERT_TRUE(std::holds_alternative<hm::LineScan>(data));
    const auto& scan = std::get<hm::LineScan>(data);
    EXPECT_EQ(scan.size(), 3001u);
    EXPECT_NEAR(scan.spacing_um, 1.6655563e-2, 0.5e-9);
    EXPECT_NEAR(scan.heights_um.front(), 1.3718306e-3, 0.5e-10);
    EXPECT_NEAR(scan.heights_um.back(), 1.4412931e-2, 0.5e-9);
    EXPECT_EQ(scan.valid_count(), 3001u);
    EXPECT_NEAR(profile_rms(scan), 5.307508577130e-03, 1e-14);
    const std::string error = error_of([] { hm::read_height_map(real_file("opdx-3.opdx"), std::nullopt); });
    EXPECT_NE(error.find("a profile (Bruker OPDx (.opdx), stylus profile: one line of 3001 points"), std::string::npos);
}

// hfm-1.hfm: 9600 points 0.0005 mm apart, all valid (its third column); rms of the heights 9.056882243861e-01 um from
// scripts/height-format-figures.
TEST(HeightFormats, RealHfmFileIsAProfile) {
    const hm::LineScan scan = hm::read_hfm(real_file("hfm-1.hfm"));
    EXPECT_EQ(scan.size(), 9600u);
    EXPECT_NEAR(scan.spacing_um, 0.5, 1e-9);
    EXPECT_EQ(scan.valid_count(), 9600u);
    EXPECT_NEAR(profile_rms(scan), 9.056882243861e-01, 1e-12);
    const std::string error = error_of([] { hm::read_height_map(real_file("hfm-1.hfm"), std::nullopt); });
    EXPECT_NE(error.find("one line of 9600 points 0.5 um apart, 4799.5 um long, 100 % valid"), std::string::npos);
}

}  // namespace
