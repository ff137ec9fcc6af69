// Dust opacities on the device for the temperature solver (RBO24 sec. 4.1-4.2):
// per species, the Planck mean of the absorption and the Rosseland mean of
// the total opacity in every FLD band, binned from the fine stellar bins
// (band_means at a binning temperature), and the extinction and absorption at
// the stellar bins. Filling the solver's fields sums over species weighted by
// the dust densities and adds the gas opacity floor rho_g kappa_gas of RBO24
// sec. 7 to absorption and extinction alike.
#pragma once

#include <vector>

#include "mote/core/units.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/opacity.hpp"

namespace mote::radiation {

struct DustOpacities {
  RealView2 planck_absorption;   // (species, band), code units (length^2 / mass)
  RealView2 rosseland_total;     // (species, band)
  RealView2 stellar_extinction;  // (species, bin)
  RealView2 stellar_absorption;  // (species, bin)

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

/// extinction(i, j, B) and absorption(i, j, B) at the stellar bins, for StellarIrradiation::heat.
void fill_stellar_opacities(const DustOpacities& opacities, const RealView3& rho_dust, const RealView2& rho_gas,
                            Real kappa_gas, const RealView3& extinction, const RealView3& absorption);

}  // namespace mote::radiation
