// Fuzz target: the native X3P reader (heightmap/x3p.hpp). libzip checks every entry's CRC, so mutating
// whole archives would rarely get past it: the input is main.xml, a NUL byte, then bindata/data.bin, and the target
// stores both in a fresh zip archive before reading it. A map that loads must hold finite heights.
#include <zip.h>

#include "fuzz_common.hpp"
#include "surfscatter/heightmap/x3p.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    const std::string_view input = fuzz::as_text(data, size);
    const std::size_t split = input.find('\0');
    const std::string main_xml(input.substr(0, split));
    const std::string data_bin(split == std::string_view::npos ? std::string_view() : input.substr(split + 1));
    const auto path = fuzz::scratch() / "map.x3p";
    int code = 0;
    zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
    FUZZ_CHECK(archive != nullptr);
    for (const auto& [name, bytes] : {std::pair<const char*, const std::string*>{"main.xml", &main_xml},
                                      {"bindata/data.bin", &data_bin}}) {
        zip_source_t* source = zip_source_buffer(archive, bytes->data(), bytes->size(), 0);
        FUZZ_CHECK(source != nullptr && zip_file_add(archive, name, source, ZIP_FL_OVERWRITE) >= 0);
    }
    FUZZ_CHECK(zip_close(archive) == 0);
    fuzz::expect_clean([&] {
        const heightmap::HeightMap map = heightmap::read_x3p(path);
        for (double h : map.heights()) FUZZ_CHECK(std::isfinite(h));
    });
    return 0;
}
