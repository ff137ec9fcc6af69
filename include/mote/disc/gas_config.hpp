// Settings of the gas disc (RBO24 sec. 3.3-3.5), read from the deck tables
// [gas] and [star] and converted to code units:
//  * vertically isothermal temperature T(R) = T_ref (R / R_ref)^(-T_index), or
//    given through the aspect ratio h_ref = H / R at R_ref (cs^2 = h_ref^2 G M / R_ref
//    at R_ref, same power law); cs^2 = k_B T / (mu m_H);
//  * viscosity (sec. 3.4): alpha c_s H = alpha cs^2 / Omega_K(R), or
//    nu_0 (R / R_ref)^nu_index (nu_0 <= 0: nu_0 = alpha cs^2 / Omega_K at R_ref);
//  * initial surface density Sigma_0 (R / R_ref)^(-p) exp(-(R / R_c)^(2 - p))
//    (Lynden-Bell & Pringle 1974 similarity profile; R_c = 0: no taper), times
//    exp(-(R_cavity / R)^k) for an inner cavity (RBO24 sec. 7; R_cavity = 0: none);
//  * the gas v_R: viscous (eq. 28-31) or zero;
//  * boundary conditions of the viscous evolution (eq. 26) at R_in and R_out.
#pragma once

#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/stellar_gravity.hpp"

namespace mote::disc {

enum class ViscosityModel { Alpha, PowerLaw };

/// Radial boundaries of the viscous evolution (eq. 26), on the flux
/// G = 3 R^1/2 d(R^1/2 nu Sigma)/dR through the domain edge:
///   Closed      G = 0 (mass conserved);
///   ZeroTorque  nu Sigma = 0 at the edge (free inflow onto the star / outflow);
///   Extrapolate R^1/2 nu Sigma continued into the ghost as the power law
///               R^k through the two edge cells (exact for a steady
///               accretion disc, which passes through unchanged), with
///               k >= 0 at R_in (outflow only) and k <= 2 at R_out (bounded
///               inflow), which keeps the boundary stable for any data;
///   User        ghost Sigma from a problem hook (GasDisc::set_boundary_values).
enum class GasBoundary { Closed, ZeroTorque, Extrapolate, User };

struct GasConfig {
  // Star.
  double GM = 1.0;                 // G M_star, code units
  bool thin_disc_gravity = false;  // star.potential = "thin_disc"
  // Temperature (vertically isothermal power law).
  double R_ref = 1.0;     // code length
  double T_ref = 100.0;   // K at R_ref
  double T_index = 0.5;   // T proportional to R^-T_index
  double mu = 2.34;       // mean molecular weight
  double cs2_ref = 0.0;   // code velocity^2 at R_ref (derived)
  double cs2_to_T = 0.0;  // T [K] = cs2_to_T * cs2 [code] (derived)
  // Viscosity.
  ViscosityModel viscosity = ViscosityModel::Alpha;
  double alpha = 1e-3;
  double nu0 = 0.0;  // code length^2 / code time (derived when <= 0)
  double nu_index = 1.0;
  // Initial surface density.
  double Sigma0 = 1.0;       // code surface density at R_ref
  double Sigma_index = 1.0;  // p
  double R_c = 0.0;          // taper radius, code length (0: none)
  double R_cavity = 0.0;     // inner cavity radius, code length (0: none)
  double cavity_index = 10.0;
  bool viscous_vR = true;  // false: v_R = 0 (gas.radial_velocity = "zero")
  // Numerics.
  GasBoundary inner = GasBoundary::Extrapolate, outer = GasBoundary::Extrapolate;
  double cfl = 0.5;             // fraction of the explicit (positivity) limit of eq. 26
  double Sigma_floor = 1e-100;  // code surface density
  double rho_floor = 1e-100;    // code density

  StellarGravity gravity() const { return {GM, thin_disc_gravity}; }

  /// Tables [gas] and [star] (star.mass in M_sun). The boundary choice "user" (ghost Sigma from
  /// GasDisc::set_boundary_values) is offered only to a problem that supplies those values.
  static void declare(core::DeckSchema& schema, bool problem_boundary_values = false);
  static GasConfig from_deck(const core::Deck& deck, const units::UnitSystem& units);
  /// Fills the derived values (cs2_ref, cs2_to_T, nu0 when <= 0) from the others;
  /// `h_ref` > 0 sets the temperature from the aspect ratio instead of T_ref.
  void derive(const units::UnitSystem& units, double h_ref);
};

GasBoundary gas_boundary(const std::string& name);

}  // namespace mote::disc
