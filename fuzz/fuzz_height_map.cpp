// Fuzz target: the native height-map readers (heightmap/io.hpp), Gwyddion Simple Field and text grids
// (bare, and with the header of Gwyddion's text export), on the same bytes (X3P: fuzz_x3p.cpp); a map that loads is
// fitted (KC fit, rms slope) and everything it returns must be finite.
#include "fuzz_common.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/kc_fit.hpp"

namespace {

void check_map(const surfscatter::heightmap::HeightMap& map) {
    using namespace surfscatter;
    for (double h : map.heights()) FUZZ_CHECK(std::isfinite(h));
    FUZZ_CHECK(std::isfinite(heightmap::rms_height(map)));
    FUZZ_CHECK(std::isfinite(surface::rms_slope(map)));
    if (map.size() > 128 * 128) return;  // keep the fit cheap
    try {
        const surface::SurfaceFit fit = surface::fit_surface(map);
        FUZZ_CHECK(std::isfinite(fit.kc.sigma_h_um) && std::isfinite(fit.kc.corr_length_um) && std::isfinite(fit.kc.gamma));
        FUZZ_CHECK(std::isfinite(fit.rms_slope_from_psd));
    } catch (const Error&) {
        // a map without a KC fit: reported, not a finding
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    const auto text = fuzz::as_text(data, size);
    const auto gsf = fuzz::write_input("map.gsf", text);
    fuzz::expect_clean([&] { check_map(heightmap::read_gsf(gsf)); });
    const auto grid = fuzz::write_input("map.txt", text);
    // Without a spacing the Gwyddion text export's header states it (and the height unit); with one, the header
    // must agree.
    fuzz::expect_clean([&] { check_map(heightmap::read_text_grid(grid, std::nullopt)); });
    fuzz::expect_clean([&] { check_map(heightmap::read_text_grid(grid, 0.1)); });
    return 0;
}
