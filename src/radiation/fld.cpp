// Multi-band FLD (RBO24 sec. 4.1, eq. 40-43, 47-49, app. A); see fld.hpp.
#include "mote/radiation/fld.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/radiation/flux_limiter.hpp"
#include "mote/radiation/planck.hpp"

namespace mote::radiation {

using linalg::Ordinal;

RadiationConstants RadiationConstants::in(const units::UnitSystem& u) {
  const double flux_unit = u.energy() / (u.length * u.length * u.time);
  return {units::cgs::c / u.velocity(), units::cgs::sigma_SB / flux_unit};
}

void FldSettings::validate() const {
  if (bands() < 1) throw std::invalid_argument("radiation: at least one band (two band edges) is needed");
  for (int b = 0; b <= bands(); ++b) {
    if (!(band_edges_cm[b] > 0.0) || !std::isfinite(band_edges_cm[b]))
      throw std::invalid_argument("radiation: band edge " + std::to_string(b) + " must be a positive wavelength");
    if (b > 0 && !(band_edges_cm[b] > band_edges_cm[b - 1]))
      throw std::invalid_argument("radiation: band edges must increase (edge " + std::to_string(b) + ")");
  }
  if (!(boundaries.T_ext > 0.0) || !std::isfinite(boundaries.T_ext))
    throw std::invalid_argument("radiation: T_ext must be a positive, finite temperature");
  solver.validate();
}

namespace {

/// Active cells and rows of the FLD system; ghost references resolved
/// through the boundaries. Under MPI a radial side may face the neighbouring
/// rank's slab: its first ghost row holds that rank's cells (a halo), whose
/// E^b unknowns are ghost columns after the owned rows, the left slab's
/// first, each as (theta cell, band).
struct CellMap {
  int ng, nr, nt, nb;
  bool reflect_inner, reflect_outer, reflect_lower, reflect_upper;
  bool slab_inner, slab_outer;  // a neighbour rank's slab beyond R_in / R_out of this rank

