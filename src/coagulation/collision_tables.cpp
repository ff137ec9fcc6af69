// Collision-product gather tables (RBO24 eq. 61-68; Rafikov et al. 2020;
// product splits of product_split.hpp).
#include "mote/coagulation/collision_tables.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "mote/coagulation/fragmentation.hpp"
#include "mote/coagulation/product_split.hpp"

namespace mote::coagulation {

namespace {

struct Entry {
  int target, pair;
  double weight;
  int limiter = -1;
};

GatherList to_gather_list(std::vector<Entry> entries, int targets, const char* name) {
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.target < b.target; });
  GatherList g;
  const std::string base = std::string("coagulation::") + name;
  g.ptr = IntView1(base + "_ptr", targets + 1);
  g.pair = IntView1(base + "_pair", entries.size());
  g.weight = RealView1(base + "_weight", entries.size());
  const bool limited = !entries.empty() && entries.front().limiter >= 0;
  if (limited) g.limiter = IntView1(base + "_limiter", entries.size());
  auto ptr = Kokkos::create_mirror_view(g.ptr);
  auto pair = Kokkos::create_mirror_view(g.pair);
  auto weight = Kokkos::create_mirror_view(g.weight);
  auto limiter = Kokkos::create_mirror_view(g.limiter);
  for (int t = 0; t <= targets; ++t) ptr(t) = 0;
  for (size_t e = 0; e < entries.size(); ++e) {
    ptr(entries[e].target + 1) += 1;
    pair(e) = entries[e].pair;
    weight(e) = entries[e].weight;
    if (limited) limiter(e) = entries[e].limiter;
  }
  for (int t = 0; t < targets; ++t) ptr(t + 1) += ptr(t);
  Kokkos::deep_copy(g.ptr, ptr);
  Kokkos::deep_copy(g.pair, pair);
  Kokkos::deep_copy(g.weight, weight);
  if (limited) Kokkos::deep_copy(g.limiter, limiter);
  return g;
}

/// Index of the largest centre <= m (m_c[0] < m < m_c[n-1]).
int lower_centre(const std::vector<double>& mc, double m) {
  return static_cast<int>(std::upper_bound(mc.begin(), mc.end(), m) - mc.begin()) - 1;
}

/// Adds the entries of a product of mass `m` split between the centres
/// either side of it (product_split.hpp; RBO24 eq. 63-65), all of it to the
/// first/last bin outside the grid. When a share lands in the bin of the
/// pair's larger grain i, that entry holds its share net of the mass the
/// collision removes from bin i (`net` = m - removed, given by the caller
/// without cancellation) and `self` is set, so the loss term skips it: the
/// weights are then O(m_j) for m_j << m_i and the round-off is relative to the
/// mass actually moved. `near_l` / `near_u` are m - m_l and m_u - m, also
/// computed without cancellation by the caller. The quadratic split adds its
/// correction entries to `corr`.
void split(std::vector<Entry>& out, std::vector<Entry>& corr, const std::vector<double>& mc,
           const std::vector<double>& me, ProductSplit scheme, int pair, int i, double m, double net, double near_l,
           double near_u, int l, bool& self) {
  const int n = static_cast<int>(mc.size());
  auto add = [&](int target, double w) {
    if (target == i) {  // only whole-mass entries reach here with target == i
      self = true;
      w = net;
    }
    if (w != 0) out.push_back({target, pair, w});
  };
  if (l < 0) return add(0, m);
  if (l >= n - 1) return add(n - 1, m);
  const int u = l + 1;
  const TwoBinWeights w = two_bin_weights(scheme == ProductSplit::quadratic, m, mc[l], mc[u], near_l, near_u);
  if (u == i) {  // remnant just below the target's centre: m_u - m is small
    self = true;
    out.push_back({l, pair, w.lower});
    out.push_back({u, pair, net - w.lower});
  } else if (l == i) {  // coagulation product just above the larger grain's centre
    self = true;
    if (net - w.upper != 0) out.push_back({l, pair, net - w.upper});
    out.push_back({u, pair, w.upper});
  } else {
    add(l, w.lower);
    add(u, m - w.lower);
  }
  if (scheme != ProductSplit::quadratic || n < 3 || near_l == 0 || near_u == 0) return;
  // Third centre beside the nearer of m_l, m_u in log m (m < edge u), inside the grid.
  const bool below = u == n - 1 || (l > 0 && m < me[u]);
  const QuadraticCorrection c = quadratic_correction(mc.data(), l, below, near_l, near_u);
  const int lim = split_limiter_index(c.near, !below);
  corr.push_back({c.third, pair, c.to_third, lim});
  corr.push_back({l, pair, c.to_lower, lim});
  corr.push_back({u, pair, c.to_upper, lim});
}

}  // namespace

