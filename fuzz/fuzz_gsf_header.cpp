// Fuzz target: the header of Gwyddion Simple Field files (heightmap/io.hpp read_gsf, its "name = value"
// lines through heightmap/parse.hpp). The bytes are the header's text: the target adds the magic line, the
// NUL padding and, when the header's XRes x YRes is small, that many float samples, so that mutations explore the
// header instead of failing on the data's size (fuzz_height_map feeds whole files).
#include <algorithm>
#include <cstring>

#include "fuzz_common.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    std::string header(fuzz::as_text(data, size));
    header.erase(std::remove(header.begin(), header.end(), '\0'), header.end());
    std::size_t samples = 0;
    try {
        const auto fields = heightmap::parse::header_fields(header, 2, "fuzz.gsf");
        const auto side = [&](const char* key) -> std::size_t {
            const auto it = fields.find(key);
            const auto value = it == fields.end() ? std::nullopt : to_double(it->second);
            return value && *value >= 1 && *value <= 256 ? static_cast<std::size_t>(*value) : 1;
        };
        samples = side("XRes") * side("YRes");
    } catch (const Error&) {
        samples = 1;  // read_gsf reports the header's error
    }
    std::string file = "Gwyddion Simple Field 1.0\n" + header;
    file.append(4 - file.size() % 4, '\0');
    for (std::size_t i = 0; i < samples; ++i) {
        const float value = static_cast<float>(i % 7) * 0.25f;
        char bytes[4];
        std::memcpy(bytes, &value, 4);  // little-endian, as GSF's samples (x86)
        file.append(bytes, 4);
    }
    const auto path = fuzz::write_input("header.gsf", file);
    fuzz::expect_clean([&] {
        const heightmap::HeightMap map = heightmap::read_gsf(path);
        for (double h : map.heights()) FUZZ_CHECK(std::isfinite(h));
        FUZZ_CHECK(std::isfinite(map.width()) && map.width() > 0 && std::isfinite(map.height()) && map.height() > 0);
        FUZZ_CHECK(std::isfinite(map.offset_x) && std::isfinite(map.offset_y));
    });
    return 0;
}
