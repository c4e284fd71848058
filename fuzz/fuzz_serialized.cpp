// Fuzz target: the Mitsuba .serialized mesh reader (render/shapes/serialized.cpp: zlib-compressed, versions 3 and 4);
// a mesh that loads has finite vertices and indices in range.
#include "fuzz_common.hpp"
#include "fuzz_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    fuzz::expect_clean([&] {
        bool face_normals = false;
        const render::TriangleMesh mesh =
            render::parse_serialized(fuzz::as_text(data, size), "fuzz.serialized", 0, face_normals);
        for (const Vec3& n : mesh.normals)  // the reader leaves a zero normal zero; the scene rejects it
            FUZZ_CHECK(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
        render::TriangleMesh without_normals = mesh;
        without_normals.normals.clear();
        fuzz::check_mesh(without_normals);
    });
    return 0;
}
