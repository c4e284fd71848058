// Fuzz target: the PNG/JPEG/TIFF reader (io/raster.hpp, read_raster: libpng, libjpeg and libtiff behind our own
// memory input, error handlers and size checks; read_photo and read_image go through it). A file that loads has the
// size, channels and depth it states and samples within its depth.
#include "fuzz_common.hpp"
#include "surfscatter/io/raster.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    const auto path = fuzz::write_input("image", fuzz::as_text(data, size));  // the decoder is chosen by content
    fuzz::expect_clean([&] {
        const io::Raster raster = io::read_raster(path);
        FUZZ_CHECK(raster.width > 0 && raster.height > 0);
        FUZZ_CHECK(raster.channels == 1 || raster.channels == 3 || raster.channels == 4);
        FUZZ_CHECK(raster.bit_depth == 8 || raster.bit_depth == 16);
        FUZZ_CHECK(raster.samples.size() == static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height) *
                                                static_cast<std::size_t>(raster.channels));
        if (raster.bit_depth == 8)
            for (std::uint16_t s : raster.samples) FUZZ_CHECK(s <= 255);
    });
    return 0;
}
