// Dense reference solves for the sparse-solver tests (D1): a CRS matrix
// copied into a dense host matrix, and Gaussian elimination with partial
// pivoting.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "mote/linalg/crs_pattern.hpp"

namespace mote::test {

using Dense = std::vector<std::vector<double>>;

inline Dense to_dense(const linalg::CrsMatrix& A) {
  const int n = A.numRows();
  auto row_map = Kokkos::create_mirror_view_and_copy(HostSpace(), A.graph.row_map);
  auto cols = Kokkos::create_mirror_view_and_copy(HostSpace(), A.graph.entries);
  auto values = Kokkos::create_mirror_view_and_copy(HostSpace(), A.values);
  Dense dense(n, std::vector<double>(n, 0.0));
  for (int r = 0; r < n; ++r)
    for (auto k = row_map(r); k < row_map(r + 1); ++k) dense[r][cols(k)] = values(k);
  return dense;
}

inline std::vector<double> dense_solve(Dense A, std::vector<double> b) {
  const int n = static_cast<int>(b.size());
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(A[r][c]) > std::fabs(A[p][c])) p = r;
    std::swap(A[c], A[p]);
    std::swap(b[c], b[p]);
    for (int r = c + 1; r < n; ++r) {
      const double f = A[r][c] / A[c][c];
      if (f == 0.0) continue;
      for (int k = c; k < n; ++k) A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  std::vector<double> x(n);
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < n; ++k) s -= A[r][k] * x[k];
    x[r] = s / A[r][r];
  }
  return x;
}

}  // namespace mote::test
