// Instrument files through read_height_map: SDF (text and binary), X3P (standard, subfolder, ISO5436 root,
// inline DataList; every Z data type; masks and NaN), .gwy through the Gwyddion library, bad files, and the real
// instrument files in ../shared/data/realdata/heightmaps with the figures their own test suites assert.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include "zip_archive.hpp"

#include "height_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/gwyddion_file.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/x3p.hpp"

namespace hm = surfscatter::heightmap;
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kNx = 20, kNy = 14;
constexpr double kDxM = 6.25e-7, kDyM = 5e-7;  // metres
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using surfscatter::heightmap::test::error_of;
using surfscatter::heightmap::test::write_bytes;

fs::path temp_path(const std::string& name) {
    return surfscatter::heightmap::test::temp_path("surfscatter_test_height_files", name);
}

// The test surface, in metres: a few nanometres of ramps, representable exactly as int16 multiples of 0.1 nm.
double height_m(std::size_t ix, std::size_t iy) { return 1e-10 * static_cast<double>((ix * 7 + iy * 13) % 50) - 2e-9; }

template <typename T>
std::string little_endian(T value) {
    using Word = std::conditional_t<sizeof(T) == 2, std::uint16_t, std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;
    const auto word = std::bit_cast<Word>(value);
    std::string s(sizeof(T), '\0');
    for (std::size_t b = 0; b < sizeof(T); ++b) s[b] = static_cast<char>((word >> (8 * b)) & 0xffu);
    return s;
}

// ---------------------------------------------------------------- X3P, written from ISO 5436-2 with libzip

struct X3pSpec {
    std::string folder = "";      // "" or "sample/"
    std::string root = "p:ISO5436_2";
    char type = 'D';              // I, L, F, D
    bool nan_point = true;        // (4, 3) is NaN (F, D)
    bool valid_bits = false;      // bindata/valid.bin clears (1, 0) and (10, 5)
    bool data_list = false;       // values inline in main.xml instead of bindata/data.bin
    std::string data_bin_override = "";  // replaces data.bin's bytes (bad-file tests)
    std::string main_xml_override = "";  // replaces main.xml (bad-file tests)
};

double z_increment(char type) { return type == 'I' || type == 'L' ? 1e-10 : 1.0; }
double z_offset(char type) { return type == 'L' ? 3e-9 : 0.0; }

std::string x3p_main_xml(const X3pSpec& spec) {
    std::string data;
    if (spec.data_list) {
        data = "<DataList>";
        for (std::size_t iy = 0; iy < kNy; ++iy)
            for (std::size_t ix = 0; ix < kNx; ++ix)
                data += (spec.nan_point && ix == 4 && iy == 3) ? "<Datum/>" : fmt::format("<Datum>{:.17g}</Datum>", height_m(ix, iy));
        data += "</DataList>";
    } else {
        data = "<DataLink><PointDataLink>bindata/data.bin</PointDataLink>";
        if (spec.valid_bits) data += "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>";
        data += "</DataLink>";
    }
    return fmt::format(
        R"(<?xml version="1.0" encoding="UTF-8"?>
<{0} xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{1:.17g}</Increment><Offset>0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{2:.17g}</Increment><Offset>0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>{3}</DataType><Increment>{4:.17g}</Increment><Offset>{5:.17g}</Offset></CZ>
    </Axes>
  </Record1>
  <Record2><Date>2024-01-01T00:00:00+00:00</Date><Creator>surfscatter test</Creator><Comment>ramps</Comment></Record2>
  <Record3>
    <MatrixDimension><SizeX>{6}</SizeX><SizeY>{7}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    {8}
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</{0}>
)",
        spec.root, kDxM, kDyM, spec.type, z_increment(spec.type), z_offset(spec.type), kNx, kNy, data);
}

