// Dust opacities on the device for the temperature solver (RBO24 sec. 4.1-4.2):
// the extinction and absorption of every species at the fine stellar bins, and
// from them, per species, the Planck mean of the absorption and the Rosseland
// mean of the total opacity in every FLD band at a binning temperature
// (band_means). The solver's fields are filled either from those fixed means,
// summed over species weighted by the dust densities, or (RBO24 sec. 4.2, as
// cuDisc bins its opacities) per cell at the cell's temperature: the Planck
// mean over the band's fine bins of the mixture's absorption and the Rosseland
// mean of its total opacity. Both add the gas opacity floor rho_g kappa_gas of
// RBO24 sec. 7 to absorption and extinction alike.
#pragma once

#include <vector>

#include "mote/core/units.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/opacity.hpp"

namespace mote::radiation {

struct DustOpacities {
  RealView2 planck_absorption;   // (species, band), code units (length^2 / mass)
  RealView2 rosseland_total;     // (species, band)
  RealView2 stellar_extinction;  // (species, bin)
  RealView2 stellar_absorption;  // (species, bin)
  RealView1 bin_edges_cm;        // (bin + 1), the stellar bins' wavelength edges
  IntView1 band_first_bin;       // (band + 1): band b holds the bins [band_first_bin(b), band_first_bin(b + 1))

  /// `table`: opacities (cm^2/g) at the species' sizes and at the centres of
  /// the stellar bins `bin_edges_cm`; the band means are taken at T_binning.
  static DustOpacities from_table(const OpacityTable& table, const std::vector<double>& bin_edges_cm,
                                  const std::vector<double>& band_edges_cm, double T_binning,
                                  const units::UnitSystem& units);
};

/// fields.absorption(i, j, b) = sum_s rho_s(i, j) kappa_P,s^b + rho_g kappa_gas, and
/// fields.extinction likewise with the Rosseland means; kappa_gas in code units.
void fill_fld_opacities(const DustOpacities& opacities, const RealView3& rho_dust, const RealView2& rho_gas,
                        Real kappa_gas, const FldFields& fields);

/// The same fields from means over each band's stellar bins taken per cell at its temperature T (K):
/// fields.absorption(i, j, b) the Planck mean of the cell's absorption at the bins, fields.extinction
/// the Rosseland mean of its extinction, from the mixtures (dust and the gas floor) that
/// fill_stellar_opacities gives (the species summed once per update, not once per lagged solve).
/// A band without weight at T (far in the Wien tail) takes the plain means over its bins. Ghost
/// cells take the temperature of the nearest active cell of `grid`.
void fill_fld_opacities_at(const DustOpacities& opacities, const RealView3& extinction_at_bins,
                           const RealView3& absorption_at_bins, const RealView2& T, const mesh::Grid& grid,
                           const FldFields& fields);

/// extinction(i, j, B) and absorption(i, j, B) at the stellar bins, for StellarIrradiation::heat.
void fill_stellar_opacities(const DustOpacities& opacities, const RealView3& rho_dust, const RealView2& rho_gas,
                            Real kappa_gas, const RealView3& extinction, const RealView3& absorption);

}  // namespace mote::radiation
