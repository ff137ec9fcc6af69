// Grain-size bins for multi-species dust (HPL18 sec. 4.3.1, eq. 63, Table 1):
// a cell-edge logarithmic grid from s_min to s_max with N cells of width
// dlog s = log10(s_max / s_min) / N; each species sits at the geometric mean of
// its cell edges, and its dust fraction is the power law d eps = eps0 s^(3-p) ds
// integrated over the cell, normalised so that the fractions sum to eps_total
// (eq. 9). Host-side set-up helper shared by both engines.
#pragma once

#include <cmath>
#include <stdexcept>
#include <vector>

namespace mote::dust {

struct SizeBins {
  std::vector<double> size;      ///< representative size s_j (geometric mean of the cell edges)
  std::vector<double> fraction;  ///< eps_j, summing to eps_total
  std::vector<double> edges;     ///< N + 1 cell edges
};

/// HPL18 eq. 63 integrated over each cell of the logarithmic grid.
inline SizeBins power_law_bins(int n, double s_min, double s_max, double p, double eps_total) {
  if (n < 1 || !(s_min > 0.0) || !(s_max > s_min)) throw std::invalid_argument("dust: invalid size grid");
  SizeBins b;
  const double dlog = std::log10(s_max / s_min) / n;
  for (int j = 0; j <= n; ++j) b.edges.push_back(s_min * std::pow(10.0, j * dlog));
  const double q = 4.0 - p;  // integral of s^(3-p) ds = s^(4-p) / (4-p)
  double sum = 0.0;
  for (int j = 0; j < n; ++j) {
    const double lo = b.edges[j], hi = b.edges[j + 1];
    b.size.push_back(std::sqrt(lo * hi));
    const double w = std::fabs(q) < 1e-12 ? std::log(hi / lo) : (std::pow(hi, q) - std::pow(lo, q)) / q;
    b.fraction.push_back(w);
    sum += w;
  }
  for (double& f : b.fraction) f *= eps_total / sum;
  return b;
}

}  // namespace mote::dust
