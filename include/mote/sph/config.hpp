// Run-time parameters of the SPH engine, with the defaults of PL15 sec. 3:
// h_fact = 1.2 (1.0 with M6), alpha = 1, beta = 2 (eq. 31-32), alpha_u = 1
// (eq. 34-35), Courant number 0.3, h-rho tolerance 1e-4.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/kernels.hpp"

namespace mote::sph {

enum class EosType { Isothermal = 0, Adiabatic = 1 };

struct SphConfig {
  int dim = 3;
  KernelType kernel = KernelType::M4;
  Real hfact = 0.0;  ///< h / particle spacing; <= 0 selects default_hfact(kernel)

  // Equation of state (PL15 eq. 14, or P = c_s^2 rho).
  EosType eos = EosType::Adiabatic;
  Real gamma = 5.0 / 3.0;
  Real cs_iso = 1.0;  ///< isothermal sound speed

  // Shock capturing (PL15 eq. 31-35).
  Real alpha = 1.0;            ///< linear viscosity (initial / fixed value)
  Real beta = 2.0;             ///< von Neumann-Richtmyer viscosity
  Real alpha_u = 1.0;          ///< artificial conductivity
  bool cullen_dehnen = false;  ///< Cullen & Dehnen (2010) switch for alpha
  Real alpha_min = 0.0;        ///< switch floor
  Real alpha_max = 1.0;        ///< switch ceiling

  // Velocity damping (PL15 eq. 56), for relaxation; 0 = off.
  Real damping = 0.0;

  // Time-step criteria.
  Real c_cour = 0.3;
  Real c_force = 0.25;
  Real dt_max = 1e30;

  // Density iteration.
  Real h_tol = 1e-4;
  int h_max_iter = 50;

  // Neighbour list skin: relative growth of h and absolute displacement
  // (as a fraction of the smallest support radius) tolerated before a rebuild.
  Real skin = 0.1;

  Real effective_hfact() const { return hfact > 0.0 ? hfact : default_hfact(kernel); }
};

}  // namespace mote::sph