  KOKKOS_INLINE_FUNCTION int cell(int i, int j) const { return (i - ng) * nt + (j - ng); }
  KOKKOS_INLINE_FUNCTION int i_of(int c) const { return ng + c / nt; }
  KOKKOS_INLINE_FUNCTION int j_of(int c) const { return ng + c % nt; }
  KOKKOS_INLINE_FUNCTION int row_E(int c, int b) const { return c * (nb + 1) + b; }
  KOKKOS_INLINE_FUNCTION int row_B(int c) const { return c * (nb + 1) + nb; }
  KOKKOS_INLINE_FUNCTION int owned_rows() const { return nr * nt * (nb + 1); }
  /// Ghost column of band b of the neighbour's cell in theta row j.
  KOKKOS_INLINE_FUNCTION int ghost_E(bool outer, int j, int b) const {
    return owned_rows() + (outer && slab_inner ? nt * nb : 0) + (j - ng) * nb + b;
  }
  /// Moves (i, j) (one ghost layer at most) to the cell whose value it holds:
  /// mirrored across reflecting sides, kept in the ghost row beyond a
  /// neighbour's slab; false where an open side gives the external field.
  KOKKOS_INLINE_FUNCTION bool source(int& i, int& j) const {
    if (i < ng && !slab_inner) {
      if (!reflect_inner) return false;
      i = 2 * ng - 1 - i;
    } else if (i >= ng + nr && !slab_outer) {
      if (!reflect_outer) return false;
      i = 2 * (ng + nr) - 1 - i;
    }
    if (j < ng) {
      if (!reflect_lower) return false;
      j = 2 * ng - 1 - j;
    } else if (j >= ng + nt) {
      if (!reflect_upper) return false;
      j = 2 * (ng + nt) - 1 - j;
    }
    return true;
  }
  /// Column of E^b at a cell given by source(): owned, or a ghost column.
  KOKKOS_INLINE_FUNCTION int column_E(int i, int j, int b) const {
    if (i < ng) return ghost_E(false, j, b);
    if (i >= ng + nr) return ghost_E(true, j, b);
    return row_E(cell(i, j), b);
  }
  /// E^b of (i, j) from the field (with its halo) or the external field.
  KOKKOS_INLINE_FUNCTION Real value_E(const RealView3& E, const RealView1& E_ext, int i, int j, int b) const {
    return source(i, j) ? E(i, j, b) : E_ext(b);
  }
};

CellMap cell_map(const mesh::Grid& grid, int nb, const FldBoundaries& b) {
  const auto reflect = [](RadiationBoundary side) { return side == RadiationBoundary::Reflecting; };
  const bool slab_inner = !grid.has_inner_boundary(), slab_outer = !grid.has_outer_boundary();
  return {grid.ng,
          grid.nr,
          grid.nt,
          nb,
          !slab_inner && reflect(b.inner),
          !slab_outer && reflect(b.outer),
          reflect(b.lower),
          reflect(b.upper),
          slab_inner,
          slab_outer};
}

/// The E^b rows of the cells in column i, as (theta cell, band): what the
/// neighbouring slab on that side holds as ghost columns.
IntView1 slab_side_rows(const CellMap& map, bool active, int i, const std::string& name) {
  const int per_side = map.nt * map.nb;
  IntView1 rows(name, active ? per_side : 0);
  if (active)
    par_for(
        "radiation::fld_ghost_rows", 0, per_side,
        KOKKOS_LAMBDA(int k) { rows(k) = map.row_E(map.cell(i, map.ng + k / map.nb), k % map.nb); });
  return rows;
}

/// The owned rows and the ghost columns of the neighbouring slabs (E^b of
/// their cells next to this rank's), for linalg's distributed solve.
linalg::Distribution fld_distribution(const mesh::Grid& grid, const CellMap& map) {
  linalg::Distribution d;
  if (grid.comm().size() == 1) return d;
  d.comm = grid.comm();
  d.owned = map.owned_rows();
  const int per_side = map.nt * map.nb;
  d.left = map.slab_inner ? grid.comm().rank() - 1 : -1;
  d.right = map.slab_outer ? grid.comm().rank() + 1 : -1;
  d.from_left = map.slab_inner ? per_side : 0;
  d.from_right = map.slab_outer ? per_side : 0;
  d.to_left = slab_side_rows(map, map.slab_inner, map.ng, "radiation::fld_to_left");
  d.to_right = slab_side_rows(map, map.slab_outer, map.ng + map.nr - 1, "radiation::fld_to_right");
  return d;
}

/// Inserts col into the sorted cols[0 .. n) unless present.
KOKKOS_INLINE_FUNCTION void insert_sorted(Ordinal* cols, int& n, Ordinal col) {
  int k = n;
  while (k > 0 && cols[k - 1] > col) --k;
  if (k > 0 && cols[k - 1] == col) return;
  for (int m = n; m > k; --m) cols[m] = cols[m - 1];
  cols[k] = col;
  ++n;
}

/// Columns of an E^b row: B of its cell and E^b of the 3 x 3 cells around it
/// (resolved through the boundaries), sorted; returns their number (<= 10).
KOKKOS_INLINE_FUNCTION int band_row_columns(const CellMap& map, int c, int b, Ordinal* cols) {
  int n = 0;
  insert_sorted(cols, n, map.row_B(c));
  const int i = map.i_of(c), j = map.j_of(c);
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj) {
      int a = i + di, d = j + dj;
      if (map.source(a, d)) insert_sorted(cols, n, map.column_E(a, d, b));
    }
  return n;
}

linalg::CrsPattern fld_pattern(const CellMap& map) {
  const int per_cell = map.nb + 1;
  return linalg::build_pattern(
      "radiation::fld_pattern", map.nr * map.nt * per_cell,
      KOKKOS_LAMBDA(int row) {
        const int c = row / per_cell, component = row % per_cell;
        if (component == map.nb) return per_cell;
        Ordinal cols[10];
        return band_row_columns(map, c, component, cols);
      },
      KOKKOS_LAMBDA(int row, Ordinal* cols) {
        const int c = row / per_cell, component = row % per_cell;
        if (component == map.nb) {
          for (int k = 0; k < per_cell; ++k) cols[k] = c * per_cell + k;
          return;
        }
        band_row_columns(map, c, component, cols);
      },
      map.owned_rows() + (map.slab_inner ? map.nt * map.nb : 0) + (map.slab_outer ? map.nt * map.nb : 0));
}

/// Where, within an E^b row, the assembly adds (the same positions for every band b:
/// the row's columns, B of its cell and E^b of the cells around it, sort alike for
/// each b). kBSlot: B of the cell. A neighbour slot: E^b of the cell (i + di, j + dj)
/// resolved through the boundaries, or -1 where an open side gives the external field.
constexpr int kBSlot = 9, kBandSlots = 10;
KOKKOS_INLINE_FUNCTION int neighbour_slot(int di, int dj) { return (di + 1) * 3 + (dj + 1); }

/// The position of col in row, -1 if the pattern lacks it.
KOKKOS_INLINE_FUNCTION int position_in_row(const linalg::CrsMatrix::row_map_type& row_map,
                                           const linalg::CrsMatrix::index_type& entries, int row, int col) {
  for (auto k = row_map(row); k < row_map(row + 1); ++k)
    if (entries(k) == col) return static_cast<int>(k - row_map(row));
  return -1;
}

/// The column of slot q of cell (i, j) in band b, -1 for the external field.
KOKKOS_INLINE_FUNCTION int slot_column(const CellMap& map, int i, int j, int b, int q) {
  if (q == kBSlot) return map.row_B(map.cell(i, j));
  int a = i + q / 3 - 1, d = j + q % 3 - 1;
  return map.source(a, d) ? map.column_E(a, d, b) : -1;
}

/// The slot table (cells, kBandSlots), set up once with the pattern (found in the
/// rows of band 0 and checked in every band's): assemble_band adds into a row's
/// entries without searching it.
View<int**> band_slot_table(const CellMap& map, const linalg::CrsMatrix& A) {
  const int cells = map.nr * map.nt;
  View<int**> slots("radiation::fld_band_slots", cells, kBandSlots);
  const auto row_map = A.graph.row_map;
  const auto entries = A.graph.entries;
  int mismatches = 0;
  par_reduce(
      "radiation::fld_band_slots", 0, cells,
      KOKKOS_LAMBDA(int c, int& bad) {
        const int i = map.i_of(c), j = map.j_of(c);
        for (int q = 0; q < kBandSlots; ++q) {
          const int col = slot_column(map, i, j, 0, q);
          slots(c, q) = col < 0 ? -1 : position_in_row(row_map, entries, map.row_E(c, 0), col);
          if (col >= 0 && slots(c, q) < 0) ++bad;
          for (int b = 1; b < map.nb && col >= 0; ++b) {
            const int row = map.row_E(c, b);
            if (entries(row_map(row) + slots(c, q)) != slot_column(map, i, j, b, q)) ++bad;
          }
        }
      },
      mismatches);
  if (mismatches > 0)
    throw std::logic_error("radiation: " + std::to_string(mismatches) +
                           " FLD matrix slots differ between bands (a pattern this assembly cannot use)");
  return slots;
}

}  // namespace

