// Incomplete LU factorisation with level of fill k, ILU(k) (Saad 2003,
// sec. 10.3), on the device through Kokkos Kernels: spiluk symbolic once per
// pattern and level, spiluk numeric for each new set of values; the factors
// are applied as z = U^-1 L^-1 y with two sptrsv triangular solves.
#pragma once

#include <KokkosKernels_Handle.hpp>
#include <string>

#include "mote/linalg/crs_pattern.hpp"

namespace mote::linalg {

using KernelHandle =
    KokkosKernels::Experimental::KokkosKernelsHandle<Offset, Ordinal, Real, ExecSpace, MemSpace, MemSpace>;

class IluFactors {
 public:
  /// Symbolic phase: the fill pattern of L and U for level `fill_level`.
  IluFactors(const std::string& name, const CrsPattern& pattern, int fill_level);
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

 private:
  void symbolic(const CrsPattern& pattern, int estimate);

  int fill_level_;
  KernelHandle ilu_handle_, lower_handle_, upper_handle_;
  RowMap A_row_map_, L_row_map_, U_row_map_;
  Entries A_entries_, L_entries_, U_entries_;
  Values L_values_, U_values_;
  Vector between_;  // L^-1 y
};

}  // namespace mote::linalg