std::string x3p_data_bin(const X3pSpec& spec) {
    std::string bytes;
    for (std::size_t iy = 0; iy < kNy; ++iy)
        for (std::size_t ix = 0; ix < kNx; ++ix) {
            const double z = height_m(ix, iy);
            const bool nan = spec.nan_point && ix == 4 && iy == 3;
            const double raw = (z - z_offset(spec.type)) / z_increment(spec.type);
            switch (spec.type) {
                case 'I': bytes += little_endian(static_cast<std::int16_t>(std::lround(raw))); break;
                case 'L': bytes += little_endian(static_cast<std::int32_t>(std::lround(raw))); break;
                case 'F': bytes += little_endian(nan ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(raw)); break;
                default: bytes += little_endian(nan ? kNaN : raw); break;
            }
        }
    return bytes;
}

void write_x3p(const fs::path& path, const X3pSpec& spec) {
    std::vector<std::pair<std::string, std::string>> entries;
    entries.emplace_back(spec.folder + "main.xml", spec.main_xml_override.empty() ? x3p_main_xml(spec) : spec.main_xml_override);
    if (!spec.data_list) {
        entries.emplace_back(spec.folder + "bindata/data.bin",
                             spec.data_bin_override.empty() ? x3p_data_bin(spec) : spec.data_bin_override);
        if (spec.valid_bits) {
            std::string bits((kNx * kNy + 7) / 8, '\xff');
            for (std::size_t index : {std::size_t{1}, 5 * kNx + 10}) bits[index / 8] = static_cast<char>(bits[index / 8] & ~(1 << (index % 8)));
            entries.emplace_back(spec.folder + "bindata/valid.bin", bits);
        }
    }
    surfscatter::test::write_zip(path, entries);
}

// Grid, spacing, heights (um) and mask of a map read from an X3P written with `spec`.
void expect_x3p_content(const hm::HeightMap& map, const X3pSpec& spec, double tolerance_um) {
    ASSERT_EQ(map.nx(), kNx);
    ASSERT_EQ(map.ny(), kNy);
    EXPECT_NEAR(map.spacing_x(), kDxM * 1e6, 1e-12);
    EXPECT_NEAR(map.spacing_y(), kDyM * 1e6, 1e-12);
    for (std::size_t iy = 0; iy < kNy; ++iy)
        for (std::size_t ix = 0; ix < kNx; ++ix) {
            const bool nan = spec.nan_point && spec.type != 'I' && spec.type != 'L' && ix == 4 && iy == 3;
            const bool masked = spec.valid_bits && ((ix == 1 && iy == 0) || (ix == 10 && iy == 5));
            ASSERT_EQ(map.valid(ix, iy), !nan && !masked) << ix << ", " << iy;
            if (map.valid(ix, iy)) {
                ASSERT_NEAR(map(ix, iy), height_m(ix, iy) * 1e6, tolerance_um) << ix << ", " << iy;
            }
        }
}

// ---------------------------------------------------------------- SDF (ISO 25178-71)

std::string sdf_binary(std::uint8_t data_type, const std::string& values, double z_scale) {
    std::string bytes = "bISO-1.0";
    bytes += "surfscat  ";                  // ManufacID, 10 bytes
    bytes += "010120240000010120240000";    // CreateDate, ModDate: ddmmyyyyhhmm
    bytes += little_endian(static_cast<std::uint16_t>(kNx)) + little_endian(static_cast<std::uint16_t>(kNy));
    bytes += little_endian(kDxM) + little_endian(kDyM) + little_endian(z_scale) + little_endian(1e-10);
    bytes += std::string{'\0', static_cast<char>(data_type), '\0'};  // Compression, DataType, CheckType
    return bytes + values;
}

}  // namespace

