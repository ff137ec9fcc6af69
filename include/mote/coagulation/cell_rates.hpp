// Right-hand side of the Smoluchowski equation for one cell, evaluated by one
// Kokkos team (RBO24 eq. 53, 54, 61; Brauer et al. 2008), as a gather over
// target bins: no atomics, deterministic, and every collision removes exactly
// the mass it delivers, so sum_k d(rho_k)/dt = 0 to round-off.
//   loss_k = m_k n_k sum_i n_i K_ik                       (eq. 54, p_coag + p_frag = 1)
//   (a channel of pair (i <= k, k) whose product lands partly in bin k itself is
//   left out here and enters the gain with its net weight; collision_tables.hpp)
//   gain_k = sum_{p -> k} w n_i n_j K^coag_p + sum_{p -> k} w n_i n_j K^frag_p
//            + sum_{l >= k} B_l N_k(m^e_{l+1})            (eq. 61, 63-67)
//   B_l    = sum_{p -> l} m_frag,p n_i n_j K^frag_p       (Rafikov et al. 2020)
//   + with the quadratic product split, the correction entries of the
//   coagulation and remnant splits times their limiters theta (product_split.hpp)
// with K^coag_p = h_p K_ij p_coag, K^frag_p = h_p K_ij p_frag, h_p = 1/2 for
// i = j (double counting, RBO24 after eq. 61). Number densities use
// max(rho_k, 0) so a bin never loses mass it does not have.
#pragma once

#include "mote/coagulation/collision_tables.hpp"
#include "mote/coagulation/product_split.hpp"
#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

/// Pair coefficients (cells of a batch, pairs): LayoutRight so one cell's pairs are contiguous.
using PairCoefficients = Kokkos::View<Real**, Kokkos::LayoutRight, MemSpace>;

struct CellRates {
  int n = 0;
  RealView1 mass;
  GatherList coag, remnant, fragment, coag_correction, remnant_correction;
  RealView2 fragment_share;
  IntView1 pair_i, pair_j, self_target;
  PairCoefficients k_coag, k_frag;  // (batch cell, pair)
  bool has_fragmentation = true;
  bool has_correction = false;

  CellRates() = default;
  CellRates(const CollisionTables& t, const PairCoefficients& kc, const PairCoefficients& kf, bool frag)
      : n(t.species),
        mass(t.mass),
        coag(t.coag),
        remnant(t.remnant),
        fragment(t.fragment),
        coag_correction(t.coag_correction),
        remnant_correction(t.remnant_correction),
        fragment_share(t.fragment_share),
        pair_i(t.pair_i),
        pair_j(t.pair_j),
        self_target(t.self_target),
        k_coag(kc),
        k_frag(kf),
        has_fragmentation(frag),
        has_correction(t.has_correction) {}

  /// Scratch values the rate evaluation needs besides y and dydt: nd, bucket (n each), theta (2 n).
  static constexpr int scratch_per_species = 4;

  /// dydt = f(y) for batch cell `lc`; `nd` and `bucket` are scratch arrays of n
  /// values, `theta` one of 2 n (the split limiters).
  template <class Team, class V>
  KOKKOS_INLINE_FUNCTION void operator()(const Team& team, int lc, const V& y, const V& dydt, const V& nd,
                                         const V& bucket, const V& theta) const {
    const int nn = n;
    const auto m = mass;
    const bool corr = has_correction;
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nn), [&](int k) {
      nd(k) = math::max(y(k), Real(0)) / m(k);
      if (corr) {
        theta(2 * k) = k > 0 ? split_limiter(y(k - 1), y(k)) : Real(0);
        theta(2 * k + 1) = k + 1 < nn ? split_limiter(y(k + 1), y(k)) : Real(0);
      }
    });
    team.team_barrier();
    const auto kc = k_coag;
    const auto kf = k_frag;
    const auto pi = pair_i;
    const auto pj = pair_j;
    const auto self = self_target;
    const bool frag = has_fragmentation;
    if (frag) {
      const auto fr = fragment;
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nn), [&](int l) {
        Real b = 0;
        for (int e = fr.ptr(l); e < fr.ptr(l + 1); ++e) {
          const int p = fr.pair(e);
          b += fr.weight(e) * nd(pi(p)) * nd(pj(p)) * kf(lc, p);
        }
        bucket(l) = b;
      });
      team.team_barrier();
    }
    const auto co = coag;
    const auto re = remnant;
    const auto share = fragment_share;
    const auto cc = coag_correction;
    const auto rc = remnant_correction;
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nn), [&](int k) {
      const Real nk = nd(k);
      Real loss = 0;
      if (nk > 0) {
        for (int i = 0; i < nn; ++i) {
          const int p = pair_index(i, k);
          // Channels whose product lands back in bin k (k the larger grain) are net in the gain weights.
          const int s = i <= k ? self(p) : 0;
          const Real kk = ((s & 1) ? Real(0) : kc(lc, p)) + ((s & 2) ? Real(0) : kf(lc, p));
          loss += nd(i) * kk * (i == k ? 2.0 : 1.0);
        }
        loss *= m(k) * nk;
      }
      Real gain = 0;
      for (int e = co.ptr(k); e < co.ptr(k + 1); ++e) {
        const int p = co.pair(e);
        gain += co.weight(e) * nd(pi(p)) * nd(pj(p)) * kc(lc, p);
      }
      if (frag) {
        for (int e = re.ptr(k); e < re.ptr(k + 1); ++e) {
          const int p = re.pair(e);
          gain += re.weight(e) * nd(pi(p)) * nd(pj(p)) * kf(lc, p);
        }
        for (int l = k; l < nn; ++l) gain += bucket(l) * share(l, k);
      }
      if (corr) {
        for (int e = cc.ptr(k); e < cc.ptr(k + 1); ++e) {
          const int p = cc.pair(e);
          gain += cc.weight(e) * theta(cc.limiter(e)) * nd(pi(p)) * nd(pj(p)) * kc(lc, p);
        }
        if (frag)
          for (int e = rc.ptr(k); e < rc.ptr(k + 1); ++e) {
            const int p = rc.pair(e);
            gain += rc.weight(e) * theta(rc.limiter(e)) * nd(pi(p)) * nd(pj(p)) * kf(lc, p);
          }
      }
      dydt(k) = gain - loss;
    });
    team.team_barrier();
  }
};

}  // namespace mote::coagulation
