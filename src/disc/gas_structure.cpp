// Temperature, viscosity (RBO24 sec. 3.4) and hydrostatic density (eq. 33-37)
// of the gas disc; see include/mote/disc/gas_structure.hpp.
#include "mote/disc/gas_structure.hpp"

#include <cmath>

#include "mote/core/loops.hpp"

namespace mote::disc {

int midplane_index(const mesh::Grid& grid) {
  int best = grid.j_begin();
  for (int j = grid.j_begin(); j < grid.j_end(); ++j)
    if (std::fabs(grid.tc_h(j)) < std::fabs(grid.tc_h(best))) best = j;
  return best;
}

Real column_fraction(const mesh::Grid& grid) {
  const auto& e = grid.theta_edges_global;
  return (e.front() >= 0.0 || e.back() <= 0.0) ? 0.5 : 1.0;
}

void gas_temperature_profile(const mesh::Grid& grid, const GasConfig& cfg, const RealView2& T, const RealView2& cs2) {
  auto Rc = grid.Rc;
  const Real R_ref = cfg.R_ref, q = cfg.T_index, cs2_ref = cfg.cs2_ref, to_T = cfg.cs2_to_T;
  par_for(
      "disc::gas_temperature", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        const Real c2 = cs2_ref * math::pow(Rc(i) / R_ref, -q);
        cs2(i, j) = c2;
        T(i, j) = to_T * c2;
      });
}

void gas_sound_speed_from_temperature(const GasConfig& cfg, const RealView2& T, const RealView2& cs2) {
  const Real to_T = cfg.cs2_to_T;
  par_for(
      "disc::gas_sound_speed", 0, static_cast<int>(T.extent(0)), 0, static_cast<int>(T.extent(1)),
      KOKKOS_LAMBDA(int i, int j) { cs2(i, j) = T(i, j) / to_T; });
}

void gas_viscosity(const mesh::Grid& grid, const GasConfig& cfg, int j_mid, const RealView2& cs2, const RealView2& nu,
                   const RealView1& nu_mid) {
  auto Rc = grid.Rc;
  const bool alpha_model = cfg.viscosity == ViscosityModel::Alpha;
  const Real alpha = cfg.alpha, GM = cfg.GM, nu0 = cfg.nu0, n = cfg.nu_index, R_ref = cfg.R_ref;
  par_for(
      "disc::gas_viscosity", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        const Real R = Rc(i);
        // sec. 3.4: alpha c_s H with H = c_s / Omega_K(R), or nu_0 (R / R_ref)^n
        nu(i, j) = alpha_model ? alpha * cs2(i, j) / math::sqrt(GM / (R * R * R)) : nu0 * math::pow(R / R_ref, n);
      });
  par_for(
      "disc::gas_viscosity_mid", 0, grid.nr_total(), KOKKOS_LAMBDA(int i) { nu_mid(i) = nu(i, j_mid); });
}

void gas_hydrostatic_density(const mesh::Grid& grid, const StellarGravity& gravity, Real column_fraction,
                             Real rho_floor, int j_ref, const RealView2& cs2, const RealView1& Sigma,
                             const RealView2& rho) {
  auto Rc = grid.Rc, Re = grid.Re;
  auto V = grid.V, Zc = grid.Zc;
  const StellarGravity g = gravity;
  const int NJ = grid.nt_total(), jb = grid.j_begin(), je = grid.j_end();
  const Real f = column_fraction;
  // One thread per column; the scan of eq. 36 is sequential in j.
  par_for(
      "disc::gas_hydrostatic", 0, grid.nr_total(), KOKKOS_LAMBDA(int i) {
        const Real R = Rc(i);
        // Unnormalised pressure, P(j_ref) = 1, scanned upwards then downwards (eq. 34-36).
        Real P = 1.0;
        rho(i, j_ref) = P / cs2(i, j_ref);
        for (int j = j_ref + 1; j < NJ; ++j) {
          const Real dPhi = g.potential(R, Zc(i, j)) - g.potential(R, Zc(i, j - 1));
          const Real mean_inv_cs2 = 0.5 * (1.0 / cs2(i, j) + 1.0 / cs2(i, j - 1));  // eq. 35
          P *= math::exp(-mean_inv_cs2 * dPhi);                                     // eq. 34
          rho(i, j) = P / cs2(i, j);
        }
        P = 1.0;
        for (int j = j_ref - 1; j >= 0; --j) {
          const Real dPhi = g.potential(R, Zc(i, j)) - g.potential(R, Zc(i, j + 1));
          const Real mean_inv_cs2 = 0.5 * (1.0 / cs2(i, j) + 1.0 / cs2(i, j + 1));
          P *= math::exp(-mean_inv_cs2 * dPhi);
          rho(i, j) = P / cs2(i, j);
        }
        // Normalisation to the surface density (eq. 37), over the active rows.
        Real column = 0;
        for (int j = jb; j < je; ++j) column += rho(i, j) * V(i, j);
        const Real RdR = 0.5 * (Re(i + 1) * Re(i + 1) - Re(i) * Re(i));
        const Real scale = column > 0 ? f * Sigma(i) * RdR / column : 0.0;
        for (int j = 0; j < NJ; ++j) rho(i, j) = math::max(rho(i, j) * scale, rho_floor);
      });
}

}  // namespace mote::disc
