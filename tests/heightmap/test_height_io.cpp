// Height map files: .gsf round trip, a .gsf written by hand per the Gwyddion spec, text grids, and bad input.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "height_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/io.hpp"

namespace hm = surfscatter::heightmap;
namespace fs = std::filesystem;

namespace {

using surfscatter::heightmap::test::error_of;
using surfscatter::heightmap::test::write_bytes;

fs::path temp_path(const std::string& name) {
    return surfscatter::heightmap::test::temp_path("surfscatter_test_height_io", name);
}

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string float_le(float f) {
    const auto word = std::bit_cast<std::uint32_t>(f);
    std::string s(4, '\0');
    for (int b = 0; b < 4; ++b) s[b] = static_cast<char>((word >> (8 * b)) & 0xffu);
    return s;
}

// A GSF file assembled byte by byte from the spec: magic, header lines, NUL padding to a multiple of 4, data.
std::string hand_made_gsf(const std::string& header_lines, const std::vector<float>& data) {
    std::string bytes = "Gwyddion Simple Field 1.0\n" + header_lines;
    bytes.append(4 - bytes.size() % 4, '\0');
    for (float f : data) bytes += float_le(f);
    return bytes;
}

hm::HeightMap ramp_map(std::size_t nx, std::size_t ny, double spacing) {
    std::vector<double> h(nx * ny);
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = 0.001 * static_cast<double>(i % 97) - 0.03;
    return hm::HeightMap(nx, ny, spacing, 1.5 * spacing, std::move(h));
}

}  // namespace

TEST(HeightIo, GsfRoundTripKeepsFloatsAndMetadata) {
    hm::HeightMap map = ramp_map(13, 9, 0.37);
    map.offset_x = 12.5;
    map.offset_y = -3.25;
    map.title = "ground steel, \xc2\xb5m scale";
    const fs::path first = temp_path("round_trip.gsf"), second = temp_path("round_trip2.gsf");
    hm::write_gsf(map, first);
    const hm::HeightMap back = hm::read_gsf(first);
    ASSERT_EQ(back.nx(), 13u);
    ASSERT_EQ(back.ny(), 9u);
    EXPECT_DOUBLE_EQ(back.spacing_x(), 0.37);
    EXPECT_DOUBLE_EQ(back.spacing_y(), 1.5 * 0.37);
    EXPECT_DOUBLE_EQ(back.offset_x, 12.5);
    EXPECT_DOUBLE_EQ(back.offset_y, -3.25);
    EXPECT_EQ(back.title, map.title);
    // Heights are stored as float32 metres: equal to the original within float rounding ...
    for (std::size_t i = 0; i < map.size(); ++i)
        EXPECT_NEAR(back.heights()[i], map.heights()[i], 6e-8 * std::abs(map.heights()[i]) + 1e-15);
    // ... and writing what was read reproduces the file byte for byte (identical floats and header).
    hm::write_gsf(back, second);
    EXPECT_EQ(read_bytes(first), read_bytes(second));
    const std::string bytes = read_bytes(first);
    EXPECT_EQ(bytes.size() % 4, 0u);
    EXPECT_EQ(bytes.size(), bytes.find('\0') / 4 * 4 + 4 + 4 * map.size());
}

TEST(HeightIo, ReadsHandMadeGsfWithUnits) {
    // 8 x 8 field, 40 um x 20 um in nm units for heights, extra whitespace and an unknown key (ignored by spec).
    std::vector<float> data(64);
    for (int i = 0; i < 64; ++i) data[i] = static_cast<float>(i) - 31.5f;  // nm
    const std::string header =
        "XRes = 8\n  YRes=8\nXReal = 4e-05\nYReal = 2e-05\nXYUnits = m\nZUnits = nm\nTitle = Height\nVendor = x\n";
    const fs::path path = temp_path("hand.gsf");
    write_bytes(path, hand_made_gsf(header, data));
    const hm::HeightMap map = hm::read_gsf(path);
    EXPECT_EQ(map.nx(), 8u);
    EXPECT_EQ(map.ny(), 8u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 5.0);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 2.5);
    EXPECT_EQ(map.title, "Height");
    EXPECT_DOUBLE_EQ(map(0, 0), -0.0315);
    EXPECT_DOUBLE_EQ(map(7, 0), -0.0245);  // row-major: x along the row
    EXPECT_DOUBLE_EQ(map(0, 1), -0.0235);
    EXPECT_DOUBLE_EQ(map(7, 7), 0.0315);
    EXPECT_TRUE(hm::is_gsf_file(path));
    // Padding when the header length is already a multiple of 4 is four NULs (spec: one to four).
    std::string header4 = "XRes = 8\nYRes = 8\nXYUnits = um\nZUnits = um\n";
    while (("Gwyddion Simple Field 1.0\n" + header4).size() % 4 != 0) header4 += " ";
    const std::string bytes = hand_made_gsf(header4, data);
    EXPECT_EQ(bytes.substr(bytes.size() - 256 - 4, 4), std::string(4, '\0'));
    write_bytes(path, bytes);
    const hm::HeightMap unit_map = hm::read_gsf(path);
    EXPECT_DOUBLE_EQ(unit_map.spacing_x(), 1.0 / 8.0);  // XReal defaults to 1 (um here)
    EXPECT_DOUBLE_EQ(unit_map(1, 0), -30.5);
}

