// Mitsuba's `normalmap` BSDF adapter: the nested BSDF seen through shading normals read from an RGB texture.
//
// Supported: `normalmap` (a bitmap texture, normally with raw = true; its linear RGB c gives the normal
// n' = normalize(2 c - 1) in the local shading frame, x along dp/du) and one nested BSDF. The frame's first axis is
// dp/du made orthogonal to n' (perturbed_frame.hpp evaluates the nested BSDF there).
// Not supported (an error): a normal map that is not a bitmap.
// Differences: dp/du is taken in the local shading frame (Mitsuba mixes it in from world space).
#include "surfscatter/render/bsdfs/perturbed_frame.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class NormalMap final : public PerturbedFrameMaterial {
public:
    NormalMap(TexturePtr normals, MaterialPtr nested)
        : PerturbedFrameMaterial(std::move(nested)), normals_(std::move(normals)) {}

protected:
    Frame frame(const ShadingPoint& sp) const override {
        const Vec3 c = normals_->eval_rgb(sp.uv).value_or(Vec3(0.5, 0.5, 1));
        const Vec3 n = c * 2.0 - Vec3(1, 1, 1);
        if (!(n.length() > 0)) return Frame();
        return frame_from_normal_and_tangent(normalize(n), sp.dpdu);
    }

private:
    TexturePtr normals_;
};

}  // namespace

MaterialPtr plugins::normalmap(Properties& props) {
    TexturePtr normals = props.get_texture_required("normalmap");
    if (!normals->eval_rgb({0.5, 0.5})) props.fail_param("normalmap", "normalmap must be a bitmap texture");
    std::vector<MaterialPtr> nested = props.take_bsdfs();
    if (nested.size() != 1) props.fail("normalmap needs exactly one nested BSDF, got {}", nested.size());
    return std::make_shared<NormalMap>(std::move(normals), nested[0]);
}

}  // namespace surfscatter::render
