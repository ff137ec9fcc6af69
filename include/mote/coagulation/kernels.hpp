// Collision kernels of the coagulation solver as interchangeable policies.
// A policy is a small device-copyable struct with
//   KOKKOS_INLINE_FUNCTION PairRate operator()(int cell, int i, int j) const
// returning the kernel K_ij (volume per time; area per time for the
// vertically integrated kernel) and the fragmentation probability of species
// i and j in `cell`, and the same split in three for the solver's pair loop:
// cell(c) (the gas terms of a cell), species(cell, k) (one species' terms in
// it) and pair(cell, c, i, j, species_i, species_j), so a cell's n species
// terms are computed once for its n (n + 1) / 2 pairs. The split gives the
// same values, bit for bit, as operator(), which is written with it.
// Coagulation::integrate is instantiated for each of them.
//  * ConstantKernel, AdditiveKernel, ProductKernel: K = K0, K0 (m_i + m_j),
//    K0 m_i m_j (Smoluchowski test kernels with analytic solutions, VALIDATION E1/E2).
//  * PhysicalKernel: K_ij = sigma_ij dv_ij (RBO24 eq. 56) with dv_ij from eq. 57-60
//    (relative_velocity.hpp) and p_frag from eq. 62; with `vertically_integrated`
//    the kernel is divided by sqrt(2 pi (h_i^2 + h_j^2)) and the vertical relative
//    speed is the difference of settling speeds at one dust scale height (RBO24
//    sec. 5.1, after Birnstiel et al. 2010).
#pragma once

#include "mote/coagulation/fragmentation.hpp"
#include "mote/coagulation/relative_velocity.hpp"
#include "mote/core/kokkos_types.hpp"
#include "mote/core/units.hpp"

namespace mote::coagulation {

struct PairRate {
  Real K = 0;       // collision kernel K_ij
  Real p_frag = 0;  // fragmentation probability (p_coag = 1 - p_frag)
};

/// The split interface of a kernel without per-cell or per-species terms.
template <class Kernel>
struct PairOnlyKernel {
  struct Cell {};
  struct Species {};
  KOKKOS_INLINE_FUNCTION Cell cell(int) const { return {}; }
  KOKKOS_INLINE_FUNCTION Species species(const Cell&, int) const { return {}; }
  KOKKOS_INLINE_FUNCTION PairRate pair(const Cell&, int c, int i, int j, const Species&, const Species&) const {
    return static_cast<const Kernel&>(*this)(c, i, j);
  }
};

struct ConstantKernel : PairOnlyKernel<ConstantKernel> {
  Real K0 = 1.0;
  KOKKOS_INLINE_FUNCTION PairRate operator()(int, int, int) const { return {K0, 0.0}; }
};

struct AdditiveKernel : PairOnlyKernel<AdditiveKernel> {
  Real K0 = 1.0;
  RealView1 mass;
  KOKKOS_INLINE_FUNCTION PairRate operator()(int, int i, int j) const { return {K0 * (mass(i) + mass(j)), 0.0}; }
};

struct ProductKernel : PairOnlyKernel<ProductKernel> {
  Real K0 = 1.0;
  RealView1 mass;
  KOKKOS_INLINE_FUNCTION PairRate operator()(int, int i, int j) const { return {K0 * mass(i) * mass(j), 0.0}; }
};

/// Gas state of the cells the physical kernel is evaluated in (cgs or any
/// consistent units). `density` is the gas volume density, or the gas surface
/// density for the vertically integrated kernel.
struct GasCells {
  RealView1 sound_speed;  // c_s
  RealView1 density;      // rho_g (or Sigma_g when vertically integrated)
  RealView1 omega;        // Keplerian angular frequency
  RealView1 alpha;        // turbulence parameter
  RealView1 height;       // height z above the mid-plane (volume kernel, settling estimate); may be empty
  RealView1 headwind;     // head-wind speed eta v_K for drift estimates; may be empty
  /// Dust velocities from the dynamics (cells, species, 3: R, z, phi). When
  /// given (extent(0) > 0) they replace the settling/drift estimates (eq. 57).
  View<Real***> dust_velocity;
};

struct PhysicalKernel {
  RealView1 mass, size;  // grain masses and radii (MassGrid)
  GasCells gas;
  Real rho_m = 1.6;                    // intrinsic grain density
  Real mu_mH = 2.4 * units::cgs::m_H;  // mean molecular mass mu m_H
  Real sigma_h2 = 2e-15;               // collision cross-section of H2 for the mean free path (cm^2)
  Real v_frag = 100.0;                 // fragmentation velocity
  bool vertically_integrated = false;
  bool fragmentation = true;

