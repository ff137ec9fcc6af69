// Two-fluid dust with the improved semi-implicit pairwise drag (LAB15 sec. 2,
// eq. 17-22, 27-30, with the moment normalisation and the exact energy
// bookkeeping described in include/mote/sph/two_fluid_dust.hpp).
#include "mote/sph/two_fluid_dust.hpp"

#include <stdexcept>
#include <string>

#include "mote/core/device_sort.hpp"
#include "mote/core/loops.hpp"
#include "mote/core/small_eigen.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/phantom_dump.hpp"
#include "mote/sph/kernels.hpp"
#include "mote/sph/mixture_drag.hpp"

namespace mote::sph {

namespace two_fluid_detail {

/// Relaxation time of v_DG for the pair (dust species j, densities rho_d,
/// rho_g, gas sound speed cs): the shared laws of dust_drag.hpp; and the decay
/// 1 - exp(-dt / t_s) of eq. 6 over the (sub-)step dt.
struct PairDecay {
  KOKKOS_INLINE_FUNCTION static Real decay(int /*j*/, Real ts, Real dt) { return -math::expm1(-dt / ts); }
  void prepare(Real /*dt*/) const {}
};
/// Constant t_s per species: the decay is one number per species and step,
/// computed by prepare() (the same expression, so the same bits) instead of
/// in every pair (expm1 was 37 % of a drag update on the B2 box).
struct ConstantStoppingTime {
  RealView1 ts, species_decay;
  KOKKOS_INLINE_FUNCTION Real operator()(int j, Real, Real, Real) const { return ts(j); }
  KOKKOS_INLINE_FUNCTION Real decay(int j, Real /*ts*/, Real /*dt*/) const { return species_decay(j); }
  void prepare(Real dt) const;
};
struct ConstantDragCoefficient : PairDecay {
  RealView1 k;
  KOKKOS_INLINE_FUNCTION Real operator()(int j, Real rho_d, Real rho_g, Real) const {
    return rho_d * rho_g / (k(j) * (rho_d + rho_g));
  }
};
struct EpsteinDrag : PairDecay {
  RealView1 size;
  Real rho_grain, gamma;
  KOKKOS_INLINE_FUNCTION Real operator()(int j, Real rho_d, Real rho_g, Real cs) const {
    return ts_epstein(rho_grain, size(j), rho_d + rho_g, cs, gamma);
  }
};

/// out(j) = 1 - exp(-dt / ts(j)) (a free function: nvcc's extended lambdas may not live in member functions of
/// some classes).
void fill_species_decay(const RealView1& ts, const RealView1& out, Real dt) {
  par_for(
      "sph::two_fluid_species_decay", 0, static_cast<int>(ts.extent(0)),
      KOKKOS_LAMBDA(int j) { out(j) = PairDecay::decay(j, ts(j), dt); });
}

void ConstantStoppingTime::prepare(Real dt) const { fill_species_decay(ts, species_decay, dt); }

/// Columns of TwoFluidDust::drag_pack: per-particle factors of the pair terms,
/// packed once per drag update so that a pair costs three divisions.
enum DragSlot : int {
  kHinv = 0,    // 1 / h
  kWfac = 1,    // (m / rho) K::norm() / h^Dim: w_ik = kWfac(k) f(r_ik / h_k)
  kRhoInv = 2,  // 1 / rho
  kAcc = 3,     // non-drag acceleration over the (sub-)step, (v - v_start) / dt (Dim)
  kDragSlots = 6
};

/// The pair (dust i, gas k) of LAB15 eq. 17-21 and 27-28; Coupled (several
/// species) also gives the coefficients the mixture correction needs.
template <int Dim, class K, class Law, bool Coupled>
struct DragPair {
  RealView2 x, v, pk;
  RealView1 rho, cs;
  RealView2 tinv;
  IntView1 type;
  Box box;
  Law law;
  Real dt, lambda_on;

