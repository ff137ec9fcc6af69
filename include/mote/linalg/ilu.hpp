// Incomplete LU factorisation with level of fill k, ILU(k) (Saad 2003,
// sec. 10.3, the IKJ variant of Algorithm 10.4), on the device: the fill
// pattern from Kokkos Kernels' spiluk symbolic once per pattern and level;
// the numeric phase for each new set of values is mote's, level-scheduled
// over rows (the levels of L's dependency graph, found once at set-up), with
// the arithmetic of Kokkos Kernels' spiluk numeric in the same order (the
// same factors bit for bit) but without its work array of (widest level) x
// (rows) indices, 4.8 GB for RBO24's 150 x 240 x 20 FLD system in Kokkos
// Kernels 3.4. The factors are applied as z = U^-1 L^-1 y with two sptrsv
// triangular solves, level-scheduled (one kernel per level: on a GPU the
// launches of a few hundred levels per solve dominate; the Serial back-end
// substitutes row after row instead, with sptrsv's arithmetic in each row,
// so the same bits without the levels' scattered accesses), or with m Jacobi
// sweeps per factor (Chow & Patel 2015; Anzt, Chow & Dongarra 2015): w = y,
// then m times w <- y - (L - I) w, and z = D^-1 w, then m times
// z <- D^-1 (w - (U - D) z): 2m + 1 row-parallel kernels, the truncated
// Neumann series of each factor, exact once m reaches the factor's longest
// dependency chain (levels - 1). A fixed m is a fixed linear preconditioner.
#pragma once

#include <KokkosKernels_Handle.hpp>
#include <string>
#include <vector>

#include "mote/linalg/crs_pattern.hpp"

namespace mote::linalg {

using KernelHandle =
    KokkosKernels::Experimental::KokkosKernelsHandle<Offset, Ordinal, Real, ExecSpace, MemSpace, MemSpace>;

class IluFactors {
 public:
  /// Symbolic phase: the fill pattern of L and U for level `fill_level`; the
  /// factors are applied by exact triangular solves (`sweeps` = 0) or by
  /// `sweeps` Jacobi sweeps per factor.
  IluFactors(const std::string& name, const CrsPattern& pattern, int fill_level, int sweeps = 0);
  ~IluFactors();
  IluFactors(const IluFactors&) = delete;
  IluFactors& operator=(const IluFactors&) = delete;

  /// Numeric phase from the values of A (on the pattern given at set-up).
  /// Returns the first row whose pivot is zero or non-finite, or -1.
  int factorise(const CrsMatrix& A);
  /// z = (LU)^-1 y; y and z must differ.
  void apply(const Vector& y, const Vector& z);

  int fill_level() const { return fill_level_; }
  int nnz_lower() const { return static_cast<int>(L_entries_.extent(0)); }
  int nnz_upper() const { return static_cast<int>(U_entries_.extent(0)); }
  /// The factors: L unit lower triangular (diagonal last in each row), U upper
  /// (diagonal first); columns ascending in every row.
  struct Factor {
    RowMap row_map;
    Entries entries;
    Values values;
  };
  Factor lower() const { return {L_row_map_, L_entries_, L_values_}; }
  Factor upper() const { return {U_row_map_, U_entries_, U_values_}; }
  /// Rows of each level of the numeric phase (levels of L's dependency graph).
  int levels() const { return static_cast<int>(level_ptr_.size()) - 1; }

 private:
  void symbolic(const CrsPattern& pattern, int estimate);
  void sort_rows_and_find_levels();
  void apply_sweeps(const Vector& y, const Vector& z);

  int fill_level_, sweeps_;
  KernelHandle ilu_handle_, lower_handle_, upper_handle_;
  RowMap A_row_map_, L_row_map_, U_row_map_;
  Entries A_entries_, L_entries_, U_entries_;
  Values L_values_, U_values_;
  std::vector<int> level_ptr_;  // host: rows of level l are level_rows_(level_ptr_[l] .. level_ptr_[l + 1] - 1)
  IntView1 level_rows_;
  Vector between_;  // L^-1 y
  Vector sweep_;    // the other half of each sweep's pair of iterates (sweeps > 0)
};

}  // namespace mote::linalg
