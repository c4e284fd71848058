// Fuzz target: the colour chart reference reader (photo/color_checker.hpp, `colorcorrect --reference`, an IT8/CGATS
// file of CIELAB values); a reference that loads has finite values for all 24 patches.
#include "fuzz_common.hpp"
#include "surfscatter/photo/color_checker.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    const auto path = fuzz::write_input("chart.cie", fuzz::as_text(data, size));
    fuzz::expect_clean([&] {
        const photo::ChartReference reference = photo::read_chart_reference(path);
        for (std::size_t i = 0; i < photo::kChartPatches; ++i) {
            for (double v : {reference.lab_d50[i].L, reference.lab_d50[i].a, reference.lab_d50[i].b,
                             reference.lab_d65[i].L, reference.lab_d65[i].a, reference.lab_d65[i].b})
                FUZZ_CHECK(std::isfinite(v));
            for (int c = 0; c < 3; ++c) FUZZ_CHECK(std::isfinite(reference.linear_srgb[i][c]));
        }
    });
    return 0;
}