  /// For the pair (dust i, gas k; image code of k in i's list): the weight
  /// w = m_k W(r_ik, h_k) / rho_k, S_ik . r^ (eq. 21), the direction
  /// e = T_i^-1 r^ of the impulse, v~_ik . e, and (Coupled) the pair's
  /// coefficients for the coupling of several species: the rate
  /// 1 / (t_s (1 + eps)), xi, Lambda and r^ . e.
  KOKKOS_INLINE_FUNCTION bool terms(int i, int k, int img_from_i, Real& w, Real& sr, Real e[3], Real& ve,
                                    Real coeff[4]) const {
    Real tinv_trace = 0.0;
    for (int d = 0; d < Dim; ++d) tinv_trace += tinv(i, 4 * d);
    if (!(tinv_trace > 0.0)) return false;  // a dust particle outside all gas supports feels no drag
    Real rhat[3] = {0.0, 0.0, 0.0}, r2 = 0.0;
    for (int d = 0; d < Dim; ++d) {
      rhat[d] = box.separation(x(i, d), x(k, d), img_from_i, d);
      r2 += rhat[d] * rhat[d];
    }
    if (!(r2 > 0.0)) return false;
    const Real r = math::sqrt(r2);
    const Real q = r * pk(k, kHinv);
    if (q >= K::radius()) return false;
    Real f, df;
    K::shape(q, f, df);
    w = pk(k, kWfac) * f;
    const Real rinv = 1.0 / r;
    for (int d = 0; d < Dim; ++d) rhat[d] *= rinv;
    const Real eps = rho(i) * pk(k, kRhoInv);
    const Real ts = law(type(i) - kDust, rho(i), rho(k), cs(k));
    const Real mix = 1.0 / (1.0 + eps);
    const Real xi = law.decay(type(i) - kDust, ts, dt) * mix;     // eq. 6
    const Real lambda = lambda_on * ((dt + ts) * xi - dt * mix);  // eq. 19
    if constexpr (Coupled) {
      coeff[0] = mix / ts;
      coeff[1] = xi;
      coeff[2] = lambda;
      coeff[3] = 0.0;
    }
    sr = 0.0;
    ve = 0.0;
    for (int d = 0; d < Dim; ++d) {
      Real ed = 0.0;
      for (int c = 0; c < Dim; ++c) ed += tinv(i, 3 * d + c) * rhat[c];
      e[d] = ed;
      if constexpr (Coupled) coeff[3] += rhat[d] * ed;
    }
    for (int d = 0; d < Dim; ++d) {
      const Real vdg = v(i, d) - v(k, d);
      const Real adg = pk(i, kAcc + d) - pk(k, kAcc + d);  // non-drag a_DG over the step
      sr += (xi * vdg - lambda * adg) * rhat[d];           // eq. 21
      ve += vdg * e[d];
    }
    return true;
  }
};

/// Fills TwoFluidDust::drag_pack for the (sub-)step dt.
template <int Dim, class K>
void pack_drag_factors(const Particles& p, const RealView2& v_start, const RealView2& pk, Real dt) {
  const auto v = p.v;
  const auto m = p.m;
  const auto h = p.h;
  const auto rho = p.rho;
  const Real dt_inv = 1.0 / dt;
  par_for(
      "sph::two_fluid_drag_pack", 0, p.n, KOKKOS_LAMBDA(int a) {
        const Real hinv = 1.0 / h(a);
        pk(a, kHinv) = hinv;
        pk(a, kWfac) = m(a) / rho(a) * K::norm() * ipow<Dim>(hinv);
        pk(a, kRhoInv) = 1.0 / rho(a);
        for (int d = 0; d < Dim; ++d) pk(a, kAcc + d) = (v(a, d) - v_start(a, d)) * dt_inv;
      });
}

/// Pseudo-inverse of the symmetric positive semi-definite t: the inverse on
/// the eigen-directions with eigenvalue above 1e-6 of the largest, zero on the
/// others (the directions no gas neighbour samples).
template <int Dim>
KOKKOS_INLINE_FUNCTION void pseudo_inverse(const Real t[9], Real out[9]) {
  Real a[9], vec[9];
  for (int c = 0; c < 9; ++c) a[c] = t[c];
  jacobi_eigen_spd(Dim, 3, a, vec);
  Real largest = 0.0;
  for (int d = 0; d < Dim; ++d) largest = math::fmax(largest, a[4 * d]);
  for (int e = 0; e < Dim; ++e) {
    const Real lambda = a[4 * e];
    if (!(lambda > 1e-6 * largest)) continue;
    for (int r = 0; r < Dim; ++r)
      for (int c = 0; c < Dim; ++c) out[3 * r + c] += vec[3 * r + e] * vec[3 * c + e] / lambda;
  }
}

/// Inverse of the symmetric Dim x Dim moment t (row-major, 3 x 3 storage), or
/// its pseudo-inverse where t is nearly singular (gas neighbours on a line or
/// a plane, or a single one): the drag then acts, exactly, along the
/// directions the neighbours sample and not at all across them. (LAB15's
/// isotropic nu / N_i, used here before, multiplied the impulse along a
/// single neighbour's direction by Dim: v_DG went 1, -2, 4, ... in 3D at
/// dt >> t_s.)
template <int Dim>
KOKKOS_INLINE_FUNCTION void invert_moment(const Real t[9], Real out[9]) {
  for (int c = 0; c < 9; ++c) out[c] = 0.0;
  Real trace = 0.0;
  for (int d = 0; d < Dim; ++d) trace += t[4 * d];
  if (!(trace > 0.0)) return;
  const Real scale = trace / Dim;
  Real det = 0.0;
  if (Dim == 1) {
    out[0] = 1.0 / t[0];
    return;
  }
  if (Dim == 2) {
    det = t[0] * t[4] - t[1] * t[3];
    if (det > 1e-6 * scale * scale) {
      out[0] = t[4] / det;
      out[1] = -t[1] / det;
      out[3] = -t[3] / det;
      out[4] = t[0] / det;
      return;
    }
  } else {
    const Real c00 = t[4] * t[8] - t[5] * t[7], c01 = t[5] * t[6] - t[3] * t[8], c02 = t[3] * t[7] - t[4] * t[6];
    det = t[0] * c00 + t[1] * c01 + t[2] * c02;
    if (det > 1e-6 * scale * scale * scale) {
      out[0] = c00 / det;
      out[1] = (t[2] * t[7] - t[1] * t[8]) / det;
      out[2] = (t[1] * t[5] - t[2] * t[4]) / det;
      out[3] = c01 / det;
      out[4] = (t[0] * t[8] - t[2] * t[6]) / det;
      out[5] = (t[2] * t[3] - t[0] * t[5]) / det;
      out[6] = c02 / det;
      out[7] = (t[1] * t[6] - t[0] * t[7]) / det;
      out[8] = (t[0] * t[4] - t[1] * t[3]) / det;
      return;
    }
  }
  pseudo_inverse<Dim>(t, out);
}

/// Columns of TwoFluidDust::pair_terms: a pair's terms as DragPair::terms gives them.
enum PairSlot : int { kPairW = 0, kPairSr = 1, kPairVe = 2, kPairE = 3, kPairSlots = 6 };
/// Columns of TwoFluidDust::mixture_terms (several species), in the gas
/// particles' order: the weight w and the coefficients of DragPair::terms.
enum MixtureSlot : int { kMixW = 0, kMixCoeff = 1, kMixSlots = 5 };

/// kept, or new storage with 1/16 slack where kept holds fewer than n entries.
template <class V>
V fitted(V& kept, std::size_t n, const std::string& label) {
  if (kept.extent(0) < n) {
    kept = V();
    kept = V(Kokkos::view_alloc(Kokkos::WithoutInitializing, label), n + n / 16);
  }
  return kept;
}

/// CSR offsets of the entries of each list whose particle is of the other
/// phase: dust lists count their gas entries, gas lists their dust entries
/// (by the list's symmetry the two totals agree). Returns the dust total.
int pair_offsets(const NeighbourList& nl, const IntView1& type, bool dust_side, const View<int*>& start) {
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const int n = nl.size();
  Kokkos::parallel_scan(
      "sph::two_fluid_pair_offsets", Kokkos::RangePolicy<ExecSpace>(0, n + 1),
      KOKKOS_LAMBDA(int a, int& acc, bool final) {
        if (final) start(a) = acc;
        if (a == n || (type(a) != kGas) != dust_side) return;
        for (int j = offsets(a); j < offsets(a + 1); ++j) acc += (type(neigh(j)) != kGas) != dust_side ? 1 : 0;
      });
  if (!dust_side) return 0;
  int total = 0;
  Kokkos::deep_copy(total, Kokkos::subview(start, n));
  return total;
}

/// Several species: each slot's position in the gas order (slot_in_gas), the
/// dust particle at each gas-ordered position (gas_dust), and room for the
/// gas-ordered mixture_terms, so that the mixture pass reads its pairs in
/// sequence.
void number_mixture_pairs(TwoFluidDust& dust, int slots) {
  const auto gas_pairs = dust.gas_pairs;
  const auto pair_dust = dust.pair_dust;
  const auto slot_in_gas = fitted(dust.slot_in_gas, slots, "sph::two_fluid_slot_in_gas");
  const auto gas_dust = fitted(dust.gas_dust, slots, "sph::two_fluid_gas_dust");
  par_for(
      "sph::two_fluid_mixture_numbering", 0, slots, KOKKOS_LAMBDA(int q) {
        const int s = gas_pairs(q);
        slot_in_gas(s) = q;
        gas_dust(q) = pair_dust(s);
      });
  if (dust.mixture_terms.extent(0) < static_cast<std::size_t>(slots)) {
    dust.mixture_terms = RealView2();
    dust.mixture_terms = RealView2(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::two_fluid_mixture_terms"),
                                   slots + slots / 16, static_cast<int>(kMixSlots));
  }
}

/// Numbers the dust-gas pairs of the current neighbour list (see
/// TwoFluidDust::pair_start): slots in dust order, then each gas particle's
/// slots in the order of its own list, matched through the mirrored image
/// code (a transpose by counting sort, then a binary search per entry).
void update_pair_map(TwoFluidDust& dust, const Particles& p, const NeighbourList& nl) {
  const int n = p.n;
  const auto type = p.type;
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const auto image = nl.image;
  const auto pair_start = fitted(dust.pair_start, n + 1, "sph::two_fluid_pair_start");
  const auto gas_start = fitted(dust.gas_start, n + 1, "sph::two_fluid_gas_start");
  const int slots = pair_offsets(nl, type, true, pair_start);
  pair_offsets(nl, type, false, gas_start);
  const auto pair_dust = fitted(dust.pair_dust, slots, "sph::two_fluid_pair_dust");
  const auto pair_code = fitted(dust.pair_code, slots, "sph::two_fluid_pair_code");
  const auto by_dust = fitted(dust.gas_sorted, slots, "sph::two_fluid_gas_sorted");
  const auto gas_pairs = fitted(dust.gas_pairs, slots, "sph::two_fluid_gas_pairs");
  const auto fill = fitted(dust.gas_fill, n, "sph::two_fluid_gas_fill");
  if (dust.pair_terms.extent(0) < static_cast<std::size_t>(slots)) {
    dust.pair_terms = RealView2();
    dust.pair_terms = RealView2(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::two_fluid_pair_terms"),
                                slots + slots / 16, static_cast<int>(kPairSlots));
  }
  par_for(
      "sph::two_fluid_gas_fill_zero", 0, n, KOKKOS_LAMBDA(int a) { fill(a) = 0; });
  // Slots of each dust particle in its list's order; each also goes to its gas particle.
  par_for(
      "sph::two_fluid_pair_slots", 0, n, KOKKOS_LAMBDA(int i) {
        if (type(i) == kGas) return;
        int s = pair_start(i);
        for (int j = offsets(i); j < offsets(i + 1); ++j) {
          const int k = neigh(j);
          if (type(k) != kGas) continue;
          pair_dust(s) = i;
          pair_code(s) = image(j);
          by_dust(gas_start(k) + Kokkos::atomic_fetch_add(&fill(k), 1)) = s;
          ++s;
        }
      });
  // Each gas particle's slots sorted (slot order is dust order), then in the order of its list.
  par_for(
      "sph::two_fluid_gas_pairs", 0, n, KOKKOS_LAMBDA(int k) {
        if (type(k) != kGas) return;
        const int b = gas_start(k), e = gas_start(k + 1);
        insertion_sort(by_dust, b, e);
        int out = b;
        for (int j = offsets(k); j < offsets(k + 1); ++j) {
          const int i = neigh(j);
          if (type(i) == kGas) continue;
          const unsigned char code = static_cast<unsigned char>(mirror_image(image(j)));
          int lo = b, hi = e;  // the first slot of dust particle i
          while (lo < hi) {
            const int mid = (lo + hi) / 2;
            if (pair_dust(by_dust(mid)) < i)
              lo = mid + 1;
            else
              hi = mid;
          }
          while (lo < e - 1 && pair_code(by_dust(lo)) != code) ++lo;
          gas_pairs(out++) = by_dust(lo);
        }
      });
  if (dust.settings().nspecies > 1) number_mixture_pairs(dust, slots);
}

/// Several species (include/mote/sph/mixture_drag.hpp): per gas particle k,
/// the mixture of its dust neighbours, species by species, from the pairs'
/// weights om = m_i w_ik: eps_j = sum om (r^ . e) / (Dim m_k), the ratio with
/// which the gas's side of the pairs takes up their impulses, and the
/// om-weighted means of the pairs' rates d_ik = 1 / (t_s (1 + eps_ik)), of
/// v~_i - v~_k, of the non-drag a_i - a_k and of S_ik; from these the
/// correction c_jk = -<S>_j - delta_j of every species present, into corr(k, 3 j + d)
/// (w, the rates and r^ . e come from the dust pass, in mixture_terms, which
/// holds them in the gas particles' order).
template <int Dim>
void mixture_corrections(TwoFluidDust& dust, const Particles& p, Real dt) {
  const auto type = p.type;
  const auto m = p.m;
  const auto v = p.v;
  const auto pk = dust.drag_pack;
  const auto mix = dust.mixture_terms;
  const auto gas_start = dust.gas_start;
  const auto gas_dust = dust.gas_dust;
  const auto corr = dust.mixture_corr;
  const auto unsolved = dust.mixture_unsolved;
  const int ns = dust.settings().nspecies;
  par_for(
      "sph::two_fluid_mixture", 0, p.n, KOKKOS_LAMBDA(int k) {
        if (type(k) != kGas) return;
        constexpr int nmax = kMaxCoupledSpecies;
        Real weight[nmax], eps[nmax], rate[nmax], w[3 * nmax], da[3 * nmax], sm[3 * nmax];
        for (int j = 0; j < ns; ++j) {
          weight[j] = eps[j] = rate[j] = 0.0;
          for (int d = 0; d < 3; ++d) w[3 * j + d] = da[3 * j + d] = sm[3 * j + d] = 0.0;
        }
        for (int q = gas_start(k); q < gas_start(k + 1); ++q) {
          const Real wik = mix(q, kMixW);
          if (wik < 0.0) continue;
          const int i = gas_dust(q), j = type(i) - kDust;
          const Real om = m(i) * wik;
          const Real xi = mix(q, kMixCoeff + 1), lambda = mix(q, kMixCoeff + 2);
          weight[j] += om;
          eps[j] += om * mix(q, kMixCoeff + 3);
          rate[j] += om * mix(q, kMixCoeff);
          for (int d = 0; d < Dim; ++d) {
            const Real vdg = v(i, d) - v(k, d), adg = pk(i, kAcc + d) - pk(k, kAcc + d);
            w[3 * j + d] += om * vdg;
            da[3 * j + d] += om * adg;
            sm[3 * j + d] += om * (xi * vdg - lambda * adg);
          }
        }
        int present[nmax], n = 0;  // the species present around k, compacted
        for (int j = 0; j < ns; ++j) {
          if (!(weight[j] > 0.0)) continue;
          const Real inv = 1.0 / weight[j];
          eps[n] = eps[j] / (Dim * m(k));
          rate[n] = rate[j] * inv;
          for (int d = 0; d < 3; ++d) {
            w[3 * n + d] = w[3 * j + d] * inv;
            da[3 * n + d] = da[3 * j + d] * inv;
            sm[3 * n + d] = sm[3 * j + d] * inv;
          }
          present[n++] = j;
        }
        for (int c = 0; c < 3 * ns; ++c) corr(k, c) = 0.0;
        if (n == 0) return;
        Real delta[3 * nmax];
        if (!mixture_drag_change(n, Dim, eps, rate, w, da, dt, delta)) {
          Kokkos::atomic_add(&unsolved(), 1);
          return;
        }
        for (int l = 0; l < n; ++l)
          for (int d = 0; d < Dim; ++d) corr(k, 3 * present[l] + d) = -sm[3 * l + d] - delta[3 * l + d];
      });
}

/// Adds each pair's c_jk . r^ to its S_ik . r^ (kept in its slot for the gas
/// pass) and the resulting impulses to the dust particles' dv.
template <int Dim>
void apply_mixture_corrections(TwoFluidDust& dust, const Particles& p, const NeighbourList& nl, const Box& box) {
  const auto type = p.type;
  const auto x = p.x;
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const auto image = nl.image;
  const auto terms = dust.pair_terms;
  const auto pair_start = dust.pair_start;
  const auto corr = dust.mixture_corr;
  const auto dv = dust.dv;
  par_for(
      "sph::two_fluid_mixture_apply", 0, p.n, KOKKOS_LAMBDA(int i) {
        if (type(i) == kGas) return;
        const int j3 = 3 * (type(i) - kDust);
        Real acc[3] = {0.0, 0.0, 0.0};
        int s = pair_start(i);
        for (int jn = offsets(i); jn < offsets(i + 1); ++jn) {
          const int k = neigh(jn);
          if (type(k) != kGas) continue;
          const Real w = terms(s, kPairW);
          if (w >= 0.0) {
            Real r[3] = {0.0, 0.0, 0.0}, r2 = 0.0, cr = 0.0;
            for (int d = 0; d < Dim; ++d) {
              r[d] = box.separation(x(i, d), x(k, d), image(jn), d);
              r2 += r[d] * r[d];
            }
            const Real rinv = 1.0 / math::sqrt(r2);
            for (int d = 0; d < Dim; ++d) cr += corr(k, j3 + d) * r[d] * rinv;
            terms(s, kPairSr) += cr;
            for (int d = 0; d < Dim; ++d) acc[d] -= w * cr * terms(s, kPairE + d);
          }
          ++s;
        }
        for (int d = 0; d < Dim; ++d) dv(i, d) += acc[d];
      });
}

template <int Dim, class K, class Law, bool Coupled>
void apply_drag_impl(TwoFluidDust& dust, SphSystem& sys, Real dt, Law law, Real lambda_on) {
  const Particles& p = sys.particles();
  const NeighbourList& nl = sys.neighbours();
  const int n = p.n;
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const auto image = nl.image;
  const auto type = p.type;
  const auto x = p.x;
  const auto m = p.m;
  const auto pk = dust.drag_pack;
  const auto tinv = dust.tinv;
  const auto dv = dust.dv;
  const auto du = dust.du;
  const Box box = sys.box();
  pack_drag_factors<Dim, K>(p, dust.v_start, pk, dt);
  law.prepare(dt);
  if (dust.pair_map_builds != nl.builds()) {
    update_pair_map(dust, p, nl);
    dust.pair_map_builds = nl.builds();
  }
  const auto pair_start = dust.pair_start;
  const auto pair_dust = dust.pair_dust;
  const auto gas_start = dust.gas_start;
  const auto gas_pairs = dust.gas_pairs;
  const auto terms = dust.pair_terms;
  const auto mix = dust.mixture_terms;        // several species only
  const auto slot_in_gas = dust.slot_in_gas;  // several species only

  // Pass 1: T_i = sum_k^gas (m_k / rho_k) W(r_ik, h_k) r^ r^T and its inverse
  // (for isotropic neighbours T_i = (N_i / nu) I, eq. 30).
  par_for(
      "sph::two_fluid_moment", 0, n, KOKKOS_LAMBDA(int i) {
        Real t[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, inv[9];
        if (type(i) != kGas) {
          for (int j = offsets(i); j < offsets(i + 1); ++j) {
            const int k = neigh(j);
            if (type(k) != kGas) continue;
            Real r[3] = {0.0, 0.0, 0.0}, r2 = 0.0;
            for (int d = 0; d < Dim; ++d) {
              r[d] = box.separation(x(i, d), x(k, d), image(j), d);
              r2 += r[d] * r[d];
            }
            if (!(r2 > 0.0)) continue;
            Real f, df;
            K::shape(math::sqrt(r2) * pk(k, kHinv), f, df);
            const Real wk = pk(k, kWfac) * f / r2;
            for (int d = 0; d < Dim; ++d)
              for (int c = 0; c < Dim; ++c) t[3 * d + c] += wk * r[d] * r[c];
          }
        }
        invert_moment<Dim>(t, inv);
        for (int c = 0; c < 9; ++c) tinv(i, c) = inv[c];
      });

  const DragPair<Dim, K, Law, Coupled> pair{p.x, p.v, pk, p.rho, p.cs, tinv, p.type, box, law, dt, lambda_on};
  // Pass 2: the dust, eq. 27; every pair's terms go to its slot (w < 0: no drag).
  par_for(
      "sph::two_fluid_drag_dust", 0, n, KOKKOS_LAMBDA(int i) {
        Real acc[3] = {0.0, 0.0, 0.0};
        if (type(i) != kGas) {
          int s = pair_start(i);
          for (int j = offsets(i); j < offsets(i + 1); ++j) {
            const int k = neigh(j);
            if (type(k) != kGas) continue;
            Real w, sr, e[3] = {0.0, 0.0, 0.0}, ve, coeff[4] = {0.0, 0.0, 0.0, 0.0};
            const bool drag = pair.terms(i, k, image(j), w, sr, e, ve, coeff);
            terms(s, kPairW) = drag ? w : -1.0;
            if (Coupled) {  // a plain if: nvcc's lambdas may not first capture inside if constexpr
              const int q = slot_in_gas(s);
              mix(q, kMixW) = drag ? w : -1.0;
              if (drag)
                for (int c = 0; c < 4; ++c) mix(q, kMixCoeff + c) = coeff[c];
            }
            if (drag) {
              terms(s, kPairSr) = sr;
              terms(s, kPairVe) = ve;
              for (int d = 0; d < Dim; ++d) terms(s, kPairE + d) = e[d];
              for (int d = 0; d < Dim; ++d) acc[d] -= w * sr * e[d];
            }
            ++s;
          }
        }
        for (int d = 0; d < Dim; ++d) dv(i, d) = acc[d];
        du(i) = 0.0;
      });
  if constexpr (Coupled) {
    mixture_corrections<Dim>(dust, p, dt);
    apply_mixture_corrections<Dim>(dust, p, nl, box);
  }
  // Pass 3: the gas, eq. 28, and its heating (eq. 29 made exact, see above),
  // from the slots of pass 2 in the order of the gas particle's list.
  par_for(
      "sph::two_fluid_drag_gas", 0, n, KOKKOS_LAMBDA(int k) {
        if (type(k) != kGas) return;
        Real acc[3] = {0.0, 0.0, 0.0};
        Real work = 0.0;  // sum_i m_i w_ik (S_ik . r^) (v~_ik + Dv_i / 2) . e_ik
        const Real mk_inv = 1.0 / m(k);
        for (int q = gas_start(k); q < gas_start(k + 1); ++q) {
          const int s = gas_pairs(q);
          const Real w = terms(s, kPairW);
          if (w < 0.0) continue;
          const int i = pair_dust(s);
          const Real sr = terms(s, kPairSr), ve = terms(s, kPairVe);
          Real e[3] = {0.0, 0.0, 0.0};
          for (int d = 0; d < Dim; ++d) e[d] = terms(s, kPairE + d);
          const Real mw = m(i) * w;
          Real dvi_e = 0.0;
          for (int d = 0; d < Dim; ++d) {
            acc[d] += mw * mk_inv * sr * e[d];
            dvi_e += dv(i, d) * e[d];
          }
          work += mw * sr * (ve + 0.5 * dvi_e);
        }
        Real dv2 = 0.0;
        for (int d = 0; d < Dim; ++d) {
          dv(k, d) = acc[d];
          dv2 += acc[d] * acc[d];
        }
        du(k) = work * mk_inv - 0.5 * dv2;
      });
  // Pass 4: apply; the heating total stays on the device.
  const auto v = p.v;
  const auto u = p.u;
  const bool energy = sys.config().eos == EosType::Adiabatic;
  const auto heat_step = dust.heat_step;
  const auto heat_total = dust.heat_total;
  par_reduce(
      "sph::two_fluid_drag_apply", 0, n,
      KOKKOS_LAMBDA(int a, Real& s) {
        for (int d = 0; d < Dim; ++d) v(a, d) += dv(a, d);
        if (energy) u(a) += du(a);
        s += m(a) * du(a);
      },
      heat_step);
  par_for(
      "sph::two_fluid_heating_total", 0, 1, KOKKOS_LAMBDA(int) { heat_total() += heat_step(); });
}

template <class Law>
struct DragDispatch {
  TwoFluidDust& dust;
  SphSystem& sys;
  Real dt;
  Law law;
  Real lambda_on;
  template <int Dim, class K>
  void operator()() {
    if (dust.settings().nspecies > 1)
      apply_drag_impl<Dim, K, Law, true>(dust, sys, dt, law, lambda_on);
    else
      apply_drag_impl<Dim, K, Law, false>(dust, sys, dt, law, lambda_on);
  }
};

template <class Law>
void run_drag(TwoFluidDust& dust, SphSystem& sys, Real dt, const Law& law, Real lambda_on) {
  DragDispatch<Law> f{dust, sys, dt, law, lambda_on};
  dispatch(sys.particles().dim, sys.config().kernel, f);
}

}  // namespace two_fluid_detail

TwoFluidDust::TwoFluidDust(const DustSettings& settings, const SphSystem& sys) : s_(settings) {
  s_.validate();
  const Particles& p = sys.particles();
  const int ns = s_.nspecies;
  auto type = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.type);
  std::vector<long long> count(ns + 1, 0);
  for (int a = 0; a < p.n; ++a) {
    const int t = type(a);
    if (t < kGas || t > kDust + ns - 1)
      throw std::invalid_argument("dust: particle type " + std::to_string(t) + " is neither gas nor one of the " +
                                  std::to_string(ns) + " dust species (types 1.." + std::to_string(ns) + ")");
    ++count[t];
  }
  if (count[kGas] == 0) throw std::invalid_argument("dust: two-fluid dust needs gas particles");
  for (int j = 0; j < ns; ++j)
    if (count[kDust + j] == 0)
      throw std::invalid_argument("dust: two-fluid dust species " + std::to_string(j) + " has no particles");
  v_start = RealView2("sph::two_fluid_v_start", p.n, p.dim);
  dv = RealView2("sph::two_fluid_dv", p.n, p.dim);
  du = RealView1("sph::two_fluid_du", p.n);
  tinv = RealView2("sph::two_fluid_moment_inverse", p.n, 9);
  drag_pack = RealView2("sph::two_fluid_drag_pack", p.n, static_cast<int>(two_fluid_detail::kDragSlots));
  const SpeciesDrag drag = s_.species_drag("sph::two_fluid");
  kdrag = drag.k_drag;
  size = drag.size;
  tstop = drag.stopping_time;
  species_decay = RealView1("sph::two_fluid_species_decay", ns);
  if (ns > 1) mixture_corr = RealView2("sph::two_fluid_mixture_corr", p.n, 3 * ns);
  mixture_unsolved = Kokkos::View<int, MemSpace>("sph::two_fluid_mixture_unsolved");
  heat_step = Kokkos::View<Real, MemSpace>("sph::two_fluid_heat_step");
  heat_total = Kokkos::View<Real, MemSpace>("sph::two_fluid_heat_total");
}

namespace {

/// v_start = v, as a kernel (a deep copy would count as traffic in the device-traffic tests).
void keep_velocity(const RealView2& v_start, const Particles& p) {
  const auto v = p.v;
  const int dim = p.dim;
  par_for(
      "sph::two_fluid_keep_velocity", 0, p.n, KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < dim; ++d) v_start(i, d) = v(i, d);
      });
}

}  // namespace