FldSolver::FldSolver(const mesh::Grid& grid, FldSettings settings, RadiationConstants constants)
    : grid_(grid), halo_(grid), settings_(std::move(settings)), constants_(constants), nb_(settings_.bands()) {
  settings_.validate();
  if (!(constants.c > 0.0 && constants.sigma > 0.0))
    throw std::invalid_argument("radiation: c and sigma must be positive in code units");
  band_edges_ = RealView1("radiation::band_edges", nb_ + 1);
  auto edges_h = Kokkos::create_mirror_view(band_edges_);
  for (int b = 0; b <= nb_; ++b) edges_h(b) = settings_.band_edges_cm[b];
  Kokkos::deep_copy(band_edges_, edges_h);

  E_ext_ = RealView1("radiation::E_ext", nb_);
  auto ext_h = Kokkos::create_mirror_view(E_ext_);
  const double T = settings_.boundaries.T_ext;
  for (int b = 0; b < nb_; ++b) {
    const double lo = b == 0 ? 0.0 : edges_h(b), hi = b == nb_ - 1 ? 0.0 : edges_h(b + 1);
    ext_h(b) = band_fraction(lo, hi, T) * 4.0 * constants_.sigma * T * T * T * T / constants_.c;
  }
  Kokkos::deep_copy(E_ext_, ext_h);

  planck_ = RealView3("radiation::planck_factors", grid.nr_total(), grid.nt_total(), nb_);
  for (int b = 0; b < nb_; ++b) {
    D_.emplace_back("radiation::D_band" + std::to_string(b), grid.nr_total(), grid.nt_total());
    Kokkos::deep_copy(D_.back(), 1.0);
    coef_.push_back(mesh::diffusion_coefficients(grid, D_.back()));
  }
  const CellMap map = cell_map(grid, nb_, settings_.boundaries);
  solver_ = std::make_unique<linalg::LinearSolver>("radiation::fld", fld_pattern(map), settings_.solver,
                                                   fld_distribution(grid, map));
  band_slots_ = band_slot_table(map, solver_->matrix());
  T_previous_ = RealView2("radiation::T_previous", grid.nr_total(), grid.nt_total());
  rhs_ = linalg::Vector("radiation::rhs", solver_->pattern().n_rows);
  x_ = linalg::Vector("radiation::x", solver_->pattern().n_rows);
}

FldSolver::~FldSolver() = default;

