#pragma once
// A measured BRDF as the fit reads it (docs/FIT.md): one row per (wavelength, incidence, outgoing direction), angles
// in degrees in the local frame of docs/CONVENTIONS.md (directions away from the surface, phi from +x), the BRDF in
// 1/sr without the cosine, and optionally its standard error.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace surfscatter::inverse {

struct BrdfData {
    std::vector<double> wavelength_nm, theta_i_deg, phi_i_deg, theta_o_deg, phi_o_deg, brdf;
    std::vector<double> brdf_stderr;  // empty: no errors given (the fit then uses relative residuals)
    std::vector<int> line;            // the row's line in its file (for messages), or its index from 1
    std::string source;               // where the rows came from ("meas.csv", "data"), named in messages
    std::size_t size() const { return brdf.size(); }
};

// The CSV header: wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,brdf and optionally brdf_stderr, in
// that order. Blank lines and '#' lines are skipped (core/input_file.hpp).
BrdfData parse_brdf_csv(std::string_view text, const std::string& source);
BrdfData read_brdf_csv(const std::string& path);

// An RGL measured file (bsdf/rgl_measured.hpp; real gonio-photometer measurements or `brdf export`) as fit data: at
// each of the file's incidences below 89 degrees (theta_i nodes; and each phi_i node of an anisotropic file but a
// repeated +pi), the outgoing directions of its sample-square nodes, where the file holds its values (each node mapped
// through the incidence's VNDF warp to a half vector, as a reader maps it back), every k-th node per side so that
// at most max_directions directions remain, evaluated as Mitsuba 3 reads the file at `wavelengths_nm` (spectral
// files: within their wavelengths; rgb files: the reader's spectrum of the node's colour, docs/FIT.md). Directions
// with theta_o >= 89 degrees and zero values are left out; no standard errors. The file's `valid` field is not used
// (no reader defines it).
BrdfData read_brdf_rgl(const std::string& path, const std::vector<double>& wavelengths_nm,
                       std::size_t max_directions = 1000);

// Throws Error naming the first bad row ("meas.csv:7: brdf must be finite and >= 0, got -0.1"): wavelengths > 0,
// theta_i and theta_o in [0, 90) (a direction at or below the horizon is refused), finite azimuths, BRDF finite and
// >= 0 (> 0 without brdf_stderr: the residuals are then relative), errors finite and > 0; at least two distinct
// outgoing directions. Columns of unequal length are an Error too (data given as arrays).
void validate(const BrdfData& data);

// How messages name row j: "meas.csv:7" (its line), or "data row 8".
std::string row_name(const BrdfData& data, std::size_t j);

}  // namespace surfscatter::inverse
