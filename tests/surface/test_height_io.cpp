// Height map files: .gsf round trip, a .gsf written by hand per the Gwyddion spec, text grids, and bad input.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/height_map_io.hpp"

namespace ss = surfscatter::surface;
namespace fs = std::filesystem;

namespace {

fs::path temp_path(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "surfscatter_test_height_io";
    fs::create_directories(dir);
    return dir / name;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
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

ss::HeightMap ramp_map(std::size_t nx, std::size_t ny, double spacing) {
    std::vector<double> h(nx * ny);
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = 0.001 * static_cast<double>(i % 97) - 0.03;
    return ss::HeightMap(nx, ny, spacing, 1.5 * spacing, std::move(h));
}

// Runs f and returns the Error message (fails the test if nothing is thrown).
template <typename F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const surfscatter::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no surfscatter::Error thrown";
    return {};
}

}  // namespace

TEST(HeightIo, GsfRoundTripKeepsFloatsAndMetadata) {
    ss::HeightMap map = ramp_map(13, 9, 0.37);
    map.offset_x = 12.5;
    map.offset_y = -3.25;
    map.title = "ground steel, \xc2\xb5m scale";
    const fs::path first = temp_path("round_trip.gsf"), second = temp_path("round_trip2.gsf");
    ss::write_gsf(map, first);
    const ss::HeightMap back = ss::read_gsf(first);
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
    ss::write_gsf(back, second);
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
    const ss::HeightMap map = ss::read_gsf(path);
    EXPECT_EQ(map.nx(), 8u);
    EXPECT_EQ(map.ny(), 8u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 5.0);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 2.5);
    EXPECT_EQ(map.title, "Height");
    EXPECT_DOUBLE_EQ(map(0, 0), -0.0315);
    EXPECT_DOUBLE_EQ(map(7, 0), -0.0245);  // row-major: x along the row
    EXPECT_DOUBLE_EQ(map(0, 1), -0.0235);
    EXPECT_DOUBLE_EQ(map(7, 7), 0.0315);
    EXPECT_TRUE(ss::is_gsf_file(path));
    // Padding when the header length is already a multiple of 4 is four NULs (spec: one to four).
    std::string header4 = "XRes = 8\nYRes = 8\nXYUnits = um\nZUnits = um\n";
    while (("Gwyddion Simple Field 1.0\n" + header4).size() % 4 != 0) header4 += " ";
    const std::string bytes = hand_made_gsf(header4, data);
    EXPECT_EQ(bytes.substr(bytes.size() - 256 - 4, 4), std::string(4, '\0'));
    write_bytes(path, bytes);
    const ss::HeightMap unit_map = ss::read_gsf(path);
    EXPECT_DOUBLE_EQ(unit_map.spacing_x(), 1.0 / 8.0);  // XReal defaults to 1 (um here)
    EXPECT_DOUBLE_EQ(unit_map(1, 0), -30.5);
}

TEST(HeightIo, MalformedGsfNamesFileAndProblem) {
    std::vector<float> data(64, 1.0f);
    const std::string good = "XRes = 8\nYRes = 8\nXYUnits = m\nZUnits = m\n";
    const fs::path path = temp_path("bad.gsf");
    auto message_for = [&](const std::string& bytes) {
        write_bytes(path, bytes);
        return error_of([&] { ss::read_gsf(path); });
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
    data[10] = std::numeric_limits<float>::quiet_NaN();
    const std::string nan_message = message_for(hand_made_gsf(good, data));
    EXPECT_NE(nan_message.find("column 2, row 1"), std::string::npos) << nan_message;
    EXPECT_NE(nan_message.find(path.string()), std::string::npos);
    EXPECT_NE(error_of([&] { ss::read_gsf(temp_path("does_not_exist.gsf")); }).find("cannot open"),
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
    const ss::HeightMap map = ss::read_text_grid(path, 0.25, 1e-3);
    EXPECT_EQ(map.nx(), 9u);
    EXPECT_EQ(map.ny(), 8u);
    EXPECT_DOUBLE_EQ(map.spacing_x(), 0.25);
    EXPECT_DOUBLE_EQ(map.spacing_y(), 0.25);
    EXPECT_DOUBLE_EQ(map(3, 5), 0.053);
    // read_height_map dispatches on content and insists on a spacing for text grids only.
    EXPECT_DOUBLE_EQ(ss::read_height_map(path, 0.5)(8, 7), 78.0);
    EXPECT_NE(error_of([&] { ss::read_height_map(path, std::nullopt); }).find("--spacing"), std::string::npos);
    const fs::path gsf = temp_path("grid.gsf");
    ss::write_gsf(map, gsf);
    EXPECT_NE(error_of([&] { ss::read_height_map(gsf, 1.0); }).find("stores its own"), std::string::npos);
    EXPECT_DOUBLE_EQ(ss::read_height_map(gsf, std::nullopt).spacing_x(), 0.25);
}

TEST(HeightIo, MalformedTextGridNamesLine) {
    const fs::path path = temp_path("bad.csv");
    auto message_for = [&](const std::string& text, double spacing = 1.0) {
        write_bytes(path, text);
        return error_of([&] { ss::read_text_grid(path, spacing); });
    };
    std::string rows;
    for (int i = 0; i < 8; ++i) rows += "1,2,3,4,5,6,7,8\n";
    EXPECT_NE(message_for(rows + "1,2,3\n").find(":9: row has 3 values"), std::string::npos);
    EXPECT_NE(message_for(rows + "1,2,x,4,5,6,7,8\n").find(":9: column 3: 'x'"), std::string::npos);
    EXPECT_NE(message_for(rows + "1,2,nan,4,5,6,7,8\n").find(":9: column 3: height is nan"), std::string::npos);
    EXPECT_NE(message_for(rows + "1,,3,4,5,6,7,8\n").find("column 2"), std::string::npos);
    EXPECT_NE(message_for(rows, 0.0).find("spacing"), std::string::npos);
    EXPECT_NE(message_for(rows, -1.0).find("spacing"), std::string::npos);
    EXPECT_NE(message_for("# nothing\n").find("no height values"), std::string::npos);
    EXPECT_NE(message_for("1 2 3\n4 5 6\n").find("at least 8"), std::string::npos);
}