FldFields FldSolver::make_fields() const {
  const int NI = grid_.nr_total(), NJ = grid_.nt_total();
  return {RealView2("radiation::heat_capacity", NI, NJ), RealView2("radiation::heating", NI, NJ),
          RealView3("radiation::absorption", NI, NJ, nb_), RealView3("radiation::extinction", NI, NJ, nb_),
          RealView3("radiation::scattering_source", NI, NJ, nb_)};
}

FldState FldSolver::make_state() const {
  return {RealView2("radiation::T", grid_.nr_total(), grid_.nt_total()),
          RealView3("radiation::E", grid_.nr_total(), grid_.nt_total(), nb_)};
}

namespace {

/// f^b(T^n) in every active cell (eq. 40).
void compute_planck_factors(const mesh::Grid& grid, const RealView1& edges, const RealView2& T, const RealView3& f) {
  const int nb = static_cast<int>(f.extent(2));
  par_for(
      "radiation::planck_factors", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        for (int b = 0; b < nb; ++b) {
          const Real lo = b == 0 ? 0.0 : edges(b), hi = b == nb - 1 ? 0.0 : edges(b + 1);
          f(i, j, b) = band_fraction(lo, hi, T(i, j));
        }
      });
}

/// E^b = f^b(T) 4 sigma T^4 / c in every active cell.
void equilibrium_field(const mesh::Grid& grid, const RealView1& edges, Real c, Real sigma, const RealView2& T,
                       const RealView3& E) {
  const int nb = static_cast<int>(E.extent(2));
  par_for(
      "radiation::equilibrium_field", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const Real t = T(i, j), B = 4.0 * sigma * t * t * t * t;
        for (int b = 0; b < nb; ++b) {
          const Real lo = b == 0 ? 0.0 : edges(b), hi = b == nb - 1 ? 0.0 : edges(b + 1);
          E(i, j, b) = band_fraction(lo, hi, t) * B / c;
        }
      });
}

/// D = min(c lambda / rho kappa_R, c r) at active cells (eq. 41-43), from E^n (with its
/// halo) with its gradient from the four neighbours; ghost cells copy the nearest active
/// cell, but for the ghost rows of a neighbour's slab, which the halo exchange fills.
void compute_diffusion_coefficient(const mesh::Grid& grid, const CellMap& map, int b, Real c,
                                   const RealView3& extinction, const RealView3& E, const RealView1& E_ext,
                                   mesh::RadialHalo& halo, const RealView2& D) {
  const auto Rc = grid.Rc;
  const auto Zc = grid.Zc;
  par_for(
      "radiation::fld_diffusion_coefficient", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const auto value = [&](int a, int d) { return map.value_E(E, E_ext, a, d, b); };
        const Real e1R = Rc(i + 1) - Rc(i - 1), e1Z = Zc(i + 1, j) - Zc(i - 1, j);
        const Real e2R = 0.0, e2Z = Zc(i, j + 1) - Zc(i, j - 1);  // a column has one R
        const Real inner = value(i - 1, j), outer = value(i + 1, j), lower = value(i, j - 1), upper = value(i, j + 1);
        const Real d1 = outer - inner, d2 = upper - lower;
        const Real det = e1R * e2Z - e1Z * e2R;
        const Real gR = (d1 * e2Z - d2 * e1Z) / det, gZ = (e1R * d2 - e2R * d1) / det;
        const Real chi = extinction(i, j, b);
        const Real E_scale = limiter_energy_scale(E(i, j, b), inner, outer, lower, upper);
        const Real lambda = kley_limiter(limiter_ratio(math::sqrt(gR * gR + gZ * gZ), chi, E_scale));
        // Where E is nearly uniform (R -> 0 in a cell however thin) lambda -> 1/3 and c / 3 chi is
        // unbounded; c r, r the distance to the star, bounds it (a departure from eq. 41). It binds
        // only in cells thin over r whose E varies on a scale L longer than r, where the flux
        // becomes c E r / L instead of ~c E; rows of nearly empty cells no longer carry
        // coefficients ~1e22 times their neighbours'.
        const Real r = math::sqrt(Rc(i) * Rc(i) + Zc(i, j) * Zc(i, j));
        D(i, j) = math::fmin(c * lambda / chi, c * r);
      });
  const int i0 = grid.i_begin(), i1 = grid.i_end() - 1, j0 = grid.j_begin(), j1 = grid.j_end() - 1;
  par_for(
      "radiation::fld_diffusion_ghosts", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        if ((i < i0 && map.slab_inner) || (i > i1 && map.slab_outer)) return;
        const int ia = i < i0 ? i0 : (i > i1 ? i1 : i), ja = j < j0 ? j0 : (j > j1 ? j1 : j);
        if (ia != i || ja != j) D(i, j) = D(ia, ja);
      });
  halo.exchange(D);
}

