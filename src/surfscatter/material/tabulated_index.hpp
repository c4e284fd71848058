#pragma once
// Refractive index from a table of (wavelength, n, k), linearly interpolated in wavelength. Outside the table it is
// an error (no extrapolation). Also the loader for plain CSV files `wavelength_nm,n,k`.
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/material/refractive_index.hpp"

namespace surfscatter::material {

// y(x) by linear interpolation between rows with strictly increasing x; x must lie in [front, back] (the caller
// checks the range and names the source).
class LinearTable {
public:
    LinearTable() = default;
    // Throws Error (naming `source`) unless x is strictly increasing, x and y are finite and have equal sizes >= 1.
    LinearTable(std::vector<double> x, std::vector<double> y, const std::string& source);
    double operator()(double x) const;
    double min_x() const { return x_.front(); }
    double max_x() const { return x_.back(); }
    std::size_t size() const { return x_.size(); }

private:
    std::vector<double> x_, y_;
};

// The one check of a tabulated n or k (CSV rows, refractiveindex.info tables, built-in tables): finite and >= 0, as
// N = n + i k of a passive medium is (docs/CONVENTIONS.md). `name` is "n" or "k", `where` names the row.
void check_index_value(double value, const char* name, const std::string& where);

class TabulatedIndex final : public RefractiveIndex {
public:
    // `name` is used in error messages (a file path or a material name). n and k must be >= 0.
    TabulatedIndex(std::string name, std::vector<double> lambda_nm, std::vector<double> n, std::vector<double> k);
    std::complex<double> at(double lambda_nm) const override;
    double min_wavelength_nm() const override { return n_.min_x(); }
    double max_wavelength_nm() const override { return n_.max_x(); }
    std::string name() const override { return name_; }

private:
    std::string name_;
    LinearTable n_, k_;
};

// CSV with rows `wavelength_nm,n,k`: lines starting with '#' and blank lines are skipped, one optional header row
// (first field not a number) is allowed. Throws Error naming path:line for anything malformed.
std::shared_ptr<const RefractiveIndex> load_csv_refractive_index(const std::string& path);
// Same from the file's text; `path` names it in messages.
std::shared_ptr<const RefractiveIndex> parse_csv_refractive_index(const std::string& text, const std::string& path);

}  // namespace surfscatter::material
