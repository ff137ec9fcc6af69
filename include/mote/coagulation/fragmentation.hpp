// Collision outcomes of RBO24 sec. 5 as small device functions:
//  * fragmentation probability for a Maxwellian distribution of relative
//    speeds around dv (RBO24 eq. 62; Stammler & Birnstiel 2022),
//  * remnant and fragment masses with the impactor-excavation factor chi_im
//    (RBO24 eq. 68), and the largest fragment min(chi_im m_im, m_tar) that
//    bounds the fragments' distribution (RBO24 sec. 5, as cuDisc's
//    SimpleErosion::mass_scale),
//  * the cumulative mass fraction of a power-law fragment distribution
//    n(m) ~ m^-eta (RBO24 eq. 66-67; Rafikov et al. 2020).
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

/// p_frag = [3/2 (v_frag/dv)^2 + 1] exp(-3/2 (v_frag/dv)^2)  (RBO24 eq. 62); p_coag = 1 - p_frag (eq. 55).
KOKKOS_INLINE_FUNCTION Real fragmentation_probability(Real dv, Real v_frag) {
  if (!(dv > 0)) return 0.0;
  const Real x = 1.5 * (v_frag / dv) * (v_frag / dv);
  if (x > 700.0) return 0.0;
  return (x + 1.0) * math::exp(-x);
}

/// Remnant of the target: m_tar - chi_im m_im if that is positive, else 0 (RBO24 eq. 68).
KOKKOS_INLINE_FUNCTION Real remnant_mass(Real m_a, Real m_b, Real chi_im) {
  const Real m_tar = math::max(m_a, m_b), m_im = math::min(m_a, m_b);
  const Real removed = chi_im * m_im;
  return removed < m_tar ? m_tar - removed : 0.0;
}

/// Largest fragment of a fragmenting collision: the mass the impactor
/// excavates, min(chi_im m_im, m_tar) (RBO24 sec. 5, below eq. 67). The
/// fragments (m_a + m_b - m_rem in all) are distributed up to this mass, so
/// none is heavier than the target.
KOKKOS_INLINE_FUNCTION Real largest_fragment_mass(Real m_a, Real m_b, Real chi_im) {
  const Real m_tar = math::max(m_a, m_b), m_im = math::min(m_a, m_b);
  return math::min(chi_im * m_im, m_tar);
}

/// Mass fraction of a fragment distribution n(m) ~ m^-eta below mass m, for
/// fragments spanning [m_low, m_max]: (m^(2-eta) - m_low^(2-eta)) / (m_max^(2-eta) - m_low^(2-eta))
/// (RBO24 eq. 67; the logarithm replaces the power at eta = 2).
KOKKOS_INLINE_FUNCTION Real fragment_mass_fraction_below(Real m, Real m_low, Real m_max, Real eta) {
  const Real p = 2.0 - eta;
  if (math::fabs(p) < 1e-12) return math::log(m / m_low) / math::log(m_max / m_low);
  return (math::pow(m, p) - math::pow(m_low, p)) / (math::pow(m_max, p) - math::pow(m_low, p));
}

}  // namespace mote::coagulation
