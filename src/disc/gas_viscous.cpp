// Explicit viscous evolution of the surface density, RBO24 eq. 26 (see
// include/mote/disc/gas_viscous.hpp).
#include "mote/disc/gas_viscous.hpp"

#include <limits>

#include "mote/core/loops.hpp"

namespace mote::disc {

namespace {

/// f at radius x from a power law through (x0, f0) and (x1, f1), the change
/// from f0 bounded to a factor 1e3; f0 if either value is not positive.
KOKKOS_INLINE_FUNCTION Real power_law_extrapolate(Real x, Real x0, Real f0, Real x1, Real f1) {
  if (!(f0 > 0) || !(f1 > 0)) return f0;
  const Real bound = 6.907755278982137;  // ln 1e3
  const Real e = (math::log(f0) - math::log(f1)) * math::log(x / x0) / math::log(x0 / x1);
  return f0 * math::exp(math::min(math::max(e, -bound), bound));
}

/// f0 (x / x0)^k with k = ln(f0 / f1) / ln(x0 / x1) (the power law through both
/// points) limited to [k_lo, k_hi]; f0 if either value is not positive.
KOKKOS_INLINE_FUNCTION Real limited_power_law(Real x, Real x0, Real f0, Real x1, Real f1, Real k_lo, Real k_hi) {
  if (!(f0 > 0) || !(f1 > 0)) return f0;
  const Real k = (math::log(f0) - math::log(f1)) / math::log(x0 / x1);
  return f0 * math::exp(math::min(math::max(k, k_lo), k_hi) * math::log(x / x0));
}

}  // namespace

void gas_fill_sigma_ghosts(const mesh::Grid& grid, mesh::RadialHalo& halo, GasBoundary inner, GasBoundary outer,
                           const RealView1& Sigma) {
  halo.exchange(Sigma);
  const bool do_inner = grid.has_inner_boundary() && inner != GasBoundary::User;
  const bool do_outer = grid.has_outer_boundary() && outer != GasBoundary::User;
  if (!do_inner && !do_outer) return;
  auto Rc = grid.Rc;
  const int ib = grid.i_begin(), ie = grid.i_end(), ng = grid.ng;
  par_for(
      "disc::gas_sigma_ghosts", 0, ng, KOKKOS_LAMBDA(int g) {
        if (do_inner) {
          const int i = ib - 1 - g;
          Sigma(i) = power_law_extrapolate(Rc(i), Rc(ib), Sigma(ib), Rc(ib + 1), Sigma(ib + 1));
        }
        if (do_outer) {
          const int i = ie + g;
          Sigma(i) = power_law_extrapolate(Rc(i), Rc(ie - 1), Sigma(ie - 1), Rc(ie - 2), Sigma(ie - 2));
        }
      });
}

void gas_viscous_step(const mesh::Grid& grid, mesh::RadialHalo& halo, GasBoundary inner, GasBoundary outer,
                      const RealView1& nu_mid, const RealView1& Sigma, const RealView1& Y, const RealView1& G,
                      Real dt) {
  auto Rc = grid.Rc, Re = grid.Re;
  const int ib = grid.i_begin(), ie = grid.i_end();
  par_for(
      "disc::gas_torque", 0, grid.nr_total(),
      KOKKOS_LAMBDA(int i) { Y(i) = math::sqrt(Rc(i)) * nu_mid(i) * Sigma(i); });
  halo.exchange(Y);

  // Ghost Y next to the domain edges (only the nearest ghost enters a flux).
  const bool edge_in = grid.has_inner_boundary(), edge_out = grid.has_outer_boundary();
  par_for(
      "disc::gas_torque_bc", 0, 1, KOKKOS_LAMBDA(int) {
        if (edge_in) {
          const int a = ib, g = ib - 1;
          if (inner == GasBoundary::Closed) Y(g) = Y(a);
          if (inner == GasBoundary::ZeroTorque) Y(g) = -Y(a) * (Re(a) - Rc(g)) / (Rc(a) - Re(a));  // Y = 0 at R_in
          // Power law with exponent >= 0: never inflow through R_in.
          if (inner == GasBoundary::Extrapolate)
            Y(g) = limited_power_law(Rc(g), Rc(a), Y(a), Rc(a + 1), Y(a + 1), 0.0, 10.0);
        }
        if (edge_out) {
          const int a = ie - 1, g = ie;
          if (outer == GasBoundary::Closed) Y(g) = Y(a);
          if (outer == GasBoundary::ZeroTorque) Y(g) = -Y(a) * (Rc(g) - Re(ie)) / (Re(ie) - Rc(a));  // Y = 0 at R_out
          // Power law with exponent <= 2: inflow through R_out bounded.
          if (outer == GasBoundary::Extrapolate)
            Y(g) = limited_power_law(Rc(g), Rc(a), Y(a), Rc(a - 1), Y(a - 1), -10.0, 2.0);
        }
      });

  const bool closed_in = edge_in && inner == GasBoundary::Closed, closed_out = edge_out && outer == GasBoundary::Closed;
  par_for(
      "disc::gas_viscous_flux", ib, ie + 1, KOKKOS_LAMBDA(int f) {
        const bool closed = (f == ib && closed_in) || (f == ie && closed_out);
        G(f) = closed ? Real(0) : 3.0 * math::sqrt(Re(f)) * (Y(f) - Y(f - 1)) / (Rc(f) - Rc(f - 1));
      });
  par_for(
      "disc::gas_viscous_update", ib, ie, KOKKOS_LAMBDA(int i) {
        const Real RdR = 0.5 * (Re(i + 1) * Re(i + 1) - Re(i) * Re(i));
        Sigma(i) += dt * (G(i + 1) - G(i)) / RdR;
      });
}

double gas_viscous_max_dt(const mesh::Grid& grid, GasBoundary inner, GasBoundary outer, const RealView1& nu_mid,
                          Real cfl) {
  auto Rc = grid.Rc, Re = grid.Re;
  const int ib = grid.i_begin(), ie = grid.i_end();
  const bool edge_in = grid.has_inner_boundary(), edge_out = grid.has_outer_boundary();
  const bool zt_in = edge_in && inner == GasBoundary::ZeroTorque, zt_out = edge_out && outer == GasBoundary::ZeroTorque;
  const bool closed_in = edge_in && inner == GasBoundary::Closed, closed_out = edge_out && outer == GasBoundary::Closed;
  Real rate = 0;
  par_reduce(
      "disc::gas_viscous_max_dt", ib, ie,
      KOKKOS_LAMBDA(int i, Real& m) {
        // Conductances K_f of the two faces; the zero-torque edge face spans half a cell.
        Real K_in = 3.0 * math::sqrt(Re(i)) / (Rc(i) - Rc(i - 1));
        Real K_out = 3.0 * math::sqrt(Re(i + 1)) / (Rc(i + 1) - Rc(i));
        if (i == ib && zt_in) K_in = 3.0 * math::sqrt(Re(i)) / (Rc(i) - Re(i));
        if (i == ib && closed_in) K_in = 0;
        if (i == ie - 1 && zt_out) K_out = 3.0 * math::sqrt(Re(i + 1)) / (Re(i + 1) - Rc(i));
        if (i == ie - 1 && closed_out) K_out = 0;
        const Real RdR = 0.5 * (Re(i + 1) * Re(i + 1) - Re(i) * Re(i));
        m = math::max(m, math::sqrt(Rc(i)) * nu_mid(i) * (K_in + K_out) / RdR);
      },
      Kokkos::Max<Real>(rate));
  return rate > 0 ? cfl / rate : std::numeric_limits<double>::max();
}

}  // namespace mote::disc
