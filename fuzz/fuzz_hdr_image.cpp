// Fuzz target: the Radiance RGBE reader (io/image.hpp, read_image of a .hdr file; the one image decoder written here,
// the others are libpng, libjpeg and OpenEXR). An image that loads has the size its header states and finite,
// non-negative pixels.
#include "fuzz_common.hpp"
#include "surfscatter/io/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    const auto path = fuzz::write_input("image.hdr", fuzz::as_text(data, size));
    fuzz::expect_clean([&] {
        const io::Image image = io::read_image(path);
        FUZZ_CHECK(image.channels == 3);
        FUZZ_CHECK(image.pixels.size() == static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
        for (float v : image.pixels) FUZZ_CHECK(std::isfinite(v) && v >= 0);
    });
    return 0;
}
