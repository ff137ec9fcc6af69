// Dust opacities per grain size and wavelength (RBO24 sec. 4.2), set up once
// on the host: simple functional forms, the two table formats in use, and
// their interpolation to the run's sizes and wavelengths with monotone
// piecewise-cubic Hermite interpolation (Fritsch & Carlson 1980) in
// log(lambda), log(a) and log(kappa).
//
// Table formats:
//  * DSHARP / cuDisc: a header line "n_a n_lambda", then n_a x n_lambda rows
//    "a[cm] lambda[um] k_abs k_sca [g]", sizes outer and wavelengths inner;
//    with the asymmetry factor g the effective scattering opacity is
//    k_sca (1 - g).
//  * RADMC-3D `dustkappa_*.inp` (one grain size per file): comment lines
//    starting with '#', then iformat (1, 2 or 3), n_lambda, and n_lambda rows
//    "lambda[um] k_abs [k_sca [g]]".
// A malformed file (wrong counts, non-numeric or negative values, axes that do
// not increase) is an OpacityFileError naming the file and line.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace mote::radiation {

/// Opacities in cm^2 per gram of dust, (size, wavelength) row-major.
struct OpacityTable {
  std::vector<double> sizes_cm, wavelengths_cm;
  std::vector<double> absorption, scattering;  // effective scattering k_sca (1 - g)
  int sizes() const { return static_cast<int>(sizes_cm.size()); }
  int wavelengths() const { return static_cast<int>(wavelengths_cm.size()); }
  double k_abs(int a, int l) const { return absorption[a * wavelengths() + l]; }
  double k_sca(int a, int l) const { return scattering[a * wavelengths() + l]; }
};

class OpacityFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// kappa_abs and kappa_sca independent of size and wavelength.
OpacityTable grey_opacity(const std::vector<double>& sizes_cm, const std::vector<double>& wavelengths_cm,
                          double kappa_abs, double kappa_sca);

/// Geometric cross-section per mass 3 / (4 rho_grain a) times the efficiency
/// Q_abs = min(1, (2 pi a / lambda)^beta) (the power law in wavelength with a
/// size cut-off of RBO24 sec. 4.2); no scattering.
OpacityTable power_law_opacity(const std::vector<double>& sizes_cm, const std::vector<double>& wavelengths_cm,
                               double rho_grain, double beta);

OpacityTable read_dsharp_table(const std::string& path);
OpacityTable read_radmc_dustkappa(const std::string& path, double size_cm);

/// Monotone cubic Hermite interpolation (Fritsch & Carlson 1980) of y(x) at
/// xq; x strictly increasing, xq inside [x.front(), x.back()].
std::vector<double> pchip(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& xq);

/// The table at other sizes and wavelengths, interpolated in log-log space
/// (PCHIP in wavelength, then in size). Throws std::invalid_argument if a
/// requested size or wavelength lies outside the table.
OpacityTable interpolate(const OpacityTable& table, const std::vector<double>& sizes_cm,
                         const std::vector<double>& wavelengths_cm);

/// Means over the coarse bands (edges band_edges_cm; the outer two stand for
/// 0 and infinity) of a table given at the centres of fine wavelength bins
/// (fine_edges_cm, one more than the table's wavelengths), at temperature T:
/// the Planck mean of the absorption and the Rosseland mean of absorption +
/// scattering (weights dB/dT), per size: (size, band) row-major.
struct BandMeans {
  std::vector<double> planck_absorption, rosseland_total;
};
BandMeans band_means(const OpacityTable& fine, const std::vector<double>& fine_edges_cm,
                     const std::vector<double>& band_edges_cm, double T);

/// The coarse band of every fine bin (by its central wavelength; the outer band edges stand for 0
/// and infinity): non-decreasing. Throws std::invalid_argument for a band that holds no fine bin.
std::vector<int> fine_bin_bands(const std::vector<double>& fine_edges_cm, const std::vector<double>& band_edges_cm);

}  // namespace mote::radiation