TEST(HeightFiles, SdfTextAndBinaryThroughGwyddion) {
    // Text: heights in nm with Zscale = 1e-9 (m per unit).
    std::string text = fmt::format(
        "aISO-1.0\nManufacID   = surfscat\nCreateDate  = 010120240000\nModDate     = 010120240000\n"
        "NumPoints   = {}\nNumProfiles = {}\nXscale      = {:.17g}\nYscale      = {:.17g}\nZscale      = 1e-09\n"
        "Zresolution = -1\nCompression = 0\nDataType    = 7\nCheckType   = 0\n*\n",
        kNx, kNy, kDxM, kDyM);
    for (std::size_t iy = 0; iy < kNy; ++iy)
        for (std::size_t ix = 0; ix < kNx; ++ix) text += fmt::format("{:.17g}\n", height_m(ix, iy) * 1e9);
    text += "*\n";
    const fs::path text_path = temp_path("text.sdf");
    write_bytes(text_path, text);
    const X3pSpec plain{.nan_point = false};
    const hm::HeightMap from_text = hm::read_height_map(text_path, std::nullopt);
    expect_x3p_content(from_text, plain, 1e-12);
    EXPECT_EQ(from_text.source.reader, "gwyddion " + hm::gwyddion_version() + ":sdfile-txt");

    // Binary double with a NaN (invalid), and int16 with the type's bad-data value -32768 (invalid).
    std::string doubles, shorts;
    for (std::size_t iy = 0; iy < kNy; ++iy)
        for (std::size_t ix = 0; ix < kNx; ++ix) {
            const bool bad = ix == 4 && iy == 3;
            doubles += little_endian(bad ? kNaN : height_m(ix, iy));
            shorts += little_endian(static_cast<std::int16_t>(bad ? -32768 : std::lround(height_m(ix, iy) / 1e-10)));
        }
    const X3pSpec with_nan{.nan_point = true};
    const fs::path double_path = temp_path("double.sdf"), short_path = temp_path("int16.sdf");
    write_bytes(double_path, sdf_binary(7, doubles, 1.0));
    write_bytes(short_path, sdf_binary(5, shorts, 1e-10));
    const hm::HeightMap from_double = hm::read_height_map(double_path, std::nullopt);
    expect_x3p_content(from_double, with_nan, 1e-12);
    EXPECT_EQ(from_double.valid_count(), kNx * kNy - 1);
    EXPECT_EQ(from_double.source.reader, "gwyddion " + hm::gwyddion_version() + ":sdfile-bin");
    expect_x3p_content(hm::read_height_map(short_path, std::nullopt), with_nan, 1e-12);
}

TEST(HeightFiles, StandardX3pEveryDataTypeThroughGwyddionAndNatively) {
    for (char type : {'D', 'F', 'I', 'L'}) {
        SCOPED_TRACE(std::string("DataType ") + type);
        const X3pSpec spec{.type = type, .valid_bits = true};
        const fs::path path = temp_path(fmt::format("standard_{}.x3p", type));
        write_x3p(path, spec);
        const double tolerance = type == 'F' ? 1e-9 : 1e-12;  // um; float32 rounding of nanometre heights
        const hm::HeightMap gwyddion = hm::read_height_map(path, std::nullopt);
        EXPECT_EQ(gwyddion.source.reader, "gwyddion " + hm::gwyddion_version() + ":opengps");
        expect_x3p_content(gwyddion, spec, tolerance);
        // The native reader reads the same file to the same numbers: two independent readers agree.
        const hm::HeightMap native = hm::read_x3p(path);
        EXPECT_EQ(native.source.reader, "native:x3p");
        expect_x3p_content(native, spec, tolerance);
        EXPECT_EQ(native.title, "ramps");
    }
}

TEST(HeightFiles, X3pAsFoundInTheWildIsReadNatively) {
    // Gwyddion 2.62 refuses main.xml in a folder and the root element ISO5436; the native reader takes both, with
    // data links relative to main.xml's folder, and inline DataList values.
    const std::vector<X3pSpec> specs = {
        {.folder = "sample/"},
        {.root = "p:ISO5436"},
        {.folder = "scan 1/", .root = "ISO5436", .type = 'I', .nan_point = false, .valid_bits = true},
        {.folder = "sample/", .data_list = true},
    };
    for (std::size_t i = 0; i < specs.size(); ++i) {
        SCOPED_TRACE(fmt::format("variant {}", i));
        const fs::path path = temp_path(fmt::format("wild_{}.x3p", i));
        write_x3p(path, specs[i]);
        const auto layout = hm::x3p_layout(path);
        ASSERT_TRUE(layout);
        EXPECT_FALSE(layout->standard());
        EXPECT_THROW(hm::gwyddion_read(path), surfscatter::Error);  // what the native reader is for
        const hm::HeightMap map = hm::read_height_map(path, std::nullopt);
        EXPECT_EQ(map.source.reader.rfind("native:x3p", 0), 0u) << map.source.reader;
        expect_x3p_content(map, specs[i], 1e-12);
    }
    // The standard layout with an inline DataList (empty Datum = invalid), read by Gwyddion.
    const X3pSpec list{.data_list = true};
    write_x3p(temp_path("list.x3p"), list);
    expect_x3p_content(hm::read_height_map(temp_path("list.x3p"), std::nullopt), list, 1e-12);
}

