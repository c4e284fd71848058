// Mitsuba's `bumpmap` BSDF adapter: the nested BSDF seen through the shading normal of a surface displaced by a
// height texture (Blinn 1978).
//
// Supported: a nested height texture (any name, as in Mitsuba; its scalar value, eval_1 - a bitmap with raw = true
// is the usual choice), `scale` (default 1) and one nested BSDF. With h the height times scale and the surface's
// dp/du, dp/dv in the shading frame (z = n): dp/du' = dp/du + n (dh/du - n.dp/du), likewise for v, n' = the
// normalised dp/du' x dp/dv' (turned to the side of n), and the frame's first axis dp/du' made orthogonal to n'
// (perturbed_frame.hpp evaluates the nested BSDF there). dh/du comes from the bilinear interpolation of the bitmap.
// Differences: the orientation test uses the shading normal (Mitsuba: the geometric normal).
#include "surfscatter/render/bsdfs/perturbed_frame.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class BumpMap final : public PerturbedFrameMaterial {
public:
    BumpMap(TexturePtr height, double scale, MaterialPtr nested)
        : PerturbedFrameMaterial(std::move(nested)), height_(std::move(height)), scale_(scale) {}

protected:
    Frame frame(const ShadingPoint& sp) const override {
        const Vec2 grad = height_->eval_1_grad(sp.uv) * scale_;
        const Vec3 dpdu(sp.dpdu.x, sp.dpdu.y, grad.x);
        const Vec3 dpdv(sp.dpdv.x, sp.dpdv.y, grad.y);
        Vec3 n = cross(dpdu, dpdv);
        if (!(n.length() > 0)) return Frame();
        n = normalize(n);
        if (n.z < 0) n = -n;
        return frame_from_normal_and_tangent(n, dpdu);
    }

private:
    TexturePtr height_;
    double scale_;
};

}  // namespace

MaterialPtr plugins::bumpmap(Properties& props) {
    const double scale = props.get_float("scale", 1.0);
    std::vector<TexturePtr> textures = props.take_textures();
    if (textures.size() != 1) props.fail("bumpmap needs exactly one nested height texture, got {}", textures.size());
    std::vector<MaterialPtr> nested = props.take_bsdfs();
    if (nested.size() != 1) props.fail("bumpmap needs exactly one nested BSDF, got {}", nested.size());
    return std::make_shared<BumpMap>(textures[0], scale, nested[0]);
}

}  // namespace surfscatter::render
