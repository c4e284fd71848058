// surfscatter ior: complex refractive index N = n + i k of a built-in metal or a data file, as CSV.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "list_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/refractive_index.hpp"

namespace surfscatter::cli {

namespace {

struct IorArgs {
    std::string material;
    std::vector<double> wavelengths;
};

void run_ior(const IorArgs& a) {
    for (double l : a.wavelengths) require_positive(l, "--wavelength");
    const auto ior = material::load_refractive_index(a.material);
    // Evaluate everything first so that a bad wavelength prints nothing but the error.
    std::vector<std::complex<double>> values;
    for (double l : a.wavelengths) values.push_back(ior->at(l));
    std::printf("wavelength_nm,n,k\n");
    for (std::size_t i = 0; i < values.size(); ++i)
        std::printf("%s,%s,%s\n", format_number(a.wavelengths[i]).c_str(), format_number(values[i].real()).c_str(),
                    format_number(values[i].imag()).c_str());
}

const Command command("ior", [](CLI::App& app) {
    auto args = std::make_shared<IorArgs>();
    auto* sub = app.add_subcommand("ior", "Print the complex refractive index n + i k as CSV wavelength_nm,n,k");
    sub->add_option("--material", args->material,
                    "Built-in metal (Ag Al Au Be Cr Cu Ni Pd Pt Ti W, Lorentz-Drude of Rakic 1998), "
                    "a refractiveindex.info .yml file or a wavelength_nm,n,k .csv file")
        ->required();
    add_number_list(sub, "--wavelength", args->wavelengths, "Wavelengths in nm, comma-separated")->required();
    sub->callback([args] { run_ior(*args); });
});

}  // namespace

}  // namespace surfscatter::cli