// Issue 36 class 2: bad content in the standard layout, which Gwyddion's opengps module read with exit 0 (a zero
// increment "fixed" to 1 m, a negative or NaN one taken as it comes, an unknown DataType or a non-number among inline
// values): every edit of a good file is refused, naming the field.
TEST(HeightFiles, StandardX3pWithBadContentIsRefused) {
    const auto edited = [](const X3pSpec& spec, const std::string& from, const std::string& to) {
        std::string xml = x3p_main_xml(spec);
        const std::size_t at = xml.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return xml.replace(at, from.size(), to);
    };
    const std::string cx = fmt::format("<Increment>{:.17g}</Increment>", kDxM);
    const std::string cz = "<DataType>D</DataType><Increment>1</Increment>";
    const X3pSpec list{.data_list = true};
    struct Case {
        std::string name, main_xml, message;
        bool data_list = false;
    };
    std::string one_short = x3p_main_xml(list);
    one_short.erase(one_short.rfind("<Datum>"), one_short.rfind("</DataList>") - one_short.rfind("<Datum>"));
    std::string not_a_number = x3p_main_xml(list);
    not_a_number.replace(not_a_number.find("<Datum>") + 7, 1, "x");
    const std::vector<Case> cases = {
        {"zero_increment", edited({}, cx, "<Increment>0</Increment>"), "axis increments must be positive, got CX 0 m"},
        {"negative_increment", edited({}, cx, "<Increment>-6.25e-07</Increment>"),
         "axis increments must be positive, got CX -6.25e-07 m"},
        {"nan_z_increment", edited({}, cz, "<DataType>D</DataType><Increment>nan</Increment>"),
         "Record1/Axes/CZ/Increment = 'nan' is not a finite number"},
        {"missing_x_increment", edited({}, cx, ""), "main.xml has no ISO5436_2/Record1/Axes/CX/Increment"},
        {"list_bad_data_type", edited(list, "<DataType>D</DataType><Increment>1", "<DataType>Q</DataType><Increment>1"),
         "CZ DataType 'Q' is not I, L, F or D", true},
        {"list_not_a_number", not_a_number, "is not a number", true},
        {"list_one_point_short", one_short, "DataList holds 279 values, but SizeX x SizeY = 280", true},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path path = temp_path("bad_" + c.name + ".x3p");
        write_x3p(path, {.data_list = c.data_list, .main_xml_override = c.main_xml});
        ASSERT_TRUE(hm::x3p_layout(path) && hm::x3p_layout(path)->standard());
        const std::string message = error_of([&] { hm::read_height_map(path, std::nullopt); });
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
        EXPECT_EQ(message.find("Gwyddion"), std::string::npos) << message;
    }
}