/// The E^b rows of eq. 49 (times V): exchange with B, storage, and the net
/// outflow through the four faces, sum_faces (flux x area), from the Wu
/// coefficients; reflecting faces carry no flux, open ghosts go to the rhs.
void assemble_band(const mesh::Grid& grid, const CellMap& map, const View<int**>& slots, int b, Real inv_dt, Real c,
                   const mesh::DiffusionCoefficients& coef, const FldFields& fields, const RealView3& E,
                   const RealView3& f, const RealView1& E_ext, const linalg::CrsMatrix& A, const linalg::Vector& rhs) {
  const auto row_map = A.graph.row_map;
  const auto values = A.values;
  const auto V = grid.V;
  const auto k_abs = fields.absorption, S_sca = fields.scattering_source;
  const int ng = map.ng, nr = map.nr, nt = map.nt;
  par_for(
      "radiation::fld_assemble_band", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const int cell = map.cell(i, j), row = map.row_E(cell, b);
        const auto first = row_map(row);
        const Real vol = V(i, j), k = k_abs(i, j, b);
        values(first + slots(cell, kBSlot)) += -vol * k * f(i, j, b);
        values(first + slots(cell, neighbour_slot(0, 0))) += vol * (inv_dt + c * k) / c;
        Real r = vol * (inv_dt * E(i, j, b) + S_sca(i, j, b));
        // sign * (coefficient of the cell (ci, cj)) for every cell of a face flux.
        const auto face = [&](Real sign, const Real* cf, const int* ci, const int* cj) {
          for (int q = 0; q < 4; ++q) {
            const int slot = slots(cell, neighbour_slot(ci[q] - i, cj[q] - j));
            if (slot >= 0)
              values(first + slot) += sign * cf[q] / c;
            else
              r -= sign * cf[q] * E_ext(b);
          }
        };
        for (int side = 0; side < 2; ++side) {  // radial faces at Re(i) (inflow side) and Re(i + 1)
          const int I = i + side;
          const bool closed = side == 0 ? (I == ng && map.reflect_inner) : (I == ng + nr && map.reflect_outer);
          if (closed) continue;
          const Real cf[4] = {coef.radial(I, j, 0), coef.radial(I, j, 1), coef.radial(I, j, 2), coef.radial(I, j, 3)};
          const int ci[4] = {I - 1, I, I - 1, I}, cj[4] = {j, j, j - 1, j + 1};
          face(side == 0 ? -1.0 : 1.0, cf, ci, cj);
        }
        for (int side = 0; side < 2; ++side) {  // theta faces at te(j) and te(j + 1)
          const int J = j + side;
          const bool closed = side == 0 ? (J == ng && map.reflect_lower) : (J == ng + nt && map.reflect_upper);
          if (closed) continue;
          const Real cf[4] = {coef.theta(i, J, 0), coef.theta(i, J, 1), coef.theta(i, J, 2), coef.theta(i, J, 3)};
          const int ci[4] = {i, i, i - 1, i + 1}, cj[4] = {J - 1, J, J - 1, J};
          face(side == 0 ? -1.0 : 1.0, cf, ci, cj);
        }
        rhs(row) = r;
      });
}

/// The B rows of eq. 48 (times V), with C = rho c_V / (16 sigma T^3) (eq. 47);
/// the unknowns c E^b make their coefficients -V rho kappa_P^b.
void assemble_temperature(const mesh::Grid& grid, const CellMap& map, Real inv_dt, Real sigma, const FldFields& fields,
                          const RealView2& T, const RealView3& f, const linalg::CrsMatrix& A,
                          const linalg::Vector& rhs) {
  const auto row_map = A.graph.row_map;
  const auto values = A.values;
  const auto V = grid.V;
  const auto C_V = fields.heat_capacity, S = fields.heating;
  const auto k_abs = fields.absorption;
  const int nb = map.nb;
  par_for(
      "radiation::fld_assemble_temperature", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const int row = map.row_B(map.cell(i, j));
        const Real vol = V(i, j), Tn = T(i, j);
        const Real C = C_V(i, j) / (16.0 * sigma * Tn * Tn * Tn);
        const auto first = row_map(row);  // columns E^1 .. E^nb, B of this cell
        Real diagonal = inv_dt * C;
        for (int b = 0; b < nb; ++b) {
          diagonal += k_abs(i, j, b) * f(i, j, b);
          values(first + b) = -vol * k_abs(i, j, b);
        }
        values(first + nb) = vol * diagonal;
        rhs(row) = vol * (inv_dt * C * 4.0 * sigma * Tn * Tn * Tn * Tn + S(i, j));
      });
}