void TwoFluidDust::begin_step(SphSystem& sys, Real) { keep_velocity(v_start, sys.particles()); }

void TwoFluidDust::after_first_kick(SphSystem& sys, Real half_dt) {
  apply_drag(sys, half_dt);
  keep_velocity(v_start, sys.particles());  // the start of the second half
}

void TwoFluidDust::after_kick(SphSystem& sys, Real half_dt) { apply_drag(sys, half_dt); }

void TwoFluidDust::apply_drag(SphSystem& sys, Real dt) {
  using namespace two_fluid_detail;
  const Real lambda_on = s_.drag_scheme == TwoFluidDrag::Improved ? 1.0 : 0.0;
  const Real gamma = sys.config().eos == EosType::Adiabatic ? sys.config().gamma : 1.0;
  switch (s_.drag) {
    case DragLaw::ConstantStoppingTime:
      run_drag(*this, sys, dt, ConstantStoppingTime{tstop, species_decay}, lambda_on);
      break;
    case DragLaw::ConstantK:
      run_drag(*this, sys, dt, ConstantDragCoefficient{{}, kdrag}, lambda_on);
      break;
    case DragLaw::Epstein:
      run_drag(*this, sys, dt, EpsteinDrag{{}, size, s_.rho_grain, gamma}, lambda_on);
      break;
  }
}