TEST(HeightFiles, GwyFileWrittenThroughTheGwyddionLibrary) {
    std::vector<double> h(kNx * kNy);
    std::vector<std::uint8_t> valid(h.size(), 1);
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = height_m(i % kNx, i / kNx) * 1e6;
    valid[7] = valid[100] = 0;
    hm::HeightMap map(kNx, kNy, kDxM * 1e6, kDyM * 1e6, h, valid, "written");
    map.title = "Topography";
    map.offset_x = 12.5;
    const fs::path path = temp_path("written.gwy");
    hm::gwyddion_write_gwy(map, path);
    const hm::HeightMap back = hm::read_height_map(path, std::nullopt);
    EXPECT_EQ(back.source.reader, "gwyddion " + hm::gwyddion_version() + ":gwyfile");
    EXPECT_EQ(back.title, "Topography");
    EXPECT_DOUBLE_EQ(back.offset_x, 12.5);
    EXPECT_EQ(back.valid_count(), kNx * kNy - 2);
    EXPECT_FALSE(back.valid(7, 0));
    EXPECT_FALSE(back.valid(0, 5));
    for (std::size_t i = 0; i < h.size(); ++i)
        if (valid[i]) {
            ASSERT_NEAR(back.heights()[i], h[i], 1e-15);
        }
    EXPECT_NEAR(back.spacing_x(), kDxM * 1e6, 1e-15);
    // One --spacing cannot agree with non-square pixels.
    EXPECT_NE(error_of([&] { hm::read_height_map(path, kDxM * 1e6); }).find("states dx = 0.625 um, dy = 0.5 um"),
              std::string::npos);
}

TEST(HeightFiles, BadFilesGetOneClearError) {
    const fs::path garbage = temp_path("garbage.bin");
    std::string bytes;
    for (int i = 0; i < 4000; ++i) bytes += static_cast<char>((i * 37) % 256);
    write_bytes(garbage, bytes);
    EXPECT_EQ(error_of([&] { hm::read_height_map(garbage, std::nullopt); }),
              fmt::format("{}: unknown height map format: none of Gwyddion {}'s {} file modules recognises it, and "
                          "it is not a GSF, X3P, TMD, OPDx, NMS, HFM, MNT or text grid",
                          garbage.string(), hm::gwyddion_version(), hm::gwyddion_loader_count()));
    EXPECT_GT(hm::gwyddion_loader_count(), 100u);

    const fs::path zip = temp_path("broken.x3p");
    write_bytes(zip, "PK\x03\x04" + bytes);
    EXPECT_NE(error_of([&] { hm::read_height_map(zip, std::nullopt); }).find("not a readable zip archive"),
              std::string::npos);

    const fs::path bad_xml = temp_path("bad_xml.x3p");
    write_x3p(bad_xml, {.folder = "s/", .main_xml_override = "<p:ISO5436_2><Record1><FeatureType>SUR</Record1>"});
    EXPECT_NE(error_of([&] { hm::read_height_map(bad_xml, std::nullopt); }).find("'s/main.xml' is not well-formed XML"),
              std::string::npos);

    const fs::path short_data = temp_path("short_data.x3p");
    write_x3p(short_data, {.folder = "s/", .data_bin_override = std::string(100, '\0')});
    EXPECT_EQ(error_of([&] { hm::read_height_map(short_data, std::nullopt); }),
              short_data.string() + ": the point data hold 100 bytes, but 280 points of DataType D need 2240 "
                                    "(inconsistent sizes)");

    const fs::path all_nan = temp_path("all_nan.x3p");
    std::string nans;
    for (std::size_t i = 0; i < kNx * kNy; ++i) nans += little_endian(kNaN);
    write_x3p(all_nan, {.folder = "s/", .data_bin_override = nans});
    EXPECT_EQ(error_of([&] { hm::read_height_map(all_nan, std::nullopt); }),
              all_nan.string() + ": every one of the 20 x 14 points is invalid");

    const fs::path profile = temp_path("profile.x3p");
    std::string xml = x3p_main_xml({});
    xml.replace(xml.find("SUR"), 3, "PRF");
    write_x3p(profile, {.folder = "s/", .main_xml_override = xml});
    EXPECT_EQ(error_of([&] { hm::read_height_map(profile, std::nullopt); }),
              profile.string() + ": FeatureType PRF is not a surface (SUR): profiles are not height maps");

    // Found by fuzz_x3p: a value with a line break was quoted raw, breaking the one-line message.
    const fs::path line_break = temp_path("line_break.x3p");
    xml = x3p_main_xml({});
    const std::size_t increment = xml.find("<Increment>") + std::string_view("<Increment>").size();
    xml.replace(increment, xml.find('<', increment) - increment, "1e\n06");
    write_x3p(line_break, {.folder = "s/", .main_xml_override = xml});
    EXPECT_EQ(error_of([&] { hm::read_height_map(line_break, std::nullopt); }),
              line_break.string() + ": s/main.xml: Record1/Axes/CX/Increment = '1e\\x0a06' is not a finite number");

    // A photograph is an image Gwyddion reads, but it has no height channel.
    const fs::path photo = fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "photos" / "gboriginal.jpg";
    const std::string no_heights = error_of([&] { hm::read_height_map(photo, std::nullopt); });
    EXPECT_NE(no_heights.find("no height channel (x, y and z in metres)"), std::string::npos) << no_heights;

    EXPECT_NE(error_of([&] { hm::read_height_map(temp_path("missing.dat"), std::nullopt); }).find("height map file not found"),
              std::string::npos);
    EXPECT_NE(error_of([&] { hm::read_height_map(temp_path(""), std::nullopt); }).find("is a directory"),
              std::string::npos);
}

