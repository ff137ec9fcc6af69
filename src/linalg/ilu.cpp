// ILU(k) on Kokkos Kernels spiluk + sptrsv (see ilu.hpp).
#include "mote/linalg/ilu.hpp"

#include <KokkosSparse_spiluk.hpp>
#include <KokkosSparse_sptrsv.hpp>
#include <stdexcept>

namespace mote::linalg {

namespace {
using KokkosSparse::Experimental::SPILUKAlgorithm;
using KokkosSparse::Experimental::SPTRSVAlgorithm;
}  // namespace

// Kokkos Kernels 4 promoted spiluk and sptrsv out of Experimental (3.4 has
// them only there; 4.x deprecates the old names).
#if defined(KOKKOSKERNELS_VERSION) && KOKKOSKERNELS_VERSION >= 40000
namespace triangular = KokkosSparse;
#else
namespace triangular = KokkosSparse::Experimental;
#endif

IluFactors::IluFactors(const std::string& name, const CrsPattern& pattern, int fill_level)
    : fill_level_(fill_level),
      A_row_map_(pattern.row_map),
      L_row_map_(name + "::L_row_map", pattern.n_rows + 1),
      U_row_map_(name + "::U_row_map", pattern.n_rows + 1),
      A_entries_(pattern.entries),
      between_(name + "::between", pattern.n_rows) {
  if (fill_level < 0) throw std::invalid_argument(name + ": ILU fill level must be >= 0");
  // spiluk needs storage for the fill before it knows it: start from
  // (k + 1) nnz(A) and grow until the symbolic phase fits.
  int estimate = (fill_level + 1) * pattern.nnz() + pattern.n_rows;
  for (int tries = 0;; ++tries) {
    try {
      L_entries_ = Entries(name + "::L_entries", estimate);
      U_entries_ = Entries(name + "::U_entries", estimate);
      symbolic(pattern, estimate);
      break;
    } catch (const std::runtime_error&) {
      if (tries == 6) throw;
      estimate *= 2;
    }
  }
  L_values_ = Values(name + "::L_values", L_entries_.extent(0));
  U_values_ = Values(name + "::U_values", U_entries_.extent(0));
}

IluFactors::~IluFactors() = default;

void IluFactors::symbolic(const CrsPattern& pattern, int estimate) {
  ilu_handle_.create_spiluk_handle(SPILUKAlgorithm::SEQLVLSCHD_TP1, pattern.n_rows, estimate, estimate);
  triangular::spiluk_symbolic(&ilu_handle_, fill_level_, A_row_map_, A_entries_, L_row_map_, L_entries_, U_row_map_,
                              U_entries_);
  Kokkos::resize(L_entries_, ilu_handle_.get_spiluk_handle()->get_nnzL());
  Kokkos::resize(U_entries_, ilu_handle_.get_spiluk_handle()->get_nnzU());
  lower_handle_.create_sptrsv_handle(SPTRSVAlgorithm::SEQLVLSCHD_TP1, pattern.n_rows, true);
  upper_handle_.create_sptrsv_handle(SPTRSVAlgorithm::SEQLVLSCHD_TP1, pattern.n_rows, false);
  triangular::sptrsv_symbolic(&lower_handle_, L_row_map_, L_entries_);
  triangular::sptrsv_symbolic(&upper_handle_, U_row_map_, U_entries_);
}

namespace {

/// First row whose U diagonal (the first entry of its sorted row) is zero or
/// not finite; n when none.
int first_bad_pivot(const RowMap& U_row_map, const Entries& U_entries, const Values& U_values) {
  const int n = static_cast<int>(U_row_map.extent(0)) - 1;
  int bad = n;
  par_reduce(
      "linalg::ilu_pivots", 0, n,
      KOKKOS_LAMBDA(int row, int& first) {
        const Offset k = U_row_map(row);
        const bool has_diagonal = k < U_row_map(row + 1) && U_entries(k) == row;
        const Real pivot = has_diagonal ? U_values(k) : 0.0;
        if ((pivot == 0.0 || !math::isfinite(pivot)) && row < first) first = row;
      },
      Kokkos::Min<int>(bad));
  return bad;
}

}  // namespace

int IluFactors::factorise(const CrsMatrix& A) {
  auto A_values = A.values;
  triangular::spiluk_numeric(&ilu_handle_, fill_level_, A_row_map_, A_entries_, A_values, L_row_map_, L_entries_,
                             L_values_, U_row_map_, U_entries_, U_values_);
  const int bad = first_bad_pivot(U_row_map_, U_entries_, U_values_);
  return bad < static_cast<int>(U_row_map_.extent(0)) - 1 ? bad : -1;
}

void IluFactors::apply(const Vector& y, const Vector& z) {
  triangular::sptrsv_solve(&lower_handle_, L_row_map_, L_entries_, L_values_, y, between_);
  triangular::sptrsv_solve(&upper_handle_, U_row_map_, U_entries_, U_values_, between_, z);
}

}  // namespace mote::linalg