Real TwoFluidDust::drag_heating() const {
  Real h = 0.0;
  Kokkos::deep_copy(h, heat_total);
  return h;
}

Real TwoFluidDust::timestep(SphSystem& sys) {
  const Particles& p = sys.particles();
  const auto type = p.type;
  const auto h = p.h;
  const auto a = p.a;
  const int dim = p.dim;
  const Real c_force = sys.config().c_force;
  Real dt = 1e300;
  par_reduce(
      "sph::two_fluid_timestep", 0, p.n,
      KOKKOS_LAMBDA(int i, Real& dmin) {
        if (type(i) == kGas) return;
        Real a2 = 0.0;
        for (int d = 0; d < dim; ++d) a2 += a(i, d) * a(i, d);
        if (a2 > 0.0) {
          const Real t = c_force * math::sqrt(h(i) / math::sqrt(a2));
          dmin = t < dmin ? t : dmin;
        }
      },
      Kokkos::Min<Real>(dt));
  return dt;
}

void TwoFluidDust::reorder(ParticleReorder& r) {
  r.apply(v_start);
  r.apply(dv);
  r.apply(du);
  r.apply(tinv);
}

namespace {

/// Mass, momentum and kinetic energy of the gas (dust = false) or of all dust particles.
struct PhaseSums {
  Real mass = 0.0, momentum[3] = {0.0, 0.0, 0.0}, kinetic = 0.0;
};

PhaseSums phase_sums(const Particles& p, bool dust) {
  const auto type = p.type;
  const auto m = p.m;
  const auto v = p.v;
  const int dim = p.dim;
  PhaseSums s;
  par_reduce(
      "sph::two_fluid_mass", 0, p.n,
      KOKKOS_LAMBDA(int i, Real& acc) { acc += ((type(i) != kGas) == dust) ? m(i) : 0.0; }, s.mass);
  for (int d = 0; d < dim; ++d)
    par_reduce(
        "sph::two_fluid_momentum", 0, p.n,
        KOKKOS_LAMBDA(int i, Real& acc) { acc += ((type(i) != kGas) == dust) ? m(i) * v(i, d) : 0.0; }, s.momentum[d]);
  par_reduce(
      "sph::two_fluid_kinetic", 0, p.n,
      KOKKOS_LAMBDA(int i, Real& acc) {
        Real v2 = 0.0;
        for (int d = 0; d < dim; ++d) v2 += v(i, d) * v(i, d);
        acc += ((type(i) != kGas) == dust) ? 0.5 * m(i) * v2 : 0.0;
      },
      s.kinetic);
  return s;
}

}  // namespace