/// The unknown floors of the solve: c E^b of a cell is needed to the tolerance
/// relative to the larger of itself and the tolerance x B^n of the cell, B to
/// the tolerance relative to itself (floor 0). A band below that floor
/// carries less than that fraction of the cell's energy: the far Wien tail of
/// a cold cell, round-off of either sign, is not chased to relative accuracy.
void band_floors(const mesh::Grid& grid, const CellMap& map, Real fraction, const linalg::Vector& x,
                 const linalg::Vector& floors) {
  const int nb = map.nb;
  par_for(
      "radiation::fld_band_floors", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const int cell = map.cell(i, j);
        floors(map.row_B(cell)) = 0.0;
        for (int b = 0; b < nb; ++b) floors(map.row_E(cell, b)) = fraction * x(map.row_B(cell));
      });
}

/// x = (c E^n, B^n) as the initial guess.
void initial_guess(const mesh::Grid& grid, const CellMap& map, Real c, Real sigma, const FldState& state,
                   const linalg::Vector& x) {
  const auto T = state.T;
  const auto E = state.E;
  const int nb = map.nb;
  par_for(
      "radiation::fld_initial_guess", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const int cell = map.cell(i, j);
        const Real t = T(i, j);
        x(map.row_B(cell)) = 4.0 * sigma * t * t * t * t;
        for (int b = 0; b < nb; ++b) x(map.row_E(cell, b)) = c * E(i, j, b);
      });
}

}  // namespace

void FldSolver::equilibrate_radiation(FldState& state) const {
  equilibrium_field(grid_, band_edges_, constants_.c, constants_.sigma, state.T, state.E);
}

void FldSolver::update_diffusion(const FldFields& fields, const FldState& state) {
  const CellMap map = cell_map(grid_, nb_, settings_.boundaries);
  halo_.exchange(state.E);
  for (int b = 0; b < nb_; ++b) {
    compute_diffusion_coefficient(grid_, map, b, constants_.c, fields.extinction, state.E, E_ext_, halo_, D_[b]);
    mesh::update_diffusion_coefficients(grid_, D_[b], coef_[b]);
  }
}

void FldSolver::assemble(double inv_dt, const FldFields& fields, const FldState& state) {
  const CellMap map = cell_map(grid_, nb_, settings_.boundaries);
  const auto& A = solver_->matrix();
  Kokkos::deep_copy(A.values, 0.0);
  for (int b = 0; b < nb_; ++b)
    assemble_band(grid_, map, band_slots_, b, inv_dt, constants_.c, coef_[b], fields, state.E, planck_, E_ext_, A,
                  rhs_);
  assemble_temperature(grid_, map, inv_dt, constants_.sigma, fields, state.T, planck_, A, rhs_);
}

namespace {

/// First cell whose solved B is <= 0 or not finite; n_cells when none.
int first_bad_temperature(const CellMap& map, const linalg::Vector& x) {
  const int cells = map.nr * map.nt;
  int first_bad = cells;  // Kokkos::Min overwrites it with the identity (INT_MAX) when no cell is bad
  par_reduce(
      "radiation::fld_check_B", 0, map.nr * map.nt,
      KOKKOS_LAMBDA(int cell, int& first) {
        const Real B = x(map.row_B(cell));
        if (!(B > 0.0 && math::isfinite(B)) && cell < first) first = cell;
      },
      Kokkos::Min<int>(first_bad));
  return std::min(first_bad, cells);
}

/// T = (B / 4 sigma)^(1/4) and E^b = (c E^b) / c at the active cells.
void unpack_solution(const mesh::Grid& grid, const CellMap& map, Real c, Real sigma, const linalg::Vector& x,
                     const FldState& state) {
  const auto T = state.T;
  const auto E = state.E;
  const int nb = map.nb;
  par_for(
      "radiation::fld_write_back", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const int cell = map.cell(i, j);
        T(i, j) = math::pow(x(map.row_B(cell)) / (4.0 * sigma), 0.25);
        for (int b = 0; b < nb; ++b) E(i, j, b) = x(map.row_E(cell, b)) / c;
      });
}

}  // namespace

