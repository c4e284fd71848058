// Fuzz target: the scene loader (render/xml_loader.hpp) on arbitrary XML text. The scene's relative file names
// resolve beside a virtual path in the scratch directory; a loaded scene must have a valid film and camera.
#include "fuzz_common.hpp"
#include "surfscatter/render/camera.hpp"
#include "surfscatter/render/xml_loader.hpp"

// Lobe tables a fuzzed scene asks for go to the scratch directory, not the user's cache.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    setenv("SURFSCATTER_CACHE_DIR", (surfscatter::fuzz::scratch() / "cache").c_str(), 1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    fuzz::expect_clean([&] {
        const auto scene = render::load_scene_from_string(std::string(fuzz::as_text(data, size)),
                                                          fuzz::scratch() / "scene.xml");
        scene->film.check();
        const render::Camera camera(scene->camera, scene->film.width, scene->film.height);
        const render::Ray ray = camera.generate_ray(0.5 * scene->film.width, 0.5 * scene->film.height);
        FUZZ_CHECK(std::isfinite(ray.direction.x) && std::isfinite(ray.direction.y) && std::isfinite(ray.direction.z));
    });
    return 0;
}
