// Model systems of the sparse-solver tests; see model_systems.hpp.
#include "mote/linalg/model_systems.hpp"

namespace mote::linalg {

CrsPattern five_point_pattern(int n) {
  return build_pattern(
      "linalg::five_point", n * n,
      KOKKOS_LAMBDA(int row) {
        const int i = row % n, j = row / n;
        return 1 + (i > 0) + (i < n - 1) + (j > 0) + (j < n - 1);
      },
      KOKKOS_LAMBDA(int row, Ordinal* cols) {
        const int i = row % n, j = row / n;
        int k = 0;
        if (j > 0) cols[k++] = row - n;
        if (i > 0) cols[k++] = row - 1;
        cols[k++] = row;
        if (i < n - 1) cols[k++] = row + 1;
        if (j < n - 1) cols[k++] = row + n;
      });
}

void convection_diffusion_values(const CrsMatrix& A, int n, double cx, double cy, double scale) {
  const auto row_map = A.graph.row_map;
  const auto cols = A.graph.entries;
  const auto values = A.values;
  const double h = 1.0 / (n + 1);
  par_for(
      "linalg::convection_diffusion", 0, n * n, KOKKOS_LAMBDA(int row) {
        for (Offset k = row_map(row); k < row_map(row + 1); ++k) {
          const int c = cols(k);
          Real a = 4.0 / (h * h);
          if (c == row - 1) a = -1.0 / (h * h) - cx / (2 * h);
          if (c == row + 1) a = -1.0 / (h * h) + cx / (2 * h);
          if (c == row - n) a = -1.0 / (h * h) - cy / (2 * h);
          if (c == row + n) a = -1.0 / (h * h) + cy / (2 * h);
          values(k) = scale * a;
        }
      });
}

CrsPattern tridiagonal_pattern(int n) {
  return build_pattern(
      "linalg::tridiagonal", n, KOKKOS_LAMBDA(int row) { return 1 + (row > 0) + (row < n - 1); },
      KOKKOS_LAMBDA(int row, Ordinal* cols) {
        int k = 0;
        if (row > 0) cols[k++] = row - 1;
        cols[k++] = row;
        if (row < n - 1) cols[k++] = row + 1;
      });
}

void near_skew_values(const CrsMatrix& A, double diagonal) {
  const auto row_map = A.graph.row_map;
  const auto cols = A.graph.entries;
  const auto values = A.values;
  par_for(
      "linalg::near_skew", 0, A.numRows(), KOKKOS_LAMBDA(int row) {
        for (Offset k = row_map(row); k < row_map(row + 1); ++k)
          values(k) = cols(k) == row ? diagonal : (cols(k) < row ? -1.0 : 1.0);
      });
}

}  // namespace mote::linalg
