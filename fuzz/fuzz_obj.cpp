// Fuzz target: the OBJ reader (render/mesh_obj.cpp); a mesh that loads has finite vertices and indices in range.
#include "fuzz_common.hpp"
#include "fuzz_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    fuzz::expect_clean([&] { fuzz::check_mesh(render::parse_obj(fuzz::as_text(data, size), "fuzz.obj")); });
    return 0;
}
