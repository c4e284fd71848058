// Fuzz target: the wavelength_nm,n,k CSV loader (material/tabulated_index.hpp); an index that loads is evaluated
// across its range, where it must be finite.
#include "fuzz_common.hpp"
#include "fuzz_ior.hpp"
#include "surfscatter/material/tabulated_index.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    fuzz::expect_clean([&] {
        fuzz::check_index(*material::parse_csv_refractive_index(std::string(fuzz::as_text(data, size)), "fuzz.csv"));
    });
    return 0;
}