void FldSolver::write_back(FldState& state) const {
  const CellMap map = cell_map(grid_, nb_, settings_.boundaries);
  const int bad = first_bad_temperature(map, x_), cells = map.nr * map.nt;
  if (grid_.comm().max(bad < cells ? 1 : 0) > 0)
    throw core::NumericalError("radiation: the FLD solve gave B <= 0 or non-finite " +
                               (bad < cells ? "in cell (" + std::to_string(grid_.i_offset + map.i_of(bad) - map.ng) +
                                                  ", " + std::to_string(map.j_of(bad) - map.ng) + ")"
                                            : std::string("on another rank")) +
                               "; the previous temperature is kept");
  unpack_solution(grid_, map, constants_.c, constants_.sigma, x_, state);
}

linalg::SolveReport FldSolver::step(double dt, const FldFields& fields, FldState& state, double tolerance) {
  if (!(dt > 0.0)) throw std::invalid_argument("radiation: the FLD time-step must be > 0 (or infinity)");
  solver_->set_tolerance(tolerance > 0.0 ? tolerance : settings_.solver.tolerance);
  const double inv_dt = std::isinf(dt) ? 0.0 : 1.0 / dt;
  compute_planck_factors(grid_, band_edges_, state.T, planck_);
  update_diffusion(fields, state);
  assemble(inv_dt, fields, state);
  const CellMap map = cell_map(grid_, nb_, settings_.boundaries);
  initial_guess(grid_, map, constants_.c, constants_.sigma, state, x_);
  band_floors(grid_, map, settings_.solver.tolerance, x_, solver_->unknown_floors());
  const int per_cell = nb_ + 1;
  const int i_offset = grid_.i_offset;
  const auto describe = [map, per_cell, i_offset](int row) {
    const int cell = row / per_cell, component = row % per_cell;
    return (component == per_cell - 1 ? std::string("B") : "band " + std::to_string(component)) + ", cell (" +
           std::to_string(i_offset + map.i_of(cell) - map.ng) + ", " + std::to_string(map.j_of(cell) - map.ng) + ")";
  };
  auto report = solver_->solve(rhs_, x_, describe);
  write_back(state);
  halo_.exchange(state.E);  // E^{n+1} of the neighbouring slabs, as open_boundary_luminosity reads it
  return report;
}

double largest_relative_change(const mesh::Grid& grid, const RealView2& T, const RealView2& T_reference) {
  double worst = 0.0;
  par_reduce(
      "radiation::fld_temperature_change", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j, double& m) { m = math::fmax(m, math::fabs(T(i, j) / T_reference(i, j) - 1.0)); },
      Kokkos::Max<double>(worst));
  return grid.comm().max(worst);
}

double mean_relative_change(const mesh::Grid& grid, const RealView2& T, const RealView2& T_reference) {
  double sum = 0.0;
  par_reduce(
      "radiation::fld_mean_temperature_change", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j, double& s) { s += math::fabs(T(i, j) / T_reference(i, j) - 1.0); }, sum);
  return grid.comm().sum(sum) / (static_cast<double>(grid.nr_global) * grid.nt);
}

RealView2 total_energy_density(const RealView3& E) {
  RealView2 sum("radiation::E_total", E.extent(0), E.extent(1));
  const int nb = static_cast<int>(E.extent(2));
  par_for(
      "radiation::E_total", 0, static_cast<int>(E.extent(0)), 0, static_cast<int>(E.extent(1)),
      KOKKOS_LAMBDA(int i, int j) {
        for (int b = 0; b < nb; ++b) sum(i, j) += E(i, j, b);
      });
  return sum;
}

FldSolver::Relaxation FldSolver::relax_to_steady_state(const FldFields& fields, FldState& state, double max_change,
                                                       int max_solves, const FieldRefresh& refresh, double forcing) {
  if (!(forcing >= 0.0 && forcing < 1.0))
    throw std::invalid_argument("radiation: the steady state's forcing must lie in [0, 1)");
  const double exact = settings_.solver.tolerance;
  double change = 1.0;  // the first solve's forcing
  Relaxation done;
  while (done.solves < max_solves) {
    if (done.solves > 0 && refresh) refresh(state);
    Kokkos::deep_copy(T_previous_, state.T);
    // Settled to max_change after a loose solve: one exact solve ends it.
    const double tolerance = change <= max_change ? exact : std::fmin(std::fmax(exact, forcing * change), 0.5);
    const auto report = step(std::numeric_limits<double>::infinity(), fields, state, tolerance);
    ++done.solves;
    if (report.attempts.size() > 1)  // the configured preconditioner failed; a fallback rung solved it
      logging::warn("radiation: steady-state solve ", done.solves, " (tolerance ", tolerance, "): ", report.summary());
    done.iterations += report.total_iterations();
    for (const auto& attempt : report.attempts) done.solve_seconds += attempt.seconds;
    done.last_residual = report.last().residual;
    change = largest_relative_change(grid_, state.T, T_previous_);
    done.changes.push_back(change);
    done.solve_iterations.push_back(report.total_iterations());
    if (change <= max_change && tolerance == exact) return done;
  }
  throw core::NumericalError("radiation: the steady state did not settle to a relative temperature change of " +
                             logging::cat(max_change) + " in " + std::to_string(max_solves) +
                             " solves; change (BiCGStab iterations) per solve: " + done.history());
}

