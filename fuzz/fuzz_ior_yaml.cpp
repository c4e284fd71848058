// Fuzz target: the refractiveindex.info YAML loader (material/refractiveindex_info.hpp); an index that loads is
// evaluated across its range, where it must be finite or an Error naming the file.
#include "fuzz_common.hpp"
#include "fuzz_ior.hpp"
#include "surfscatter/material/refractiveindex_info.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    fuzz::expect_clean([&] {
        fuzz::check_index(*material::parse_refractiveindex_info_yaml(std::string(fuzz::as_text(data, size)), "fuzz.yml"));
    });
    return 0;
}
