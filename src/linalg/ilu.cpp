// ILU(k): Kokkos Kernels spiluk symbolic and sptrsv, a level-scheduled numeric
// phase of mote's own (see ilu.hpp).
#include "mote/linalg/ilu.hpp"

#include <KokkosSparse_spiluk.hpp>
#include <KokkosSparse_sptrsv.hpp>
#include <algorithm>
#include <stdexcept>

#include "mote/core/loops.hpp"

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

IluFactors::IluFactors(const std::string& name, const CrsPattern& pattern, int fill_level, int sweeps)
    : fill_level_(fill_level),
      sweeps_(sweeps),
      A_row_map_(pattern.row_map),
      L_row_map_(name + "::L_row_map", pattern.n_rows + 1),
      U_row_map_(name + "::U_row_map", pattern.n_rows + 1),
      A_entries_(pattern.entries),
      between_(name + "::between", pattern.n_rows) {
  if (fill_level < 0) throw std::invalid_argument(name + ": ILU fill level must be >= 0");
  if (sweeps < 0) throw std::invalid_argument(name + ": triangular sweeps must be >= 0");
  if (sweeps > 0) sweep_ = Vector(name + "::sweep", pattern.n_rows);
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
  sort_rows_and_find_levels();
  ilu_handle_.destroy_spiluk_handle();     // its work arrays: mote's numeric phase needs only the pattern
  if (sweeps_ > 0 || kPlainLoops) return;  // Serial substitutes without sptrsv
  lower_handle_.create_sptrsv_handle(SPTRSVAlgorithm::SEQLVLSCHD_TP1, pattern.n_rows, true);
  upper_handle_.create_sptrsv_handle(SPTRSVAlgorithm::SEQLVLSCHD_TP1, pattern.n_rows, false);
  triangular::sptrsv_symbolic(&lower_handle_, L_row_map_, L_entries_);
  triangular::sptrsv_symbolic(&upper_handle_, U_row_map_, U_entries_);
}

/// Columns ascending in every row of L and U (L's diagonal last, U's first,
/// checked), and the level of each row: 0 without strictly lower entries,
/// else one more than the highest level among the rows it depends on.
void IluFactors::sort_rows_and_find_levels() {
  const int n = static_cast<int>(L_row_map_.extent(0)) - 1;
  auto sort = [n](const RowMap& row_map, const Entries& entries, bool diagonal_last) {
    auto rm = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), row_map);
    auto e = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), entries);
    for (int row = 0; row < n; ++row) {
      std::sort(e.data() + rm(row), e.data() + rm(row + 1));
      const Offset diagonal = diagonal_last ? rm(row + 1) - 1 : rm(row);
      if (rm(row + 1) == rm(row) || e(diagonal) != row)
        throw std::runtime_error("linalg: the ILU pattern of row " + std::to_string(row) + " has no diagonal entry");
    }
    Kokkos::deep_copy(entries, e);
    return std::make_pair(rm, e);
  };
  const auto [rm, e] = sort(L_row_map_, L_entries_, true);
  sort(U_row_map_, U_entries_, false);
  std::vector<int> level(n, 0), count;
  for (int row = 0; row < n; ++row) {
    for (Offset k = rm(row); k + 1 < rm(row + 1); ++k) level[row] = std::max(level[row], level[e(k)] + 1);
    if (level[row] >= static_cast<int>(count.size())) count.resize(level[row] + 1, 0);
    ++count[level[row]];
  }
  level_ptr_.assign(count.size() + 1, 0);
  for (std::size_t l = 0; l < count.size(); ++l) level_ptr_[l + 1] = level_ptr_[l] + count[l];
  level_rows_ = IntView1("linalg::ilu_level_rows", n);
  auto rows = Kokkos::create_mirror_view(level_rows_);
  std::vector<int> next(level_ptr_.begin(), level_ptr_.end() - 1);
  for (int row = 0; row < n; ++row) rows(next[level[row]]++) = row;
  Kokkos::deep_copy(level_rows_, rows);
}