  /// The gas terms of one cell, shared by its pairs.
  struct Cell {
    Real cs, om, alpha, dens;  // the GasCells values
    Real H;                    // gas scale height c_s / Omega
    Real re_inv_sqrt;          // Re^-1/2, Re = alpha c_s H / nu_mol (OC07 sec. 2)
    Real kT;                   // mu m_H c_s^2
  };
  /// One species' terms in a cell, shared by its pairs.
  struct Species {
    TurbulentSpeciesTerms turbulent;  // its Stokes number and OC07 terms
    Real h;                           // dust scale height (vertically integrated kernel), else H
  };

  KOKKOS_INLINE_FUNCTION Cell cell(int c) const {
    Cell g;
    g.cs = gas.sound_speed(c);
    g.om = gas.omega(c);
    g.alpha = gas.alpha(c);
    g.dens = gas.density(c);
    g.H = g.cs / g.om;
    // The gas volume density at the mid-plane / in the cell.
    const Real rho_g = vertically_integrated ? g.dens / (math::sqrt(2.0 * math::pi()) * g.H) : g.dens;
    // Turbulent Reynolds number Re = alpha c_s H / nu_mol, nu_mol = v_th lambda / 2 (OC07 sec. 2).
    const Real lambda = mu_mH / (rho_g * sigma_h2);
    const Real nu_mol = 0.5 * math::sqrt(8.0 / math::pi()) * g.cs * lambda;
    g.re_inv_sqrt = 1.0 / math::sqrt(g.alpha * g.cs * g.H / nu_mol);
    g.kT = mu_mH * g.cs * g.cs;
    return g;
  }

  KOKKOS_INLINE_FUNCTION Species species(const Cell& g, int k) const {
    const Real a = size(k);
    const Real st = vertically_integrated ? stokes_epstein_midplane(a, rho_m, g.dens)
                                          : stokes_epstein(a, rho_m, g.dens, g.cs, g.om);
    return {turbulent_species_terms(st, g.re_inv_sqrt),
            vertically_integrated ? dust_scale_height(g.H, st, g.alpha) : g.H};
  }

  KOKKOS_INLINE_FUNCTION PairRate pair(const Cell& g, int c, int i, int j, const Species& si, const Species& sj) const {
    const Real ai = size(i), aj = size(j);
    const Real st_i = si.turbulent.st, st_j = sj.turbulent.st, h_i = si.h, h_j = sj.h;
    Real dv2 = brownian_dv2(mass(i), mass(j), g.kT) +
               (g.dens > 0 ? g.alpha * g.cs * g.cs * turbulent_vrel2(si.turbulent, sj.turbulent, g.re_inv_sqrt) : 0.0);
    // Laminar relative motion: dynamics velocities, or settling/drift estimates.
    if (gas.dust_velocity.extent(0) > 0) {
      for (int d = 0; d < 3; ++d) {
        if (vertically_integrated && d == 1) continue;
        dv2 += math::square(gas.dust_velocity(c, i, d) - gas.dust_velocity(c, j, d));
      }
    } else {
      const Real hw = gas.headwind.extent(0) > 0 ? gas.headwind(c) : 0.0;
      dv2 += math::square(radial_drift(st_i, hw) - radial_drift(st_j, hw)) +
             math::square(azimuthal_drift(st_i, hw) - azimuthal_drift(st_j, hw));
    }
    if (vertically_integrated) {
      dv2 += math::square(settling_speed(h_i, st_i, g.om) - settling_speed(h_j, st_j, g.om));
    } else if (gas.dust_velocity.extent(0) == 0 && gas.height.extent(0) > 0) {
      const Real z = gas.height(c);
      dv2 += math::square(settling_speed(z, st_i, g.om) - settling_speed(z, st_j, g.om));
    }
    const Real dv = math::sqrt(dv2);
    Real K = math::pi() * math::square(ai + aj) * dv;  // eq. 56, sigma_ij = pi (a_i + a_j)^2
    if (vertically_integrated) K /= math::sqrt(2.0 * math::pi() * (h_i * h_i + h_j * h_j));
    return {K, fragmentation ? fragmentation_probability(dv, v_frag) : 0.0};
  }

  KOKKOS_INLINE_FUNCTION PairRate operator()(int c, int i, int j) const {
    const Cell g = cell(c);
    return pair(g, c, i, j, species(g, i), species(g, j));
  }
};

}  // namespace mote::coagulation
