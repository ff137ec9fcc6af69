// Set-ups of the one-fluid dust test problems of PL15 sec. 4 (VALIDATION
// A1-A3), shared by the problem executables (problems/sph_dusty*) and the unit
// tests: the dustywave (PL15 sec. 4.1), the dustyshock (sec. 4.2) and the
// dustydiffuse problem with its self-similar solution (sec. 4.3, eq. 51-52).
// The caller supplies the numerical choices (SphConfig: kernel, h_fact,
// viscosity, Courant number, gamma or c_s) and the dust settings (species,
// variable, discretisation, energy variable, drag law with K_j or t_s, and
// eps_j for the uniform problems); the set-up fills in what the problem fixes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/dust_settings.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::core {
class DeckSchema;
}

namespace mote::sph {

/// Declares the [dust] table of a dust problem with the rules its deck must
/// meet: the table present, with the drag law that the problem's reference
/// solution assumes and, for uniform set-ups, a total eps in (0, 1).
void declare_dust_problem(core::DeckSchema& schema, const std::string& problem, DragLaw drag, bool uniform_eps);

struct DustProblem {
  SphConfig cfg;
  Box box;
  ParticleSetup particles;  ///< u is the gas specific energy (converted for dust.energy = u_tilde)
  DustSettings dust;
  std::vector<Real> eps;  ///< initial eps_j (n x N, row-major); empty: uniform dust.eps

  /// A system with particles and dust set, not yet initialised.
  std::unique_ptr<SphSystem> make_system() const;
};

/// PL15 sec. 4.1: x in [0, 1) periodic, rho_g0 = 1, eps0 = sum of dust.eps,
/// v = A sin(2 pi x), rho = rho0 (1 + A sin(2 pi x)) with equal particle
/// masses, du = P0 / rho_g0^2 drho_g, adiabatic with c_s^2 = gamma P0 / rho_g0 = 1.
struct DustyWave {
  int n = 100;
  Real amplitude = 1e-4;
};
DustProblem dustywave(const DustyWave& w, SphConfig cfg, const DustSettings& dust);

/// PL15 sec. 4.2: gas Sod tube (rho_g, v, P) = (1, 0, 1) | (0.125, 0, 0.125)
/// with uniform eps = sum of dust.eps, equal masses (left spacing dx_left), in
/// x in [-1, 1] periodic: the interface at x = +-1 does not reach [-0.5, 0.5]
/// before t = 0.2.
struct DustyShock {
  Real dx_left = 0.001;
  Real rhog_left = 1.0, P_left = 1.0, rhog_right = 0.125, P_right = 0.125;
};
DustProblem dustyshock(const DustyShock& s, SphConfig cfg, const DustSettings& dust);

/// PL15 sec. 4.3: rho = 1 in [-0.5, 0.5]^3 periodic, isothermal (cfg.cs_iso),
/// eps(r, 0) of eq. 52 split equally over the species; cubic lattice of n^3
/// particles or the close-packed lattice of spacing 1 / n (n = 50: 50 x 58 x 62).
struct DustyDiffuse {
  int n = 16;
  bool close_packed = false;
  Real eps0 = 0.1, r_c = 0.25;
};
DustProblem dustydiffuse(const DustyDiffuse& d, SphConfig cfg, const DustSettings& dust);

/// PL15 eq. 51: eps = A |10 eta t + B|^(-3/5) - r^2 / (10 eta t + B), with
/// B = r_c^2 / eps0 and A = eps0 B^(3/5) so that t = 0 gives eq. 52, eta =
/// t_s c_s^2; zero where negative (outside the dust cloud).
Real dustydiffuse_eps(const DustyDiffuse& d, Real eta, Real r, Real t);

}  // namespace mote::sph