namespace {

/// One row of the IKJ elimination (Saad 2003, Algorithm 10.4) on the ILU(k)
/// pattern, in the order of Kokkos Kernels' spiluk numeric: unpack A's row,
/// then for each strictly lower entry (i, k), ascending, l_ik = a_ik / u_kk
/// and a_ij -= l_ik u_kj over the pattern's j. Rows ascending, so the targets
/// of u_k* are found by merging. A zero pivot becomes 1e6 (as spiluk).
struct RowElimination {
  RowMap A_row_map;
  Entries A_entries;
  Values A_values;
  RowMap L_row_map;
  Entries L_entries;
  Values L_values;
  RowMap U_row_map;
  Entries U_entries;
  Values U_values;
  IntView1 rows;

  /// Position of `col` in entries[lo, hi) (ascending), or hi.
  KOKKOS_INLINE_FUNCTION static Offset find(const Entries& entries, Offset lo, Offset hi, Ordinal col) {
    Offset a = lo, b = hi;
    while (a < b) {
      const Offset mid = a + (b - a) / 2;
      if (entries(mid) < col)
        a = mid + 1;
      else
        b = mid;
    }
    return a < hi && entries(a) == col ? a : hi;
  }

  KOKKOS_INLINE_FUNCTION void operator()(int r) const {
    const Ordinal row = rows(r);
    const Offset l0 = L_row_map(row), l_diag = L_row_map(row + 1) - 1;
    const Offset u0 = U_row_map(row), u1 = U_row_map(row + 1);
    for (Offset k = l0; k < l_diag; ++k) L_values(k) = 0.0;
    L_values(l_diag) = 1.0;
    for (Offset k = u0; k < u1; ++k) U_values(k) = 0.0;
    for (Offset k = A_row_map(row); k < A_row_map(row + 1); ++k) {
      const Ordinal col = A_entries(k);
      if (col < row)
        L_values(find(L_entries, l0, l_diag, col)) = A_values(k);
      else
        U_values(find(U_entries, u0, u1, col)) = A_values(k);
    }
    for (Offset k = l0; k < l_diag; ++k) {
      const Ordinal prev = L_entries(k);
      const Offset p0 = U_row_map(prev);
      const Real factor = L_values(k) / U_values(p0);
      L_values(k) = factor;
      Offset l = k + 1, u = u0;
      for (Offset kk = p0 + 1; kk < U_row_map(prev + 1); ++kk) {
        const Ordinal col = U_entries(kk);
        const Real update = -U_values(kk) * factor;
        if (col < row) {
          while (l < l_diag && L_entries(l) < col) ++l;
          if (l < l_diag && L_entries(l) == col) L_values(l) += update;
        } else {
          while (u < u1 && U_entries(u) < col) ++u;
          if (u < u1 && U_entries(u) == col) U_values(u) += update;
        }
      }
    }
    if (U_values(u0) == 0.0) U_values(u0) = 1e6;
  }
};

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
  const RowElimination eliminate{A_row_map_, A_entries_, A.values,   L_row_map_, L_entries_,
                                 L_values_,  U_row_map_, U_entries_, U_values_,  level_rows_};
  for (std::size_t l = 0; l + 1 < level_ptr_.size(); ++l)
    Kokkos::parallel_for("linalg::ilu_numeric", Kokkos::RangePolicy<ExecSpace>(level_ptr_[l], level_ptr_[l + 1]),
                         eliminate);
  const int bad = first_bad_pivot(U_row_map_, U_entries_, U_values_);
  return bad < static_cast<int>(U_row_map_.extent(0)) - 1 ? bad : -1;
}