TEST(HeightIo, MalformedGsfNamesFileAndProblem) {
    std::vector<float> data(64, 1.0f);
    const std::string good = "XRes = 8\nYRes = 8\nXYUnits = m\nZUnits = m\n";
    const fs::path path = temp_path("bad.gsf");
    auto message_for = [&](const std::string& bytes) {
        write_bytes(path, bytes);
        return error_of([&] { hm::read_gsf(path); });
    };
    EXPECT_NE(message_for("Gwyddion Simple Feld 1.0\n").find("not a Gwyddion Simple Field"), std::string::npos);
    const std::string full = hand_made_gsf(good, data);
    EXPECT_NE(message_for(full.substr(0, full.size() - 3)).find("truncated"), std::string::npos);
    EXPECT_NE(message_for(full + "xxxx").find("trailing"), std::string::npos);
    EXPECT_NE(message_for("Gwyddion Simple Field 1.0\nXRes = 8\n").find("not terminated"), std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf("YRes = 8\nXYUnits = m\nZUnits = m\n", data)).find("XRes"),
              std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf("XRes = -8\nYRes = 8\nXYUnits = m\nZUnits = m\n", data)).find("XRes"),
              std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf("XRes = 99999999999\nYRes = 99999999999\nXYUnits = m\nZUnits = m\n", data))
                  .find("larger than"),
              std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf("XRes = 8\nYRes = 8\nZUnits = m\n", data)).find("XYUnits"),
              std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf("XRes = 8\nYRes = 8\nXYUnits = V\nZUnits = m\n", data)).find("'V'"),
              std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf("XRes = 8\nYRes = 8\nXReal = -1\nXYUnits = m\nZUnits = m\n", data))
                  .find("XReal"),
              std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf("XRes = 8\nYRes = 8\ngarbage\nXYUnits = m\nZUnits = m\n", data))
                  .find("name = value"),
              std::string::npos);
    // A field given twice names both lines (the first was kept silently).
    const std::string twice = message_for(hand_made_gsf("XRes = 8\nYRes = 8\nXYUnits = m\nXYUnits = mm\nZUnits = m\n", data));
    EXPECT_NE(twice.find("bad.gsf:5: header field 'XYUnits' is given twice (first at line 4)"), std::string::npos) << twice;
    data[10] = std::numeric_limits<float>::infinity();
    const std::string inf_message = message_for(hand_made_gsf(good, data));
    EXPECT_NE(inf_message.find("column 2, row 1 is inf"), std::string::npos) << inf_message;
    EXPECT_NE(inf_message.find(path.string()), std::string::npos);
    EXPECT_NE(message_for(hand_made_gsf(good, std::vector<float>(64, std::numeric_limits<float>::quiet_NaN())))
                  .find("every one of the 8 x 8 points is invalid"),
              std::string::npos);
    EXPECT_NE(error_of([&] { hm::read_gsf(temp_path("does_not_exist.gsf")); }).find("height map file not found"),
              std::string::npos);
    std::vector<float> small(16, 0.0f);
    EXPECT_NE(message_for(hand_made_gsf("XRes = 4\nYRes = 4\nXYUnits = m\nZUnits = m\n", small)).find("at least 8"),
              std::string::npos);
}

