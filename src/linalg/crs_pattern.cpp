// CRS patterns: diagonal positions and structural checks (see crs_pattern.hpp).
#include "mote/linalg/crs_pattern.hpp"

#include <stdexcept>

namespace mote::linalg {

CrsMatrix make_matrix(const std::string& name, const CrsPattern& pattern) {
  Values values(name + "::values", pattern.nnz());
  return CrsMatrix(name, pattern.n_rows, pattern.n_cols, pattern.nnz(), values, pattern.row_map, pattern.entries);
}

namespace {

/// Smallest row whose columns are out of [0, n_cols), not increasing, or miss
/// the diagonal (n_rows when all are fine); records the diagonal positions.
int first_bad_row(const CrsPattern& pattern) {
  const int n = pattern.n_rows, n_cols = pattern.n_cols;
  const RowMap row_map = pattern.row_map, diagonal = pattern.diagonal;
  const Entries entries = pattern.entries;
  int bad = n;
  par_reduce(
      "linalg::pattern_check", 0, n,
      KOKKOS_LAMBDA(int row, int& first) {
        Offset diag = -1;
        bool ok = true;
        for (Offset k = row_map(row); k < row_map(row + 1); ++k) {
          const Ordinal col = entries(k);
          if (col < 0 || col >= n_cols || (k > row_map(row) && col <= entries(k - 1))) ok = false;
          if (col == row) diag = k;
        }
        diagonal(row) = diag;
        if ((!ok || diag < 0) && row < first) first = row;
      },
      Kokkos::Min<int>(bad));
  return bad;
}

}  // namespace

void finish_pattern(const std::string& name, CrsPattern& pattern) {
  if (static_cast<int>(pattern.row_map.extent(0)) != pattern.n_rows + 1)
    throw std::invalid_argument(name + ": row map of length " + std::to_string(pattern.row_map.extent(0)) + " for " +
                                std::to_string(pattern.n_rows) + " rows");
  if (pattern.n_cols < pattern.n_rows)
    throw std::invalid_argument(name + ": " + std::to_string(pattern.n_cols) + " columns for " +
                                std::to_string(pattern.n_rows) + " rows");
  pattern.diagonal = RowMap(name + "::diagonal", pattern.n_rows);
  const int bad = first_bad_row(pattern);
  if (bad < pattern.n_rows)
    throw std::invalid_argument(name + ": row " + std::to_string(bad) +
                                " has a column out of range, columns not strictly increasing, or no diagonal");
}

}  // namespace mote::linalg
