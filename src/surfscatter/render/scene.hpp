#pragma once
// A loaded scene: shapes in an Embree 3 BVH, their materials and emitters, the camera, film, sampler and integrator
// settings. Immutable after commit(); intersect() and occluded() may be called from many threads.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "surfscatter/render/camera.hpp"
#include "surfscatter/render/emitter.hpp"
#include "surfscatter/render/filter.hpp"
#include "surfscatter/render/material.hpp"
#include "surfscatter/render/shape.hpp"

namespace surfscatter::render {

// Limits of a scene (docs/RELIABILITY.md). Embree stores positions as float: coordinates up to 1e15 (and products
// of them in the tracer) stay finite and far from float's 3.4e38.
inline constexpr double kMaxSceneCoordinate = 1e15;
// A film side, in pixels; the memory the film needs is checked against what is available as well.
inline constexpr int kMaxFilmSide = 1 << 16;
// Exposure in stops, either way: 2^64 times any finite radiance of a scene stays inside float.
inline constexpr double kMaxExposureStops = 64;

struct FilmSettings {
    int width = 768;
    int height = 576;
    FilterPtr filter;                  // null: Mitsuba's default gaussian (stddev 0.5)
    bool sample_border = false;        // false: samples stay inside the crop window (Mitsuba's default)
    std::string pixel_format = "rgb";  // luminance, luminance_alpha, rgb, rgba, xyz, xyza
    std::string component_format = "float16";  // float16, float32, uint32 (Mitsuba's default: float16)
    double exposure = 0;              // stops: linear values are scaled by 2^exposure
    std::string white_balance = "d65"; // "d65" (none), or a blackbody temperature in K such as "2700"
    // Mitsuba's crop window: only pixels [crop_offset, crop_offset + crop_size) of the full film are rendered, and
    // the output image is the crop. crop_width = crop_height = 0 means the whole film.
    int crop_offset_x = 0, crop_offset_y = 0, crop_width = 0, crop_height = 0;
    int output_width() const { return crop_width > 0 ? crop_width : width; }
    int output_height() const { return crop_height > 0 ? crop_height : height; }
    // Throws Error naming the bad setting: sizes outside [1, kMaxFilmSide], a crop window leaving the film, more
    // memory than is available, an exposure beyond kMaxExposureStops or an unknown white balance.
    void check() const;
};

struct SamplerSettings {
    int sample_count = 4;
    std::uint64_t seed = 0;
};

struct IntegratorSettings {
    std::string type = "path";  // path or direct
    int max_depth = -1;  // path: -1 unbounded, 1 = emitters seen directly, 2 = direct lighting, ...
    int rr_depth = 5;    // path: first depth at which Russian roulette may end a path
    bool hide_emitters = false;  // emitters seen directly by the camera are black
    // path: which strategies reach emitters: "mis" (both, combined), "bsdf" (BSDF sampling only), "emitter"
    // (next-event estimation only, plus emitters seen through delta lobes). The last two exist to test the first.
    std::string strategy = "mis";
    int emitter_samples = 1;  // direct: next-event samples per camera ray
    int bsdf_samples = 1;     // direct: BSDF samples per camera ray
};

struct Hit {
    double t = 0;
    Vec3 p;
    Vec3 ng;  // geometric normal, unit, on the shape's outward side
    Vec3 ns;  // shading normal (interpolated vertex normals or ng)
    Vec2 uv;
    Vec3 dpdu, dpdv;  // world
    int shape = -1;
    // False on a mesh triangle without a uv map (or with a degenerate one): dp/du is then the triangle's first edge,
    // which turns from triangle to triangle.
    bool tangent_from_uv = true;
    // Mitsuba's shading frame: n = ns, s = dp/du made orthogonal to n. Without a uv tangent, s is Frame(ns)'s
    // (continuous in ns except at ns = -z), so that anisotropic materials (alpha_u != alpha_v, a lay) keep one
    // orientation across the triangles of a mesh; docs/RENDERER.md lists each shape's tangent.
    Frame shading_frame() const;
};

class Scene {
public:
    Scene();
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    // `radiance` (may be null) makes the shape an area emitter on its front face.
    void add_shape(ShapeGeometry geometry, MaterialPtr material, SpectrumPtr radiance);
    void add_emitter(EmitterPtr emitter);
    void commit();

    std::optional<Hit> intersect(const Ray& ray) const;
    bool occluded(const Vec3& origin, const Vec3& direction, double t_max) const;

    const Material* material(int shape) const;
    // Radiance leaving shape `shape` toward -direction (0 if not an emitter or seen from its back).
    SampledSpectrum emitted(const Hit& hit, const Vec3& direction, const SampledWavelengths& w) const;
    // Solid-angle pdf that sample_emitter() produces a ray from `from` to `hit` (area emitters).
    double emitter_pdf(const Vec3& from, const Hit& hit, const Vec3& direction) const;
    // Emitters at infinity (constant, envmap) seen along `direction` by a ray that leaves the scene, and the
    // solid-angle density with which sample_emitter() produces that direction.
    bool has_environment() const { return !environments_.empty(); }
    SampledSpectrum environment(const Vec3& direction, const SampledWavelengths& w) const;
    double environment_pdf(const Vec3& direction) const;
    // One emitter chosen uniformly (Mitsuba's choice), then a direction toward it; the pdf includes the choice.
    std::optional<EmitterSample> sample_emitter(const Vec3& p, double u_choice, Vec2 u, const SampledWavelengths& w) const;
    std::size_t emitter_count() const;

    // Offset origin for a ray leaving `hit` in `direction` (avoids re-hitting the surface).
    static Vec3 offset_origin(const Hit& hit, const Vec3& direction);

    CameraSettings camera;
    FilmSettings film;
    SamplerSettings sampler;
    IntegratorSettings integrator;
    // For the user, from the loader: each height map read and its valid fraction, what the models report about
    // themselves (e.g. how a measured PSD is extrapolated, with the bsdf's file and line).
    std::vector<std::string> notes;
    // Every file the loader read besides the scene file itself (includes, meshes, textures, spectra, height maps,
    // measured BSDFs, index tables), as resolved (-D values substituted), each with what named it ("filename at
    // scene.xml:9"): a render's outputs must replace none of them (core/output_files.hpp).
    struct LoadedFile {
        std::filesystem::path path;
        std::string named_by;
    };
    std::vector<LoadedFile> loaded_files;

private:
    struct Shape;
    struct Embree;
    std::size_t emitter_choices() const { return area_emitters_.size() + emitters_.size(); }
    std::vector<Shape> shapes_;
    std::vector<int> area_emitters_;        // shape indices
    std::vector<EmitterPtr> emitters_;      // the others
    std::vector<const Emitter*> environments_;
    std::unique_ptr<Embree> embree_;
};

}  // namespace surfscatter::render
