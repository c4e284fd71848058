// Fuzz target: the native readers of instrument formats Gwyddion lacks or misdetects (heightmap/tmd, nms, opdx,
// hfm, mnt with its compound file), each on the same bytes, and read_height_map's dispatch; a map that loads must hold finite heights and rms, a
// profile finite heights and a positive spacing.
#include <variant>

#include "fuzz_common.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/hfm.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/mnt.hpp"
#include "surfscatter/heightmap/nms.hpp"
#include "surfscatter/heightmap/opdx.hpp"
#include "surfscatter/heightmap/tmd.hpp"

namespace {

void check_map(const surfscatter::heightmap::HeightMap& map) {
    for (double h : map.heights()) FUZZ_CHECK(std::isfinite(h));
    FUZZ_CHECK(std::isfinite(surfscatter::heightmap::rms_height(map, surfscatter::heightmap::Form::none)));
}

void check_scan(const surfscatter::heightmap::LineScan& scan) {
    for (double h : scan.heights_um) FUZZ_CHECK(std::isfinite(h));
    FUZZ_CHECK(scan.spacing_um > 0.0 && std::isfinite(scan.spacing_um));
    FUZZ_CHECK(scan.validity.empty() || scan.validity.size() == scan.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    const auto bytes = fuzz::as_text(data, size);
    const auto path = fuzz::write_input("instrument.bin", bytes);
    fuzz::expect_clean([&] { check_map(heightmap::read_tmd(path)); });
    fuzz::expect_clean([&] { check_map(heightmap::read_nms(path)); });
    fuzz::expect_clean([&] {
        const auto read = heightmap::read_opdx(path);
        if (const auto* map = std::get_if<heightmap::HeightMap>(&read)) check_map(*map);
        else check_scan(std::get<heightmap::LineScan>(read));
    });
    fuzz::expect_clean([&] { check_scan(heightmap::read_hfm(path)); });
    fuzz::expect_clean([&] { check_map(heightmap::read_mnt(path)); });
    // Only the native formats: anything else would go to Gwyddion, whose modules are not fuzzed here.
    if (heightmap::is_tmd(bytes) || heightmap::is_nms(bytes) || heightmap::is_opdx(bytes) || heightmap::is_hfm(bytes) ||
        heightmap::is_mnt(path, bytes))
        fuzz::expect_clean([&] { check_map(heightmap::read_height_map(path, std::nullopt)); });
    return 0;
}
