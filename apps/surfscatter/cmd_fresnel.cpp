// surfscatter fresnel: exact Fresnel reflectance of a conductor versus the angle of incidence, as CSV.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "list_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::cli {

namespace {

struct FresnelArgs {
    std::string material;
    double wavelength = 0;
    std::vector<double> thetas;
    std::string polarization = "unpolarized";
};

void run_fresnel(const FresnelArgs& a) {
    require_positive(a.wavelength, "--wavelength");
    for (double t : a.thetas) {
        require_finite(t, "--theta");
        if (t < 0 || t >= 90) fail("--theta must be in [0, 90) degrees, got {}", t);
    }
    const auto conductor = material::Conductor::from_name(a.material);
    std::vector<double> reflectances;
    for (double t : a.thetas) {
        const auto r = conductor.reflectance_sp(std::cos(t * kDegree), a.wavelength);
        reflectances.push_back(a.polarization == "s" ? r.rs : a.polarization == "p" ? r.rp : r.unpolarized());
    }
    std::printf("theta_deg,R\n");
    for (std::size_t i = 0; i < a.thetas.size(); ++i)
        std::printf("%s,%s\n", format_number(a.thetas[i]).c_str(), format_number(reflectances[i]).c_str());
}

const Command command("fresnel", [](CLI::App& app) {
    auto args = std::make_shared<FresnelArgs>();
    auto* sub = app.add_subcommand("fresnel", "Print the exact conductor Fresnel reflectance as CSV theta_deg,R");
    sub->add_option("--material", args->material, "Built-in metal, 'perfect', or a .yml/.csv refractive index file")
        ->required();
    sub->add_option("--wavelength", args->wavelength, "Wavelength in nm")->required();
    add_number_list(sub, "--theta", args->thetas, "Angles of incidence in degrees from the normal, in [0, 90), comma-separated")
        ->required();
    sub->add_option("--polarization", args->polarization, "s, p or unpolarized (the mean of s and p)")
        ->check(CLI::IsMember({"s", "p", "unpolarized"}));
    sub->callback([args] { run_fresnel(*args); });
});

}  // namespace

}  // namespace surfscatter::cli