void TwoFluidDust::add_diagnostics(const SphSystem& sys, Diagnostics& dg) const {
  dg.dust_mass = phase_sums(sys.particles(), true).mass;
}

std::vector<io::Diagnostic> TwoFluidDust::history(const SphSystem& sys) const {
  const PhaseSums gas = phase_sums(sys.particles(), false), dust = phase_sums(sys.particles(), true);
  std::vector<io::Diagnostic> out = {{"gas_momentum_x", gas.momentum[0]},
                                     {"gas_momentum_y", gas.momentum[1]},
                                     {"gas_momentum_z", gas.momentum[2]},
                                     {"dust_momentum_x", dust.momentum[0]},
                                     {"dust_momentum_y", dust.momentum[1]},
                                     {"dust_momentum_z", dust.momentum[2]},
                                     {"gas_kinetic", gas.kinetic},
                                     {"dust_kinetic", dust.kinetic},
                                     {"dust_mass", dust.mass},
                                     {"drag_heating", drag_heating()}};
  if (s_.nspecies > 1) {
    int unsolved = 0;
    Kokkos::deep_copy(unsolved, mixture_unsolved);
    out.push_back({"drag_mixture_unsolved", static_cast<Real>(unsolved)});
  }
  return out;
}

namespace {

/// The density and sound speed of the last force evaluation: the drag after
/// the first half kick of the next step uses them (the engine recomputes them
/// only after the drift), so a restart needs them to continue bit for bit.
const char* const kSavedFields[] = {"/state/two_fluid_rho", "/state/two_fluid_cs"};

}  // namespace