// ---------------------------------------------------------------- real instrument files

namespace {
fs::path real_file(const std::string& name) {
    return fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / name;
}
}  // namespace

// Figures from ../shared/data/realdata/README.md (SurfaceTopography's test suite and Gwyddion 2.62), to half a
// unit in their last stated digit.
TEST(HeightFiles, ZygoMetroProAsItsTestSuiteStates) {
    const hm::HeightMap map = hm::read_height_map(real_file("metropro-1.dat"), std::nullopt);
    EXPECT_EQ(map.nx(), 640u);
    EXPECT_EQ(map.ny(), 480u);
    EXPECT_NEAR(map.width(), 702.8813, 0.00005);
    EXPECT_NEAR(map.height(), 527.1610, 0.00005);
    EXPECT_FALSE(map.has_invalid());
    EXPECT_NEAR(hm::rms_height(map, hm::Form::none), 7.528822e-2, 0.0000005e-2);     // 7.528822e-8 m
    EXPECT_NEAR(hm::rms_height(map, hm::Form::poly2), 3.911386e-3, 0.0000005e-3);    // after a curvature form
    EXPECT_EQ(map.source.reader, "gwyddion " + hm::gwyddion_version() + ":metropro");
    // The stated spacing may be repeated (to 1e-6), not contradicted.
    EXPECT_NO_THROW(hm::read_height_map(real_file("metropro-1.dat"), 702.8813 / 640));
    EXPECT_THROW(hm::read_height_map(real_file("metropro-1.dat"), 1.1), surfscatter::Error);
}

TEST(HeightFiles, WykoOpdWithInvalidPoints) {
    const hm::HeightMap map = hm::read_height_map(real_file("opd-1.opd"), std::nullopt);
    EXPECT_EQ(map.nx(), 640u);
    EXPECT_EQ(map.ny(), 480u);
    EXPECT_NEAR(map.width(), 125.909140, 0.0000005);
    EXPECT_NEAR(map.height(), 94.431855, 0.0000005);
    EXPECT_EQ(map.size() - map.valid_count(), 116u);
    EXPECT_NEAR(hm::rms_height(map, hm::Form::none), 8.35645e-3, 0.000005e-3);  // valid points only
}

TEST(HeightFiles, BrukerNanoscopeFirstChannel) {
    const hm::HeightMap map = hm::read_height_map(real_file("di-1.di"), std::nullopt);
    EXPECT_EQ(map.nx(), 512u);
    EXPECT_EQ(map.ny(), 512u);
    EXPECT_NEAR(map.width(), 0.5, 1e-12);
    EXPECT_NEAR(map.height(), 0.5, 1e-12);
    EXPECT_NEAR(hm::rms_height(map, hm::Form::none), 9.94599e-3, 0.000005e-3);
    EXPECT_EQ(map.source.channel, "0 'Height'");
}