namespace detail {

/// x = T^-1 b, row after row (forward for the unit lower factor, backward for the upper), each
/// row as Kokkos Kernels' sptrsv computes it: diff = -sum of T_rc x_c over the off-diagonal
/// entries in column order, x_r = (b_r + diff) / T_rr. One thread: for the Serial back-end.
template <bool Lower>
void substitute(const IluFactors::Factor& T, const Vector& b, const Vector& x) {
  const auto rm = T.row_map;
  const auto e = T.entries;
  const auto v = T.values;
  const int n = static_cast<int>(b.extent(0));
  Kokkos::parallel_for(
      "linalg::ilu_substitution", Kokkos::RangePolicy<ExecSpace>(0, 1), KOKKOS_LAMBDA(int) {
        for (int k = 0; k < n; ++k) {
          const int row = Lower ? k : n - 1 - k;
          const Offset first = rm(row) + (Lower ? 0 : 1), last = rm(row + 1) - (Lower ? 1 : 0);
          Real diff = 0;
          for (Offset p = first; p < last; ++p) diff -= v(p) * x(e(p));
          x(row) = (b(row) + diff) / v(Lower ? last : rm(row));
        }
      });
}

/// w_out = y - (L - I) w_in: one Jacobi sweep of the unit lower factor (diagonal last in each row).
void lower_sweep(const IluFactors::Factor& L, const Vector& y, const Vector& w_in, const Vector& w_out) {
  const auto rm = L.row_map;
  const auto e = L.entries;
  const auto v = L.values;
  par_for(
      "linalg::ilu_lower_sweep", 0, static_cast<int>(y.extent(0)), KOKKOS_LAMBDA(int row) {
        Real s = y(row);
        for (Offset k = rm(row); k + 1 < rm(row + 1); ++k) s -= v(k) * w_in(e(k));
        w_out(row) = s;
      });
}

/// z_out = D^-1 (w - (U - D) z_in): one Jacobi sweep of the upper factor (diagonal first in each row);
/// the First sweep starts from z_in = 0: z_out = D^-1 w.
template <bool First>
void upper_sweep(const IluFactors::Factor& U, const Vector& w, const Vector& z_in, const Vector& z_out) {
  const auto rm = U.row_map;
  const auto e = U.entries;
  const auto v = U.values;
  par_for(
      "linalg::ilu_upper_sweep", 0, static_cast<int>(w.extent(0)), KOKKOS_LAMBDA(int row) {
        Real s = w(row);
        if (!First)  // a constant: the first sweep compiles without the loop
          for (Offset k = rm(row) + 1; k < rm(row + 1); ++k) s -= v(k) * z_in(e(k));
        z_out(row) = s / v(rm(row));
      });
}

}  // namespace detail

void IluFactors::apply(const Vector& y, const Vector& z) {
  if (sweeps_ > 0) return apply_sweeps(y, z);
  if constexpr (kPlainLoops) {
    detail::substitute<true>(lower(), y, between_);
    detail::substitute<false>(upper(), between_, z);
  } else {
    triangular::sptrsv_solve(&lower_handle_, L_row_map_, L_entries_, L_values_, y, between_);
    triangular::sptrsv_solve(&upper_handle_, U_row_map_, U_entries_, U_values_, between_, z);
  }
}

void IluFactors::apply_sweeps(const Vector& y, const Vector& z) {
  // Iterates alternate between two vectors so that the last one lands in `between_` (L) and in `z` (U).
  Vector in = y;
  for (int k = 0; k < sweeps_; ++k) {
    const Vector out = (sweeps_ - 1 - k) % 2 == 0 ? between_ : sweep_;
    detail::lower_sweep(lower(), y, in, out);
    in = out;
  }
  in = (sweeps_ % 2 == 0) ? z : sweep_;
  detail::upper_sweep<true>(upper(), between_, in, in);
  for (int k = 0; k < sweeps_; ++k) {
    const Vector out = (sweeps_ - 1 - k) % 2 == 0 ? z : sweep_;
    detail::upper_sweep<false>(upper(), between_, in, out);
    in = out;
  }
}

}  // namespace mote::linalg