TEST(HeightIo, TextGridWithSpacing) {
    const fs::path path = temp_path("grid.csv");
    std::string text = "# exported heights, um\n";
    for (int iy = 0; iy < 8; ++iy) {
        for (int ix = 0; ix < 9; ++ix) text += (ix ? (iy % 2 ? ", " : "\t ") : "") + std::to_string(ix + 10 * iy);
        text += "\r\n";
    }
    text += "\n";
    write_bytes(path, text);
    const hm::HeightMap map = hm::read_text_grid(path, 0.25, 1e-3);
    EXPECT_EQ(map.nx(), 9u);
    EXPECT_EQ(map.ny(), 8u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 0.25);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 0.25);
    EXPECT_DOUBLE_EQ(map(3, 5), 0.053);
    // read_height_map dispatches on content and insists on a spacing for text grids only.
    EXPECT_DOUBLE_EQ(hm::read_height_map(path, 0.5)(8, 7), 78.0);
    EXPECT_NE(error_of([&] { hm::read_height_map(path, std::nullopt); }).find("--spacing"), std::string::npos);
    // A file that states its spacing and height unit: the same values may be given, others are errors.
    const fs::path gsf = temp_path("grid.gsf");
    hm::write_gsf(map, gsf);
    EXPECT_EQ(error_of([&] { hm::read_height_map(gsf, 1.0); }),
              gsf.string() + ": --spacing 1 um contradicts the file, which states dx = 0.25 um, dy = 0.25 um "
                             "(Gwyddion Simple Field (.gsf))");
    EXPECT_EQ(error_of([&] { hm::read_height_map(gsf, std::nullopt, 1.0); }),
              gsf.string() + ": --height-unit 1 um contradicts the file, which states its heights in units of "
                             "1000000 um (Gwyddion Simple Field (.gsf))");
    const hm::HeightMap again = hm::read_height_map(gsf, 0.25, 1e6);
    EXPECT_DOUBLE_EQ(again.spacing_x(), 0.25);
    EXPECT_EQ(again.source.reader, "native:gsf");
    EXPECT_DOUBLE_EQ(hm::read_height_map(gsf, std::nullopt).spacing_x(), 0.25);
}

TEST(HeightIo, NanMarksInvalidPointsInGsfAndTextGrids) {
    hm::HeightMap map = ramp_map(12, 10, 0.5);
    std::vector<double> h = map.heights();
    std::vector<std::uint8_t> valid(h.size(), 1);
    valid[13] = valid[50] = 0;
    const hm::HeightMap masked(12, 10, 0.5, 0.75, h, valid, "masked");
    const fs::path gsf = temp_path("masked.gsf");
    hm::write_gsf(masked, gsf);
    const hm::HeightMap back = hm::read_height_map(gsf, std::nullopt);
    EXPECT_EQ(back.valid_count(), 118u);
    EXPECT_FALSE(back.valid(1, 1));
    EXPECT_FALSE(back.valid(2, 4));
    EXPECT_NEAR(back(3, 4), h[51], 1e-9);

    const fs::path csv = temp_path("masked.csv");
    std::string text;
    for (int iy = 0; iy < 8; ++iy) {
        for (int ix = 0; ix < 8; ++ix) {
            if (ix) text += ' ';  // piece by piece: `" " + std::string` trips g++ 12's false -Wrestrict warning
            text += ix == iy ? (iy % 2 ? "NaN" : "nan") : "1.5";
        }
        text += "\n";
    }
    write_bytes(csv, text);
    const hm::HeightMap grid = hm::read_height_map(csv, 2.0);
    EXPECT_EQ(grid.valid_count(), 56u);
    EXPECT_FALSE(grid.valid(3, 3));
    EXPECT_DOUBLE_EQ(grid(3, 4), 1.5);
    EXPECT_EQ(grid.source.format, "text grid");
}

// Gwyddion's text export as Gwyddion 2.62 writes it (asciiexport with "Add informational comment header": the
// four lines below, values tab-separated in the channel's base unit).
std::string gwyddion_text_export(const std::string& width, const std::string& height, const std::string& units,
                                 std::size_t nx, std::size_t ny) {
    std::string text = "# Channel: ZSensor\n# Width: " + width + "\n# Height: " + height +
                       "\n# Value units: " + units + "\n";
    for (std::size_t iy = 0; iy < ny; ++iy) {
        for (std::size_t ix = 0; ix < nx; ++ix) {
            if (ix) text += '\t';
            text += ix == 2 && iy == 3 ? std::string("nan")
                                       : fmt::format("{:.6g}", 1e-9 * (static_cast<double>(ix) + 100.0 * static_cast<double>(iy)));
        }
        text += "\n";
    }
    return text;
}

