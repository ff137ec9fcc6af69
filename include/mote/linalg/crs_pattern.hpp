// Sparse matrices in compressed-row storage on the device, set up once and
// updated many times (DESIGN.md): a CrsPattern (row offsets, sorted column
// indices, the position of every diagonal) is built once per stencil; a
// caller's kernel writes the values of a CrsMatrix on that pattern before
// every solve. Types follow the prebuilt instantiations of Kokkos Kernels
// (double values, int ordinals and offsets, LayoutLeft vectors), so that spmv,
// spiluk and sptrsv need no new instantiation.
#pragma once

#include <KokkosSparse_CrsMatrix.hpp>
#include <string>

#include "mote/core/kokkos_types.hpp"
#include "mote/core/loops.hpp"

namespace mote::linalg {

using Offset = int;
using Ordinal = int;
using CrsMatrix = KokkosSparse::CrsMatrix<Real, Ordinal, ExecSpace::device_type, void, Offset>;
using RowMap = View<Offset*>;
using Entries = View<Ordinal*>;
using Values = View<Real*>;
/// Right-hand sides and solutions (a RealView1 converts to it).
using Vector = Kokkos::View<Real*, Kokkos::LayoutLeft, MemSpace>;

/// The fixed structure of a sparse matrix: square, or the owned rows of a
/// distributed one, whose ghost columns [n_rows, n_cols) follow the owned
/// columns (linalg/distribution.hpp).
struct CrsPattern {
  int n_rows = 0;
  int n_cols = 0;   // n_rows for a square matrix
  RowMap row_map;   // (n_rows + 1)
  Entries entries;  // (nnz), strictly increasing within a row
  RowMap diagonal;  // (n_rows): index into entries of (row, row)
  int nnz() const { return static_cast<int>(entries.extent(0)); }
};

/// A zero-valued matrix on `pattern` (shares its row map and entries).
CrsMatrix make_matrix(const std::string& name, const CrsPattern& pattern);

/// Locates the diagonals and checks the pattern: columns in [0, n_cols),
/// strictly increasing in every row, every diagonal present. Throws
/// std::invalid_argument naming the first bad row.
void finish_pattern(const std::string& name, CrsPattern& pattern);

/// Builds a pattern on the device from two device functors:
///   count(row) -> number of entries in the row;
///   fill(row, Ordinal* cols) writes them into cols[0 .. count-1] in
///   increasing order.
/// n_cols < 0: square.
template <class Count, class Fill>
CrsPattern build_pattern(const std::string& name, int n_rows, const Count& count, const Fill& fill, int n_cols = -1) {
  CrsPattern pattern;
  pattern.n_rows = n_rows;
  pattern.n_cols = n_cols < 0 ? n_rows : n_cols;
  pattern.row_map = RowMap(name + "::row_map", n_rows + 1);
  const RowMap row_map = pattern.row_map;
  par_for(
      "linalg::pattern_count", 0, n_rows, KOKKOS_LAMBDA(int row) { row_map(row + 1) = count(row); });
  Kokkos::parallel_scan(
      "linalg::pattern_offsets", Kokkos::RangePolicy<ExecSpace>(0, n_rows + 1),
      KOKKOS_LAMBDA(int row, Offset& sum, bool final) {
        sum += row_map(row);
        if (final) row_map(row) = sum;
      });
  Offset nnz = 0;
  Kokkos::deep_copy(nnz, Kokkos::subview(row_map, n_rows));
  pattern.entries = Entries(name + "::entries", nnz);
  const Entries entries = pattern.entries;
  par_for(
      "linalg::pattern_fill", 0, n_rows, KOKKOS_LAMBDA(int row) { fill(row, entries.data() + row_map(row)); });
  finish_pattern(name, pattern);
  return pattern;
}

}  // namespace mote::linalg
