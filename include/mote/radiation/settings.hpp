// The [radiation] deck table (RBO24 sec. 4): FLD bands and stellar bins,
// boundaries, linear-solver settings, the star and the dust opacities.
// Every key is validated, and the cross-key rules (bands no more than stellar
// bins, lambda_max > lambda_min, an opacity file that exists for the table
// formats) run with the deck, before anything is allocated.
#pragma once

#include <string>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/irradiation.hpp"
#include "mote/radiation/opacity.hpp"

namespace mote::radiation {

struct RadiationDeck {
  FldSettings fld;
  std::vector<double> stellar_bin_edges_cm;  // log-spaced over [lambda_min, lambda_max]
  Star star;                                 // radius in code units
  std::string opacity;                       // "grey" | "power-law" | "dsharp" | "radmc"
  std::string opacity_file;
  double kappa_abs = 0.0, kappa_sca = 0.0;  // grey, cm^2/g
  double beta = 1.0;                        // power-law
  double rho_grain = 1.6;                   // g/cm^3, power-law
  double kappa_gas = 0.0;                   // gas opacity floor, cm^2 per g of gas
  double T_binning = 100.0;                 // K, for the band means
  bool band_means_at_cell_T = false;        // band_means = "local": per cell at its temperature

  /// The opacity table at the species' sizes and the stellar bins' centres.
  OpacityTable opacities(const std::vector<double>& sizes_cm) const;
};

void declare(core::DeckSchema& schema);
RadiationDeck from_deck(const core::Deck& deck, const units::UnitSystem& units);

/// n + 1 logarithmically spaced edges from lo to hi.
std::vector<double> log_wavelength_edges(double lo, double hi, int n);

}  // namespace mote::radiation