TEST(HeightIo, GwyddionTextExportStatesSpacingAndUnits) {
    const fs::path path = temp_path("export.txt");
    // 256 x 128 samples over 10.00 x 5.000 um: dx = 0.0390625 um, printed to +-0.005 um of width.
    write_bytes(path, gwyddion_text_export("10.00 \xc2\xb5m", "5.000 \xc2\xb5m", "m", 256, 128));
    const hm::HeightMap map = hm::read_height_map(path, std::nullopt);
    EXPECT_EQ(map.nx(), 256u);
    EXPECT_EQ(map.ny(), 128u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 10.0 / 256);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 5.0 / 128);
    EXPECT_NEAR(map(5, 7), 1e-3 * (5 + 700.0), 1e-12);  // m -> um
    EXPECT_FALSE(map.valid(2, 3));
    EXPECT_EQ(map.source.format, "Gwyddion text export (text grid with header)");
    EXPECT_EQ(map.source.channel, "ZSensor");
    // A spacing within the printed precision (+-2e-5 um in x, +-4e-6 um in y) refines it; one outside contradicts.
    EXPECT_DOUBLE_EQ(hm::read_height_map(path, 0.039064).spacing_x(), 0.039064);
    EXPECT_EQ(error_of([&] { hm::read_height_map(path, 0.0395); }),
              path.string() + ": --spacing 0.0395 um contradicts the header: Width 10 um / 256 columns = 0.0390625 "
                              "um, Height 5 um / 128 rows = 0.0390625 um");
    EXPECT_NE(error_of([&] { hm::read_height_map(path, std::nullopt, 1e-3); }).find("Value units: m"),
              std::string::npos);
    EXPECT_NO_THROW(hm::read_height_map(path, std::nullopt, 1e6));
    // Other length units, the Greek mu, and headers that cannot be heights.
    write_bytes(path, gwyddion_text_export("500.0 nm", "250.0 nm", "nm", 16, 8));
    const hm::HeightMap nm = hm::read_height_map(path, std::nullopt);
    EXPECT_DOUBLE_EQ(nm.spacing_x(), 0.5 / 16);
    EXPECT_NEAR(nm(1, 1), 1e-3 * 1e-9 * 101, 1e-18);
    write_bytes(path, gwyddion_text_export("2.5 \xce\xbcm", "1.25 \xce\xbcm", "m", 16, 8));
    EXPECT_DOUBLE_EQ(hm::read_height_map(path, std::nullopt).spacing_x(), 2.5 / 16);
    write_bytes(path, gwyddion_text_export("2.5 um", "1.25 um", "V", 16, 8));
    EXPECT_EQ(error_of([&] { hm::read_height_map(path, std::nullopt); }),
              path.string() + ":4: '# Value units: V' is not a length: the channel 'ZSensor' holds no heights");
    write_bytes(path, gwyddion_text_export("2.5 furlong", "1.25 um", "m", 16, 8));
    EXPECT_NE(error_of([&] { hm::read_height_map(path, std::nullopt); }).find(":2: '# Width: 2.5 furlong'"),
              std::string::npos);
    std::string width_only = "# Width: 2 um\n";
    for (int row = 0; row < 8; ++row) width_only += "1 2 3 4 5 6 7 8\n";
    write_bytes(path, width_only);
    EXPECT_EQ(error_of([&] { hm::read_height_map(path, std::nullopt); }),
              path.string() + ": the header states '# Width:' but not '# Height:'");
}

TEST(HeightIo, MalformedTextGridNamesLine) {
    const fs::path path = temp_path("bad.csv");
    auto message_for = [&](const std::string& text, double spacing = 1.0) {
        write_bytes(path, text);
        return error_of([&] { hm::read_text_grid(path, spacing); });
    };
    std::string rows;
    for (int i = 0; i < 8; ++i) rows += "1,2,3,4,5,6,7,8\n";
    EXPECT_NE(message_for(rows + "1,2,3\n").find(":9: row has 3 values"), std::string::npos);
    EXPECT_NE(message_for(rows + "1,2,x,4,5,6,7,8\n").find(":9: column 3: 'x'"), std::string::npos);
    EXPECT_NE(message_for(rows + "1,2,inf,4,5,6,7,8\n").find(":9: column 3: height is inf"), std::string::npos);
    EXPECT_NE(message_for(rows + "1,,3,4,5,6,7,8\n").find("column 2"), std::string::npos);
    EXPECT_NE(message_for(rows, 0.0).find("spacing"), std::string::npos);
    EXPECT_NE(message_for(rows, -1.0).find("spacing"), std::string::npos);
    EXPECT_NE(message_for("# nothing\n").find("no height values"), std::string::npos);
    EXPECT_NE(message_for("1 2 3\n4 5 6\n").find("at least 8"), std::string::npos);
}