void TwoFluidDust::write_phantom_dump(const SphSystem&, io::PhantomDump& dump) const {
  dump.header_int("ndustlarge", {s_.nspecies});
  dump.header_real("grainsize", s_.grain_sizes());
  dump.header_real("graindens", s_.grain_densities());
}

void TwoFluidDust::save_state(const SphSystem& sys, io::H5File& f) const {
  const Particles& p = sys.particles();
  const io::Block block = io::Block::whole({static_cast<hsize_t>(p.n)});
  const RealView1 fields[] = {p.rho, p.cs};
  for (int k = 0; k < 2; ++k) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), fields[k]);
    f.write(kSavedFields[k], block, h.data());
  }
  const Real heating = drag_heating();
  f.write("/state/two_fluid_drag_heating", io::Block::whole({1}), &heating);
  int unsolved = 0;  // the history's running count
  Kokkos::deep_copy(unsolved, mixture_unsolved);
  f.write_attribute("/state", "two_fluid_mixture_unsolved", static_cast<std::int64_t>(unsolved));
}

void TwoFluidDust::load_state(SphSystem& sys, const io::H5File& f) {
  const Particles& p = sys.particles();
  const io::Block block = io::Block::whole({static_cast<hsize_t>(p.n)});
  const RealView1 fields[] = {p.rho, p.cs};
  for (int k = 0; k < 2; ++k) {
    auto h = Kokkos::create_mirror_view(fields[k]);
    f.read(kSavedFields[k], block, h.data());
    Kokkos::deep_copy(fields[k], h);
  }
  Real heating = 0.0;
  f.read("/state/two_fluid_drag_heating", io::Block::whole({1}), &heating);
  Kokkos::deep_copy(heat_total, heating);
  const char* unsolved = "two_fluid_mixture_unsolved";  // absent before 2026-12-07: counted from 0
  Kokkos::deep_copy(mixture_unsolved, f.has_attribute("/state", unsolved)
                                          ? static_cast<int>(f.read_attribute_int("/state", unsolved))
                                          : 0);
}

TwoFluidDust& add_two_fluid_dust(SphSystem& sys, const DustSettings& settings) {
  if (sys.particles().n == 0) throw std::runtime_error("sph: two-fluid dust added before set_particles()");
  auto dust = std::make_shared<TwoFluidDust>(settings, sys);
  TwoFluidDust& module = *dust;
  sys.add_module(std::move(dust));
  return module;
}

}  // namespace mote::sph
