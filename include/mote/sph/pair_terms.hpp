// Pair terms shared by the gas force loop (src/sph/forces.cpp) and the dusty
// force loops (src/sph/dust_forces.cpp) of PL15 sec. 3: the separation and
// kernel gradients of a pair (grad W_ab = F_ab r_hat, PL15 eq. 34) and the
// hydrodynamic sums of particle a over its neighbours: momentum (eq. 25),
// artificial viscosity (eq. 31-32), PdV and viscous heating (eq. 27, first
// term), conductivity (eq. 34-35), div v and the signal speed.
#pragma once

#include "mote/core/kokkos_compat.hpp"
#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/kernels.hpp"

namespace mote::sph {

/// Geometry of the pair (a, b) read from a force loop's packed data.
template <int Dim, class K>
struct PairGeometry {
  Real dx[3] = {0, 0, 0};  ///< x_a - x_b (minimum image)
  Real r2 = 0.0, rinv = 0.0;
  Real fa = 0.0, fb = 0.0;    ///< F_ab(h_a), F_ab(h_b)
  Real vr = 0.0, vneg = 0.0;  ///< v_ab . r_hat and its approaching part min(v_ab . r_hat, 0)

  /// Separation from b (position at pack slot sx, image code img); returns r^2 > 0.
  template <class Pack>
  KOKKOS_INLINE_FUNCTION bool separate(const Box& box, const Real xa[3], const Pack& pk, int sx, int b, int img) {
    for (int d = 0; d < Dim; ++d) {
      dx[d] = box.separation(xa[d], pk(b, sx + d), img, d);
      r2 += dx[d] * dx[d];
    }
    return r2 > 0.0;
  }

  /// Kernel gradients with norm_a = K::norm() / h_a^(Dim + 1).
  KOKKOS_INLINE_FUNCTION void gradients(Real ha_inv, Real norm_a, Real hb_inv) {
    const Real r = math::sqrt(r2);
    rinv = 1.0 / r;
    Real f, dfa, dfb;
    K::shape(r * ha_inv, f, dfa);
    K::shape(r * hb_inv, f, dfb);
    fa = norm_a * dfa;
    fb = K::norm() * ipow<Dim + 1>(hb_inv) * dfb;
  }

  /// v_ab . r_hat from a's velocity and b's at pack slot sv (after gradients()).
  template <class Pack>
  KOKKOS_INLINE_FUNCTION void approach(const Real va[3], const Pack& pk, int sv, int b) {
    for (int d = 0; d < Dim; ++d) vr += (va[d] - pk(b, sv + d)) * dx[d];
    vr *= rinv;
    vneg = vr < 0.0 ? vr : 0.0;
  }
};

/// Per-particle factors of the hydrodynamic pair terms.
struct HydroSide {
  Real ppf;  ///< P / (Omega rho^2)
  Real avf;  ///< AV prefactor: 1 / (Omega rho), times (1 - eps) with dust (PL15 eq. 31)
  Real acs;  ///< alpha c_s
  Real rpf;  ///< 1 / (Omega rho) (conductivity)
  Real u;    ///< gas specific energy
  Real cs;
};

/// Hydrodynamic sums of particle a (PL15 eq. 25, 27, 31-35).
struct HydroSums {
  Real acc[3] = {0, 0, 0};
  Real du = 0.0;  ///< (1 - eps_a) du_a/dt without dust diffusion terms
  Real dv = 0.0;  ///< -sum_b m_b v_ab . grad W_ab(h_a)
  Real vs;        ///< signal speed

  KOKKOS_INLINE_FUNCTION explicit HydroSums(Real cs_a) : vs(cs_a) {}

  /// Adds neighbour b of mass mb; `inside`: within max(R h_a, R h_b) (v_sig);
  /// Energy: the gas has an energy equation (adiabatic EOS).
  template <bool Energy, int Dim, class K>
  KOKKOS_INLINE_FUNCTION void add(const PairGeometry<Dim, K>& g, bool inside, const HydroSide& a, const HydroSide& b,
                                  Real mb, Real beta, Real alpha_u) {
    // Artificial viscosity q / (Omega rho^2), PL15 eq. 31-32: approaching pairs only.
    const Real qa = -0.5 * a.avf * (a.acs - beta * g.vneg) * g.vneg;
    const Real qb = -0.5 * b.avf * (b.acs - beta * g.vneg) * g.vneg;
    // PL15 eq. 25.
    const Real fpair = mb * ((a.ppf + qa) * g.fa + (b.ppf + qb) * g.fb) * g.rinv;
    for (int d = 0; d < Dim; ++d) acc[d] -= fpair * g.dx[d];
    if constexpr (Energy) {
      // PL15 eq. 27 (PdV + viscous heating) and eq. 34-35 (conductivity).
      du += mb * (a.ppf + qa) * g.vr * g.fa;
      const Real qcond = 0.5 * alpha_u * math::fabs(g.vr) * (a.u - b.u);
      du += mb * qcond * (a.rpf * g.fa + b.rpf * g.fb);
    }
    dv -= mb * g.vr * g.fa;
    const Real vsab = (a.cs > b.cs ? a.cs : b.cs) - beta * g.vneg;
    vs = (inside && vsab > vs) ? vsab : vs;
  }
};

}  // namespace mote::sph
