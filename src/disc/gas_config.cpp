// Deck tables [gas] and [star] of the gas disc (RBO24 sec. 3.3-3.5); see
// include/mote/disc/gas_config.hpp.
#include "mote/disc/gas_config.hpp"

#include <cmath>
#include <string>

#include "mote/core/log.hpp"

namespace mote::disc {

namespace {

/// The viscosity model needs a positive coefficient.
void check_viscosity(const core::Deck& d, core::DeckCheck& check) {
  const std::string& model = d.string("gas.viscosity");
  if (model == "alpha" && !(d.real("gas.alpha") > 0))
    check.fail("gas.alpha", "must be > 0 with " + check.quote("gas.viscosity"));
  if (model == "power_law" && !(d.real("gas.nu0") > 0) && !(d.real("gas.alpha") > 0))
    check.fail("gas.nu0", "or gas.alpha must be > 0 with " + check.quote("gas.viscosity"));
}

/// The hydrostatic column holds Sigma (a grid across the mid-plane, symmetric
/// about it) or Sigma / 2 (a grid from the mid-plane up or down, mirror
/// symmetry): any other theta range holds an unknown part of the column, which
/// eq. 37 would scale to the whole.
void check_column(const core::Deck& d, core::DeckCheck& check) {
  const bool listed = d.string("grid.theta_spacing") == "edges";
  const auto& e = d.real_array("grid.theta_edges");
  if (listed && e.empty()) return;  // the grid's own rule reports the list
  const std::string lo = listed ? "grid.theta_edges" : "grid.theta_min", hi = listed ? lo : "grid.theta_max";
  const double t0 = listed ? e.front() : d.real(lo), t1 = listed ? e.back() : d.real(hi);
  if (t0 > 0.0)
    check.fail(lo, "must start at or below 0 with the gas disc: its hydrostatic column starts at the mid-plane");
  if (t1 < 0.0)
    check.fail(hi, "must end at or above 0 with the gas disc: its hydrostatic column ends at the mid-plane");
  if (t0 < 0.0 && t1 > 0.0 && std::fabs(t0 + t1) > 1e-12 * (t1 - t0))
    check.fail(
        lo, logging::cat("a grid across the mid-plane must be symmetric about it with the gas disc (", t0, " to ", t1,
                         " rad): the hydrostatic column is normalised to Sigma over both "
                         "hemispheres (RBO24 eq. 37); use theta_min = -theta_max, or a grid from the mid-plane"));
}

}  // namespace

GasBoundary gas_boundary(const std::string& name) {
  if (name == "closed") return GasBoundary::Closed;
  if (name == "zero_torque") return GasBoundary::ZeroTorque;
  if (name == "extrapolate") return GasBoundary::Extrapolate;
  if (name == "user") return GasBoundary::User;
  throw core::DeckError("unknown gas boundary '" + name + "' (closed, zero_torque, extrapolate, user)");
}

void GasConfig::declare(core::DeckSchema& s, bool problem_boundary_values) {
  s.table("star", "The central star.");
  if (!s.find_key("star", "mass"))
    s.real("star.mass").default_value(1.0).greater_than(0.0).unit("M_sun").doc("Stellar mass M_star.");
  s.string("star.potential")
      .default_value(std::string("point_mass"))
      .one_of({"point_mass", "thin_disc"})
      .doc(
          "Stellar gravity on gas and dust. point_mass: -G M / r (RBO24); thin_disc: -G M / R + G M Z^2 / (2 R^3), "
          "the thin-disc expansion of Takeuchi & Lin (2002) models (Gaussian isothermal columns).");

  s.table("gas",
          "Gas disc: 1D viscous evolution of Sigma (RBO24 eq. 26), hydrostatic 2D density (eq. 33-37), "
          "velocities (eq. 27-31), vertically isothermal temperature.");
  s.real("gas.R_ref")
      .default_value(1.0)
      .greater_than(0.0)
      .unit("code length")
      .doc("Reference radius of the temperature, viscosity and surface-density power laws.");
  s.real("gas.T_ref")
      .default_value(100.0)
      .greater_than(0.0)
      .unit("K")
      .doc("Temperature at R_ref (RBO24's 100 K at 1 au: R_ref = 1 in au_msun units).");
  s.real("gas.T_index").default_value(0.5).doc("T proportional to (R / R_ref)^-T_index (vertically isothermal).");
  s.real("gas.h_ref")
      .default_value(0.0)
      .min(0.0)
      .doc("Aspect ratio H / R = c_s / (Omega_K R) at R_ref; > 0 sets the temperature instead of T_ref.");
  s.real("gas.mu").default_value(2.34).greater_than(0.0).doc("Mean molecular weight (c_s^2 = k_B T / (mu m_H)).");
  s.string("gas.viscosity")
      .default_value(std::string("alpha"))
      .one_of({"alpha", "power_law"})
      .doc(
          "alpha: nu = alpha c_s H = alpha c_s^2 / Omega_K(R); power_law: nu = nu0 (R / R_ref)^nu_index (RBO24 sec. "
          "3.4).");
  s.real("gas.alpha").default_value(1e-3).min(0.0).doc("Shakura-Sunyaev alpha.");
  s.real("gas.nu0")
      .default_value(0.0)
      .unit("code length^2 / code time")
      .doc("nu at R_ref for viscosity = \"power_law\"; <= 0: alpha c_s^2 / Omega_K at R_ref.");
  s.real("gas.nu_index").default_value(1.0).doc("Exponent of the power-law viscosity.");
  s.real("gas.Sigma0")
      .default_value(1.0)
      .min(0.0)
      .unit("code surface density")
      .doc("Initial Sigma at R_ref (before the taper).");
  s.real("gas.Sigma_index").default_value(1.0).doc("Initial Sigma proportional to (R / R_ref)^-Sigma_index.");
  s.real("gas.R_c")
      .default_value(0.0)
      .min(0.0)
      .unit("code length")
      .doc("Taper exp(-(R / R_c)^(2 - Sigma_index)) of the initial Sigma (Lynden-Bell & Pringle); 0: none.");
  s.real("gas.R_cavity")
      .default_value(0.0)
      .min(0.0)
      .unit("code length")
      .doc(
          "Inner cavity exp(-(R_cavity / R)^cavity_index) of the initial Sigma (RBO24 sec. 7 transition disc); 0: "
          "none.");
  s.real("gas.cavity_index")
      .default_value(10.0)
      .greater_than(0.0)
      .doc("Steepness of the inner cavity (RBO24 sec. 7: 10).");
  s.string("gas.radial_velocity")
      .default_value(std::string("viscous"))
      .one_of({"viscous", "zero"})
      .doc("Gas v_R: viscous (eq. 28-31) or zero (a static disc, as RBO24's transition disc of sec. 7).");
  std::vector<std::string> bcs = {"closed", "zero_torque", "extrapolate"};
  if (problem_boundary_values) bcs.emplace_back("user");
  s.string("gas.inner_boundary")
      .default_value(std::string("extrapolate"))
      .one_of(bcs)
      .doc(
          "Viscous boundary at R_in: closed (no mass flux), zero_torque (nu Sigma = 0), extrapolate "
          "(R^1/2 nu Sigma continued as a limited power law: steady flow passes), user (ghost Sigma from the "
          "problem: viscous_ring's similarity solution; offered by such problems only).");
  s.string("gas.outer_boundary")
      .default_value(std::string("extrapolate"))
      .one_of(bcs)
      .doc("Viscous boundary at R_out (as inner_boundary).");
  s.real("gas.cfl").default_value(0.5).greater_than(0.0).max(1.0).doc(
      "Fraction of the explicit (positivity) limit of eq. 26.");
  s.real("gas.Sigma_floor")
      .default_value(1e-100)
      .min(0.0)
      .unit("code surface density")
      .doc("Floor of Sigma after each step.");
  s.real("gas.rho_floor")
      .default_value(1e-100)
      .greater_than(0.0)
      .unit("code density")
      .doc("Floor of the hydrostatic density.");
  s.rule(check_viscosity);
  s.rule(check_column);
}

void GasConfig::derive(const units::UnitSystem& u, double h_ref) {
  const double m_gas = mu * units::cgs::m_H / u.mass;                           // code mass
  const double k_B = units::cgs::k_B / (u.mass * u.velocity() * u.velocity());  // code energy / K
  cs2_to_T = m_gas / k_B;
  if (h_ref > 0) {
    cs2_ref = h_ref * h_ref * GM / R_ref;
    T_ref = cs2_to_T * cs2_ref;
  } else {
    cs2_ref = T_ref / cs2_to_T;
  }
  if (viscosity == ViscosityModel::PowerLaw && !(nu0 > 0))
    nu0 = alpha * cs2_ref / std::sqrt(GM / (R_ref * R_ref * R_ref));
}

GasConfig GasConfig::from_deck(const core::Deck& d, const units::UnitSystem& u) {
  GasConfig c;
  c.GM = u.gravitational_constant() * d.real("star.mass") * units::cgs::M_sun / u.mass;
  c.thin_disc_gravity = d.string("star.potential") == "thin_disc";
  c.R_ref = d.real("gas.R_ref");
  c.T_ref = d.real("gas.T_ref");
  c.T_index = d.real("gas.T_index");
  c.mu = d.real("gas.mu");
  c.viscosity = d.string("gas.viscosity") == "alpha" ? ViscosityModel::Alpha : ViscosityModel::PowerLaw;
  c.alpha = d.real("gas.alpha");
  c.nu0 = d.real("gas.nu0");
  c.nu_index = d.real("gas.nu_index");
  c.Sigma0 = d.real("gas.Sigma0");
  c.Sigma_index = d.real("gas.Sigma_index");
  c.R_c = d.real("gas.R_c");
  c.R_cavity = d.real("gas.R_cavity");
  c.cavity_index = d.real("gas.cavity_index");
  c.viscous_vR = d.string("gas.radial_velocity") == "viscous";
  c.inner = gas_boundary(d.string("gas.inner_boundary"));
  c.outer = gas_boundary(d.string("gas.outer_boundary"));
  c.cfl = d.real("gas.cfl");
  c.Sigma_floor = d.real("gas.Sigma_floor");
  c.rho_floor = d.real("gas.rho_floor");
  c.derive(u, d.real("gas.h_ref"));
  return c;
}

}  // namespace mote::disc