std::string FldSolver::Relaxation::history() const {
  std::string out;
  for (std::size_t k = 0; k < changes.size(); ++k)
    out += logging::cat(k ? ", " : "", logging::format("%.2e", changes[k]), " (", solve_iterations[k], ")");
  return out;
}

namespace {

/// Outward flux x area of band b through the open boundary faces: inner and
/// outer radial faces (row j), lower and upper theta faces (column i).
double open_face_power(const CellMap& map, int b, const mesh::DiffusionCoefficients& coef, const RealView3& E,
                       const RealView1& E_ext) {
  const int ng = map.ng, nr = map.nr, nt = map.nt;
  const auto value = [=] KOKKOS_FUNCTION(int i, int j) { return map.value_E(E, E_ext, i, j, b); };
  double power = 0.0;
  par_reduce(
      "radiation::fld_open_face_power", 0, 2 * (nt + nr),
      KOKKOS_LAMBDA(int f, double& sum) {
        if (f < 2 * nt) {  // radial faces: f < nt inner, else outer
          const bool outer = f >= nt;
          if (outer ? (map.reflect_outer || map.slab_outer) : (map.reflect_inner || map.slab_inner)) return;
          const int I = outer ? ng + nr : ng, j = ng + f % nt;
          const Real flux = coef.radial(I, j, 0) * value(I - 1, j) + coef.radial(I, j, 1) * value(I, j) +
                            coef.radial(I, j, 2) * value(I - 1, j - 1) + coef.radial(I, j, 3) * value(I, j + 1);
          sum += outer ? flux : -flux;
        } else {  // theta faces: lower, then upper
          const int g = f - 2 * nt;
          const bool upper = g >= nr;
          if (upper ? map.reflect_upper : map.reflect_lower) return;
          const int J = upper ? ng + nt : ng, i = ng + g % nr;
          const Real flux = coef.theta(i, J, 0) * value(i, J - 1) + coef.theta(i, J, 1) * value(i, J) +
                            coef.theta(i, J, 2) * value(i - 1, J - 1) + coef.theta(i, J, 3) * value(i + 1, J);
          sum += upper ? flux : -flux;
        }
      },
      power);
  return power;
}

}  // namespace

double FldSolver::open_boundary_luminosity(const FldState& state) const {
  const CellMap map = cell_map(grid_, nb_, settings_.boundaries);
  double total = 0.0;
  for (int b = 0; b < nb_; ++b) total += open_face_power(map, b, coef_[b], state.E, E_ext_);
  return grid_.comm().sum(total);
}

FldSolver::FaceFluxes FldSolver::face_fluxes(const FldState& state, int b) const {
  if (b < 0 || b >= nb_) throw std::invalid_argument("radiation: no band " + std::to_string(b));
  const CellMap map = cell_map(grid_, nb_, settings_.boundaries);
  const int ng = map.ng, nr = map.nr, nt = map.nt;
  FaceFluxes F{RealView2("radiation::F_radial", nr + 1, nt), RealView2("radiation::F_theta", nr, nt + 1)};
  const auto E = state.E;
  const auto E_ext = E_ext_;
  const auto coef = coef_[b];
  const auto AR = grid_.AR, AZ = grid_.AZ;
  const auto value = [=] KOKKOS_FUNCTION(int i, int j) { return map.value_E(E, E_ext, i, j, b); };
  par_for(
      "radiation::fld_radial_face_flux", 0, nr + 1, 0, nt, KOKKOS_LAMBDA(int f, int j) {
        const bool reflecting = (f == 0 && map.reflect_inner) || (f == nr && map.reflect_outer);
        F.radial(f, j) = reflecting ? 0.0 : coef.radial_flux(value, ng + f, ng + j) / AR(ng + f, ng + j);
      });
  par_for(
      "radiation::fld_theta_face_flux", 0, nr, 0, nt + 1, KOKKOS_LAMBDA(int i, int f) {
        const bool reflecting = (f == 0 && map.reflect_lower) || (f == nt && map.reflect_upper);
        F.theta(i, f) = reflecting ? 0.0 : coef.theta_flux(value, ng + i, ng + f) / AZ(ng + i, ng + f);
      });
  return F;
}

}  // namespace mote::radiation
