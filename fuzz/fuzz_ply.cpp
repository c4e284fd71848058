// Fuzz target: the PLY reader (render/mesh_ply.cpp); a mesh that loads has finite vertices and indices in range.
#include "fuzz_common.hpp"
#include "fuzz_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    fuzz::expect_clean([&] { fuzz::check_mesh(render::parse_ply(fuzz::as_text(data, size), "fuzz.ply")); });
    return 0;
}
