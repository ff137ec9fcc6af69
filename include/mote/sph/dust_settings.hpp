// Settings of the SPH dust methods (one-fluid: PL15, MULTIGRAIN HPL18; two-fluid:
// LAB15) and their deck table [dust]: method, number of species, evolved variable (eps_j or
// S_j = sqrt(rho eps_j), PL15 app. B / HPL18 eq. 51), discretisation of the
// dust diffusion equation (two first derivatives, PL15 eq. 26, 29-30; direct
// second derivatives, PL15 eq. 43 / HPL18 eq. 51), energy variable (u, PL15
// eq. 27/45 and HPL18 eq. 56; u~ = (1 - eps) u, HPL18 eq. 55), the velocity
// of the PdV work (PL15 eq. 13: div v; or div v_g with drag heating), drag law
// (constant K_j, Epstein, constant t_s; PL15 eq. 19-20, HPL18 eq. 12-17),
// grain sizes from a list or the power law of HPL18 eq. 63, and the
// time-step criterion (HPL18 eq. 44 or PL15 eq. 16).
#pragma once

#include <string>
#include <vector>

#include "mote/core/deck_schema.hpp"
#include "mote/core/kokkos_types.hpp"
#include "mote/sph/dust_drag.hpp"

namespace mote::sph {

/// Deck rule of a problem set up for one dust method: dust.method (when the
/// table is there) must be one of the given names.
core::DeckRule requires_dust_method(const std::string& problem, const std::vector<std::string>& methods);

enum class DustVariable : int { Epsilon = 0, SqrtRhoEps = 1 };
enum class DustDiscretisation : int { SecondDerivatives = 0, FirstDerivatives = 1 };
enum class DustEnergy : int { U = 0, UTilde = 1 };
enum class DustTimestep : int { Combined = 0, Separate = 1 };
/// PdV work of the gas: div v (PL15 eq. 13, footnote 2) or div v_g plus drag heating
/// (LP14a's first-order form), rho_g du/dt += div(P D grad P / rho_g), see one_fluid_dust.hpp.
enum class DustPdV : int { Barycentric = 0, Gas = 1 };
/// Dust method: one-fluid terminal velocity (PL15, N species HPL18) or dust particles with pairwise drag (LAB15).
enum class DustMethod : int { OneFluid = 0, TwoFluid = 1 };
/// Two-fluid drag update: LAB15 eq. 17-19 (improved) or eq. 4-6 (original, excess drag under differential forces).
enum class TwoFluidDrag : int { Improved = 0, Original = 1 };
/// Pair coefficient of PL15 eq. 43: D_a + D_b (paper), or that limited to 2 D of the donor.
enum class DustFlux : int { Arithmetic = 0, DonorLimited = 1 };

/// Per-species drag parameters on the device (one View extent per species):
/// K_j (ConstantK, else 1), s_j (Epstein, else 0), t_sj (ConstantStoppingTime, else 0).
struct SpeciesDrag {
  RealView1 k_drag, size, stopping_time;
};

struct DustSettings {
  DustMethod method = DustMethod::OneFluid;
  TwoFluidDrag drag_scheme = TwoFluidDrag::Improved;  ///< two-fluid only
  int nspecies = 1;
  DustVariable variable = DustVariable::Epsilon;
  DustDiscretisation discretisation = DustDiscretisation::SecondDerivatives;
  DustFlux flux = DustFlux::Arithmetic;  ///< eps variable, direct second derivatives
  DustEnergy energy = DustEnergy::U;
  DustPdV pdv = DustPdV::Barycentric;
  DragLaw drag = DragLaw::ConstantK;
  std::vector<Real> k_drag{1000.0};      ///< K_j (ConstantK); one value = all species
  std::vector<Real> sizes{1.0};          ///< s_j (Epstein), code length
  Real rho_grain = 1.0;                  ///< intrinsic grain density (Epstein), code density
  std::vector<Real> stopping_time{0.1};  ///< t_s per species (ConstantStoppingTime)
  std::vector<Real> eps;                 ///< initial eps_j (uniform), when the problem does not set them
  DustTimestep timestep = DustTimestep::Combined;
  Real c_dust = 0.3;              ///< C0 of HPL18 eq. 44 / PL15 eq. 16
  bool floor_negative = true;     ///< PL15 sec. 4.4.2: eps_j < 0 -> 0, removed mass reported
  bool project_mass = true;       ///< S variable: rescale q_j after each step to the step's dust mass
  bool limit_ts = false;          ///< t_sj <= h / c_s wherever t_sj enters (Ballabio et al. 2018 flux limiter)
  bool write_velocities = false;  ///< snapshots hold v_dj = v_g + Dv_j per species (HPL18 eq. 24-25)

  /// Declares the optional table [dust] (method, species, drag, sizes, ...).
  static void declare(core::DeckSchema& schema);
  /// Reads [dust] (sizes from a list or the HPL18 eq. 63 power law).
  static DustSettings from_deck(const core::Deck& deck);

  /// The per-species drag parameters of the drag law, copied to the device (labels prefixed with `label`).
  SpeciesDrag species_drag(const std::string& label) const;
  /// Per-species value of a list given with one or nspecies entries.
  Real species_value(const std::vector<Real>& list, int j) const;
  /// Phantom dump header values (grainsize, graindens) per species: s_j and rho_grain
  /// with Epstein drag, 0 for the drag laws that set no grain (SPLASH then labels the species "dust").
  std::vector<Real> grain_sizes() const;
  std::vector<Real> grain_densities() const;
  /// Throws std::invalid_argument on an inconsistent set.
  void validate() const;
};

}  // namespace mote::sph
