#include "surfscatter/material/conductor.hpp"

#include "surfscatter/core/error.hpp"

namespace surfscatter::material {

Conductor Conductor::perfect() { return Conductor(nullptr); }

Conductor::Conductor(std::shared_ptr<const RefractiveIndex> ior) : ior_(std::move(ior)) {}

Conductor Conductor::from_name(const std::string& name_or_path) {
    if (name_or_path == "perfect") return perfect();
    return Conductor(load_refractive_index(name_or_path));
}

std::complex<double> Conductor::ior(double lambda_nm) const {
    if (is_perfect()) fail("the perfect conductor has no finite refractive index");
    return ior_->at(lambda_nm);
}

FresnelSP Conductor::reflectance_sp(double cos_theta, double lambda_nm) const {
    if (is_perfect()) return {1.0, 1.0};
    return fresnel_conductor_sp(cos_theta, ior_->at(lambda_nm));
}

std::string Conductor::name() const { return is_perfect() ? "perfect" : ior_->name(); }

}  // namespace surfscatter::material
