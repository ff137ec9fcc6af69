// Gas velocities from viscous theory, RBO24 eq. 27-31 (see
// include/mote/disc/gas_velocities.hpp).
#include "mote/disc/gas_velocities.hpp"

#include "mote/core/loops.hpp"

namespace mote::disc {

namespace {

/// df/dx at x0 from three points, exact for quadratics on any spacing.
KOKKOS_INLINE_FUNCTION Real three_point(Real xm, Real x0, Real xp, Real fm, Real f0, Real fp) {
  const Real hm = x0 - xm, hp = xp - x0;
  return (hm * hm * (fp - f0) + hp * hp * (f0 - fm)) / (hm * hp * (hm + hp));
}

/// Derivative of f along the ray through row j (constant theta), r_k = R_c(k) / cos(theta_j), at an interior cell.
KOKKOS_INLINE_FUNCTION Real d_dr(const RealView2& f, const RealView1& Rc, Real inv_cos, int i, int j) {
  return three_point(Rc(i - 1) * inv_cos, Rc(i) * inv_cos, Rc(i + 1) * inv_cos, f(i - 1, j), f(i, j), f(i + 1, j));
}

/// Derivative of f along Z at constant R = R_c(i), Z_k = R tan(theta_k), at an interior cell.
KOKKOS_INLINE_FUNCTION Real d_dZ(const RealView2& f, Real R, const RealView1& tan_tc, int i, int j) {
  return three_point(R * tan_tc(j - 1), R * tan_tc(j), R * tan_tc(j + 1), f(i, j - 1), f(i, j), f(i, j + 1));
}

/// Value at x from the cubic through (x1, f1) ... (x4, f4) (Lagrange form).
KOKKOS_INLINE_FUNCTION Real cubic_at(Real x, Real x1, Real x2, Real x3, Real x4, Real f1, Real f2, Real f3, Real f4) {
  const Real l1 = (x - x2) * (x - x3) * (x - x4) / ((x1 - x2) * (x1 - x3) * (x1 - x4));
  const Real l2 = (x - x1) * (x - x3) * (x - x4) / ((x2 - x1) * (x2 - x3) * (x2 - x4));
  const Real l3 = (x - x1) * (x - x2) * (x - x4) / ((x3 - x1) * (x3 - x2) * (x3 - x4));
  const Real l4 = (x - x1) * (x - x2) * (x - x3) / ((x4 - x1) * (x4 - x2) * (x4 - x3));
  return l1 * f1 + l2 * f2 + l3 * f3 + l4 * f4;
}

KOKKOS_INLINE_FUNCTION Real weight(const RealView2& w, bool weighted, int i, int j) {
  return weighted ? w(i, j) : Real(1);
}

/// Fills the outermost layer of f (i = 0, ni - 1; j = 0, nj - 1), where the
/// centred derivatives do not reach, by cubic extrapolation of f / w from the
/// next four cells along the grid line (x = R_c along rays, tan(theta_c) at
/// fixed R). Weighting by w = rho (if `weighted`) keeps the extrapolation smooth where f
/// carries the Gaussian fall-off of the density.
void extrapolate_edges(const RealView2& f, const RealView2& w, bool weighted, const RealView1& Rc,
                       const RealView1& tan_tc) {
  const int ni = static_cast<int>(f.extent(0)), nj = static_cast<int>(f.extent(1));
  par_for(
      "disc::gas_extrapolate_theta", 1, ni - 1, KOKKOS_LAMBDA(int i) {
        const int lo[2] = {0, nj - 1}, dir[2] = {1, -1};
        for (int s = 0; s < 2; ++s) {
          const int j = lo[s], d = dir[s];
          const Real g = cubic_at(
              tan_tc(j), tan_tc(j + d), tan_tc(j + 2 * d), tan_tc(j + 3 * d), tan_tc(j + 4 * d),
              f(i, j + d) / weight(w, weighted, i, j + d), f(i, j + 2 * d) / weight(w, weighted, i, j + 2 * d),
              f(i, j + 3 * d) / weight(w, weighted, i, j + 3 * d), f(i, j + 4 * d) / weight(w, weighted, i, j + 4 * d));
          f(i, j) = g * weight(w, weighted, i, j);
        }
      });
  par_for(
      "disc::gas_extrapolate_r", 0, nj, KOKKOS_LAMBDA(int j) {
        const int lo[2] = {0, ni - 1}, dir[2] = {1, -1};
        for (int s = 0; s < 2; ++s) {
          const int i = lo[s], d = dir[s];
          const Real g = cubic_at(
              Rc(i), Rc(i + d), Rc(i + 2 * d), Rc(i + 3 * d), Rc(i + 4 * d),
              f(i + d, j) / weight(w, weighted, i + d, j), f(i + 2 * d, j) / weight(w, weighted, i + 2 * d, j),
              f(i + 3 * d, j) / weight(w, weighted, i + 3 * d, j), f(i + 4 * d, j) / weight(w, weighted, i + 4 * d, j));
          f(i, j) = g * weight(w, weighted, i, j);
        }
      });
}

}  // namespace

GasVelocityScratch::GasVelocityScratch(int ni, int nj)
    : a("gas::vel_a", ni, nj),
      b("gas::vel_b", ni, nj),
      c("gas::vel_c", ni, nj),
      d("gas::vel_d", ni, nj),
      e("gas::vel_e", ni, nj) {}

void gas_velocities(const mesh::Grid& grid, mesh::RadialHalo& halo, GasVelocityScratch& s, GasFields& gas,
                    bool viscous_vR) {
  const int ni = grid.nr_total(), nj = grid.nt_total();
  auto Rc = grid.Rc, tc = grid.tc, tan_tc = grid.tan_tc;
  auto rho = gas.rho, cs2 = gas.cs2, nu = gas.nu, vphi = gas.vphi, vR = gas.vR, vZ = gas.vZ;
  auto lnP = s.a, b = s.b, c = s.c, d = s.d, e = s.e;
  const StellarGravity gravity = gas.gravity;

  par_for(
      "disc::gas_log_pressure", 0, ni, 0, nj,
      KOKKOS_LAMBDA(int i, int j) { lnP(i, j) = math::log(rho(i, j) * cs2(i, j)); });

  // eq. 27: radial balance of gravity, centrifugal force and pressure.
  par_for(
      "disc::gas_vphi", 1, ni - 1, 1, nj - 1, KOKKOS_LAMBDA(int i, int j) {
        const Real cs = math::cos(tc(j)), sn = math::sin(tc(j)), inv_cos = 1.0 / cs;
        const Real R = Rc(i), r = R * inv_cos;
        const Real dlnP_dr = d_dr(lnP, Rc, inv_cos, i, j), dlnP_dZ = d_dZ(lnP, R, tan_tc, i, j);
        Real gR, gZ;
        gravity.acceleration(R, R * tan_tc(j), gR, gZ);
        const Real v2 = -R * gR + r * cs2(i, j) * (dlnP_dr - sn * dlnP_dZ);
        vphi(i, j) = math::sqrt(math::max(v2, Real(0)));
      });
  extrapolate_edges(vphi, rho, false, Rc, tan_tc);
  halo.exchange(vphi);
  Kokkos::deep_copy(vZ, 0.0);
  if (!viscous_vR) {
    Kokkos::deep_copy(vR, 0.0);
    return;
  }

  par_for(
      "disc::gas_vphi_products", 0, ni, 0, nj, KOKKOS_LAMBDA(int i, int j) {
        const Real r = Rc(i) / math::cos(tc(j));
        b(i, j) = vphi(i, j) / r;
        c(i, j) = r * vphi(i, j);
      });

  // eq. 29-30 (stress components; d holds r^3 T^{r phi}, e holds T^{Z phi}) and
  // the denominator of eq. 28 (in lnP's place).
  auto den = lnP;
  par_for(
      "disc::gas_stress", 1, ni - 1, 1, nj - 1, KOKKOS_LAMBDA(int i, int j) {
        const Real cs = math::cos(tc(j)), sn = math::sin(tc(j)), inv_cos = 1.0 / cs;
        const Real R = Rc(i), r = R * inv_cos;
        const Real dOmega_dr = d_dr(b, Rc, inv_cos, i, j);  // d(v_phi / r)/dr
        const Real dv_dZ = d_dZ(vphi, R, tan_tc, i, j);
        const Real pref = rho(i, j) * nu(i, j) * inv_cos * inv_cos;
        d(i, j) = r * r * r * pref * (r * dOmega_dr - sn * dv_dZ);
        e(i, j) = pref * (dv_dZ - r * sn * dOmega_dr);
        den(i, j) = d_dr(c, Rc, inv_cos, i, j) - r * sn * dv_dZ;
      });
  extrapolate_edges(d, rho, true, Rc, tan_tc);
  extrapolate_edges(e, rho, true, Rc, tan_tc);

  // eq. 31 and eq. 28 with v_Z = 0.
  par_for(
      "disc::gas_vR", 1, ni - 1, 1, nj - 1, KOKKOS_LAMBDA(int i, int j) {
        const Real inv_cos = 1.0 / math::cos(tc(j));
        const Real R = Rc(i), r = R * inv_cos;
        const Real div_T = d_dr(d, Rc, inv_cos, i, j) / (r * r * r) + d_dZ(e, R, tan_tc, i, j);
        const Real q = den(i, j);
        vR(i, j) = q > 0 ? R * div_T / (rho(i, j) * q) : Real(0);
      });
  extrapolate_edges(vR, rho, false, Rc, tan_tc);
  halo.exchange(vR);
}

}  // namespace mote::disc
