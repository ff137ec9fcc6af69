// Deck keys of the coagulation module (table [coagulation]) and the settings
// struct built from them, shared by the standalone problems and the disc
// driver. Physical quantities are in cgs. See docs/coagulation.md.
#pragma once

#include <string>

#include "mote/core/deck.hpp"
#include "mote/core/deck_schema.hpp"
#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

struct CoagulationSettings {
  std::string kernel = "physical";  // constant | additive | product | physical
  Real kernel_coefficient = 1.0;    // K0 of the analytic kernels
  bool vertically_integrated = false;
  bool fragmentation = true;
  Real v_frag = 100.0;                      // cm/s
  Real fragment_slope = 11.0 / 6.0;         // eta of n(m) ~ m^-eta (RBO24 eq. 66)
  Real chi_im = 1.0;                        // RBO24 eq. 68
  std::string product_split = "quadratic";  // quadratic (product_split.hpp) | two-bin (RBO24 eq. 63)
  Real rel_tol = 1e-2;                      // BS32 relative tolerance
  Real abs_tol = 1e-10;                     // BS32 absolute tolerance, times the cell's total dust density
  int max_substeps = 1000000;               // per cell and call
  int cells_per_batch = 1024;               // cells whose pair kernels are held at once
  int team_size = 0;                        // threads per cell's team; 0: chosen per back-end
  Real a_min = 5e-5, a_max = 0.1;           // grain sizes of the first and last species (cm)
  int species = 200;
  Real rho_m = 1.6;  // intrinsic grain density (g/cm^3)
  Real mu = 2.4;     // mean molecular weight (Reynolds number, k_B T = mu m_H c_s^2)
};

/// Declares the [coagulation] table (optional: coagulation is on when present).
void declare(core::DeckSchema& schema);
/// Reads the settings from a validated deck (defaults when [coagulation] is absent).
CoagulationSettings settings_from_deck(const core::Deck& deck);

}  // namespace mote::coagulation