ProductSplit product_split_from_name(const std::string& name) {
  if (name == "two-bin") return ProductSplit::two_bin;
  if (name == "quadratic") return ProductSplit::quadratic;
  throw std::invalid_argument("coagulation.product_split must be \"two-bin\" or \"quadratic\" (got \"" + name + "\")");
}

CollisionTables build_collision_tables(const MassGrid& grid, Real chi_im, Real eta, ProductSplit scheme) {
  const int n = grid.size();
  const auto& mc = grid.masses();
  const auto& me = grid.edges();
  CollisionTables t;
  t.species = n;
  t.pairs = n * (n + 1) / 2;
  t.mass = grid.mass_view();
  t.pair_i = IntView1("coagulation::pair_i", t.pairs);
  t.pair_j = IntView1("coagulation::pair_j", t.pairs);
  auto pi = Kokkos::create_mirror_view(t.pair_i);
  auto pj = Kokkos::create_mirror_view(t.pair_j);
  std::vector<Entry> coag, rem, frag, coag_corr, rem_corr;
  coag.reserve(2 * t.pairs);
  rem.reserve(2 * t.pairs);
  frag.reserve(t.pairs);
  t.self_target = IntView1("coagulation::self_target", t.pairs);
  auto self = Kokkos::create_mirror_view(t.self_target);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      const int p = pair_index(i, j);
      pi(p) = i;
      pj(p) = j;
      const double m_small = i == j ? mc[i] : mc[j];  // m_tot - m_i
      const double m_tot = mc[i] + mc[j];
      // m_product - (mass the pair takes out of bin i), without cancellation:
      const double net_coag = i == j ? 0.0 : mc[j];
      const double net_rem = i == j ? -(1.0 + chi_im) * mc[i] : -chi_im * mc[j];
      bool self_coag = false, self_rem = false;
      {
        const int l = m_tot >= mc[n - 1] ? n - 1 : lower_centre(mc, m_tot);
        const double near_l = l == i ? m_small : m_tot - mc[std::min(l, n - 1)];
        const double near_u = l + 1 < n ? mc[l + 1] - m_tot : 0.0;
        split(coag, coag_corr, mc, me, scheme, p, i, m_tot, net_coag, near_l, near_u, l, self_coag);
      }
      const double m_rem = remnant_mass(mc[i], mc[j], chi_im);
      if (m_rem > 0) {
        const int l = m_rem <= mc[0] ? -1 : lower_centre(mc, m_rem);
        const double near_u = l + 1 == i ? chi_im * m_small : (l + 1 < n && l >= 0 ? mc[l + 1] - m_rem : 0.0);
        const double near_l = l >= 0 ? m_rem - mc[l] : 0.0;
        split(rem, rem_corr, mc, me, scheme, p, i, m_rem, net_rem, near_l, near_u, l, self_rem);
      }
      const double m_frag = m_rem > 0 ? (1.0 + chi_im) * m_small : m_tot;  // m_tot - m_rem without cancellation
      const double m_largest = largest_fragment_mass(mc[i], mc[j], chi_im);
      const int l =
          std::min(n - 1, static_cast<int>(std::upper_bound(me.begin() + 1, me.end(), m_largest) - (me.begin() + 1)));
      frag.push_back({l, p, m_frag});
      self(p) = (self_coag ? 1 : 0) | (self_rem ? 2 : 0);
    }
  Kokkos::deep_copy(t.self_target, self);
  Kokkos::deep_copy(t.pair_i, pi);
  Kokkos::deep_copy(t.pair_j, pj);
  t.coag = to_gather_list(std::move(coag), n, "coag");
  t.remnant = to_gather_list(std::move(rem), n, "remnant");
  t.fragment = to_gather_list(std::move(frag), n, "fragment");
  t.has_correction = scheme == ProductSplit::quadratic && n >= 3;
  t.coag_correction = to_gather_list(std::move(coag_corr), n, "coag_correction");
  t.remnant_correction = to_gather_list(std::move(rem_corr), n, "remnant_correction");

  t.fragment_share = RealView2("coagulation::fragment_share", n, n);
  auto share = Kokkos::create_mirror_view(t.fragment_share);
  for (int l = 0; l < n; ++l) {
    double sum = 0;
    for (int k = 0; k < n; ++k) {
      share(l, k) = 0;
      if (k > l) continue;
      share(l, k) = fragment_mass_fraction_below(me[k + 1], me[0], me[l + 1], eta) -
                    fragment_mass_fraction_below(me[k], me[0], me[l + 1], eta);
      sum += share(l, k);
    }
    for (int k = 0; k <= l; ++k) share(l, k) /= sum;  // exact normalisation: mass conserved to round-off
  }
  Kokkos::deep_copy(t.fragment_share, share);
  return t;
}

}  // namespace mote::coagulation
