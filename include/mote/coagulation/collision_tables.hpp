// Where the products of every collision go (RBO24 eq. 61-68), precomputed once
// per mass grid as gather lists so that the rate kernel (one team per cell,
// one thread per target bin) needs no atomics and conserves mass pair by pair:
//  * coagulation: the product mass m_i + m_j is split between the centres
//    either side of it with mass fractions eps and 1 - eps (eq. 63, 65);
//    products beyond the last centre stay in the last bin. Optional
//    ("quadratic", product_split.hpp): the number-conserving two-bin split
//    of Kovetz & Olund (1969) plus a limited correction over a third bin
//    that also conserves the second moment;
//  * remnants m_rem (eq. 68) are split the same way (eq. 64); remnants below
//    the first centre go to the first bin;
//  * fragments m_frag = m_i + m_j - m_rem are collected per "fragment bin" l,
//    the bin of the largest fragment min(chi_im m_im, m_tar) (RBO24 sec. 5:
//    the smallest l with m^e_{l+1} above it), and each bin's total is then
//    spread over bins k <= l with the power-law fractions N_k(m^e_{l+1})
//    (eq. 66-67) -- the two-stage redistribution of Rafikov et al. (2020),
//    O(N^2) instead of O(N^3).
// Mass conservation by construction: for every pair the weights (net of the
// colliding masses) sum to zero, and when a product lands in the bin of the
// larger grain (m_j << m_i) the entry holds the net O(m_j) transfer, so the
// round-off is relative to the mass moved, not to m_i.
// Pairs are unordered, i >= j, numbered p = i (i + 1) / 2 + j.
#pragma once

#include <string>

#include "mote/coagulation/mass_grid.hpp"
#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

KOKKOS_INLINE_FUNCTION int pair_index(int i, int j) { return i >= j ? i * (i + 1) / 2 + j : j * (j + 1) / 2 + i; }

/// Gather list: for target t, entries [ptr(t), ptr(t+1)) of (pair, weight);
/// correction lists also name the limiter each entry is scaled by (product_split.hpp).
struct GatherList {
  IntView1 ptr;
  IntView1 pair;
  RealView1 weight;
  IntView1 limiter;  // empty for plain lists
};

/// How coagulation products and remnants between two centres are shared out.
enum class ProductSplit {
  two_bin,    // RBO24 eq. 63-65: mass fractions eps, 1 - eps
  quadratic,  // Kovetz & Olund two-bin number split + limited second-moment correction
};

/// "two-bin" or "quadratic" (deck key coagulation.product_split).
ProductSplit product_split_from_name(const std::string& name);

struct CollisionTables {
  int species = 0;
  int pairs = 0;
  RealView1 mass;
  IntView1 pair_i, pair_j;  // (pairs)
  /// Per pair: bit 1 (coagulation) / bit 2 (remnant) set when a product share lands
  /// in the bin of the larger grain i; that entry's weight is net of the mass the
  /// collision removes from bin i, and the loss term of bin i skips the channel.
  IntView1 self_target;
  GatherList coag;      // target bin k; weight = mass delivered to k per coagulating collision
  GatherList remnant;   // target bin k; weight = remnant mass delivered to k per fragmenting collision
  GatherList fragment;  // target fragment bin l; weight = m_frag per fragmenting collision
  /// Quadratic split only (else empty): zero-mass, zero-number corrections of the
  /// coagulation and remnant splits, each entry scaled by its limiter theta.
  GatherList coag_correction, remnant_correction;
  bool has_correction = false;
  RealView2 fragment_share;  // (l, k): fraction of fragment bin l's mass put in bin k <= l (eq. 67), rows sum to 1
};

/// Builds the tables for a grid, impactor excavation factor chi_im (eq. 68),
/// fragment slope eta (eq. 66) and product split.
CollisionTables build_collision_tables(const MassGrid& grid, Real chi_im, Real eta,
                                       ProductSplit split = ProductSplit::two_bin);

}  // namespace mote::coagulation
