// The (R, theta) grid of RBO24 sec. 2, eq. 1-3 (see include/mote/mesh/grid.hpp).
#include "mote/mesh/grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mote/core/log.hpp"

namespace mote::mesh {

std::vector<double> log_edges(double lo, double hi, int n) {
  std::vector<double> e(n + 1);
  for (int k = 0; k <= n; ++k) e[k] = lo * std::pow(hi / lo, double(k) / n);
  e[n] = hi;
  return e;
}

std::vector<double> linear_edges(double lo, double hi, int n) {
  std::vector<double> e(n + 1);
  for (int k = 0; k <= n; ++k) e[k] = lo + (hi - lo) * double(k) / n;
  e[n] = hi;
  return e;
}

std::vector<double> power_edges(double lo, double hi, int n, double p) {
  std::vector<double> e(n + 1);
  for (int k = 0; k <= n; ++k) e[k] = lo + (hi - lo) * std::pow(double(k) / n, p);
  e[n] = hi;
  return e;
}

std::vector<double> block_edges(double lo, double split, double hi, int n, int n_inner) {
  auto inner = linear_edges(lo, split, n_inner);
  const auto outer = linear_edges(split, hi, n - n_inner);
  inner.insert(inner.end(), outer.begin() + 1, outer.end());
  return inner;
}

std::vector<double> log_block_edges(double lo, double split, double hi, int n, int n_inner) {
  auto inner = log_edges(lo, split, n_inner);
  const auto outer = log_edges(split, hi, n - n_inner);
  inner.insert(inner.end(), outer.begin() + 1, outer.end());
  return inner;
}

namespace {

/// An explicit edge list `key` must hold `n_key` + 1 strictly increasing values.
void check_edge_list(const core::Deck& d, core::DeckCheck& check, const std::string& key, const std::string& n_key) {
  const auto& e = d.real_array(key);
  const long long n = d.integer(n_key);
  if (static_cast<long long>(e.size()) != n + 1)
    check.fail(key, logging::cat("expected ", n + 1, " edges (", check.quote(n_key), " + 1), got ", e.size()));
  for (size_t k = 1; k < e.size(); ++k)
    if (!(e[k] > e[k - 1])) return check.fail(key, "edges must increase strictly");
}

void check_radial_blocks(const core::Deck& d, core::DeckCheck& check) {
  const double split = d.real("grid.R_split");
  if (!(split > d.real("grid.R_in") && split < d.real("grid.R_out")))
    check.fail("grid.R_split", "r_spacing = \"log_blocks\" needs it between " + check.quote("grid.R_in") + " and " +
                                   check.quote("grid.R_out"));
  const long long inner = d.integer("grid.r_block_cells");
  if (inner < 1 || inner >= d.integer("grid.nr"))
    check.fail("grid.r_block_cells", "r_spacing = \"log_blocks\" needs 1 <= it < " + check.quote("grid.nr"));
}

void check_radial_edges(const core::Deck& d, core::DeckCheck& check) {
  const std::string& rs = d.string("grid.r_spacing");
  if (rs == "edges") return check_edge_list(d, check, "grid.r_edges", "grid.nr");
  if (!(d.real("grid.R_out") > d.real("grid.R_in")))
    return check.fail("grid.R_out", "must exceed " + check.quote("grid.R_in"));
  if (rs == "log_blocks") check_radial_blocks(d, check);
}

void check_theta_edges(const core::Deck& d, core::DeckCheck& check) {
  const std::string& ts = d.string("grid.theta_spacing");
  if (ts == "edges") {
    check_edge_list(d, check, "grid.theta_edges", "grid.ntheta");
    const auto& e = d.real_array("grid.theta_edges");
    if (!e.empty() && (e.front() <= -1.5 || e.back() >= 1.5))
      check.fail("grid.theta_edges", "edges must lie within (-1.5, 1.5) rad");
    return;
  }
  const double t0 = d.real("grid.theta_min"), t1 = d.real("grid.theta_max");
  if (!(t1 > t0)) check.fail("grid.theta_max", "must exceed " + check.quote("grid.theta_min"));
  if (t0 <= -1.5) check.fail("grid.theta_min", "must exceed -1.5 rad");
  if (t1 >= 1.5) check.fail("grid.theta_max", "must be below 1.5 rad");
  if (ts != "blocks") return;
  const double split = d.real("grid.theta_split");
  if (!(split > t0 && split < t1))
    check.fail("grid.theta_split", "theta_spacing = \"blocks\" needs it between " + check.quote("grid.theta_min") +
                                       " and " + check.quote("grid.theta_max"));
  const long long inner = d.integer("grid.theta_block_cells");
  if (inner < 1 || inner >= d.integer("grid.ntheta"))
    check.fail("grid.theta_block_cells", "theta_spacing = \"blocks\" needs 1 <= it < " + check.quote("grid.ntheta"));
}

}  // namespace

void GridSpec::declare(core::DeckSchema& s) {
  s.table("grid", "The (R, theta) disc grid (RBO24 sec. 2).");
  s.integer("grid.nr").sets_state_size().min(1).doc("Active cells in R (over all MPI ranks).");
  s.real("grid.R_in").greater_than(0.0).unit("code length").doc("Inner radial edge.");
  s.real("grid.R_out").greater_than(0.0).unit("code length").doc("Outer radial edge (> R_in).");
  s.string("grid.r_spacing")
      .default_value(std::string("log"))
      .one_of({"log", "linear", "log_blocks", "edges"})
      .doc(
          "Radial spacing: log; linear; log_blocks (two logarithmic blocks split at R_split, r_block_cells inside "
          "it: a refined inner rim); edges (grid.r_edges).");
  s.real("grid.R_split").default_value(0.0).unit("code length").doc("Block boundary for r_spacing = \"log_blocks\".");
  s.integer("grid.r_block_cells").default_value(0LL).min(0).doc("Cells inside R_split for r_spacing = \"log_blocks\".");
  s.real_array("grid.r_edges")
      .default_value(std::vector<double>{})
      .min(0.0)
      .unit("code length")
      .doc("Explicit increasing radial edges (nr + 1 values) for r_spacing = \"edges\".");
  s.integer("grid.ntheta").sets_state_size().min(1).doc("Active cells in theta.");
  s.real("grid.theta_min")
      .default_value(0.0)
      .min(-1.5)
      .max(1.5)
      .unit("rad")
      .doc("Lowest edge angle above the mid-plane.");
  s.real("grid.theta_max").min(-1.5).max(1.5).unit("rad").doc("Highest edge angle above the mid-plane (> theta_min).");
  s.string("grid.theta_spacing")
      .default_value(std::string("linear"))
      .one_of({"linear", "power", "blocks", "edges"})
      .doc(
          "Theta spacing: linear; power (theta_min + dtheta (k/n)^theta_power); blocks (two linear blocks split at "
          "theta_split, theta_block_cells below it); edges (grid.theta_edges).");
  s.real("grid.theta_power").default_value(1.0).greater_than(0.0).doc("Exponent for theta_spacing = \"power\".");
  s.real("grid.theta_split").default_value(0.0).unit("rad").doc("Block boundary for theta_spacing = \"blocks\".");
  s.integer("grid.theta_block_cells")
      .default_value(0LL)
      .min(0)
      .doc("Cells below theta_split for theta_spacing = \"blocks\".");
  s.real_array("grid.theta_edges")
      .default_value(std::vector<double>{})
      .unit("rad")
      .doc("Explicit theta edges (ntheta + 1) for theta_spacing = \"edges\".");
  s.string("grid.geometry")
      .default_value(std::string("cylindrical"))
      .one_of({"cylindrical", "planar"})
      .doc("Cell volumes and areas: axisymmetric (eq. 1-3) or planar 2D (tests).");
  s.rule(check_radial_edges);
  s.rule(check_theta_edges);
}

GridSpec GridSpec::from_deck(const core::Deck& d) {
  GridSpec g;
  g.nr = static_cast<int>(d.integer("grid.nr"));
  g.ntheta = static_cast<int>(d.integer("grid.ntheta"));
  const double R_in = d.real("grid.R_in"), R_out = d.real("grid.R_out");
  const std::string& rs = d.string("grid.r_spacing");
  g.r_log = rs != "linear";
  if (rs == "edges") g.r_edges = d.real_array("grid.r_edges");
  if (rs == "log") g.r_edges = log_edges(R_in, R_out, g.nr);
  if (rs == "linear") g.r_edges = linear_edges(R_in, R_out, g.nr);
  if (rs == "log_blocks")
    g.r_edges =
        log_block_edges(R_in, d.real("grid.R_split"), R_out, g.nr, static_cast<int>(d.integer("grid.r_block_cells")));
  const double t0 = d.real("grid.theta_min"), t1 = d.real("grid.theta_max");
  const std::string& ts = d.string("grid.theta_spacing");
  if (ts == "linear") g.theta_edges = linear_edges(t0, t1, g.ntheta);
  if (ts == "power") g.theta_edges = power_edges(t0, t1, g.ntheta, d.real("grid.theta_power"));
  if (ts == "blocks") {
    const double split = d.real("grid.theta_split");
    const int inner = static_cast<int>(d.integer("grid.theta_block_cells"));
    g.theta_edges = block_edges(t0, split, t1, g.ntheta, inner);
  }
  if (ts == "edges") g.theta_edges = d.real_array("grid.theta_edges");
  g.geometry = d.string("grid.geometry") == "planar" ? Geometry::Planar : Geometry::Cylindrical;
  return g;
}

namespace {

/// Extends active edges by `ng` ghost edges on each side, continuing the
/// spacing of the outermost cells (geometric if `geometric`, else arithmetic).
std::vector<double> with_ghosts(const std::vector<double>& e, int ng, bool geometric) {
  std::vector<double> out(e.size() + 2 * ng);
  for (size_t k = 0; k < e.size(); ++k) out[k + ng] = e[k];
  const size_t n = e.size() - 1;
  for (int g = 1; g <= ng; ++g) {
    if (geometric) {
      out[ng - g] = out[ng - g + 1] * (e[0] / e[1]);
      out[ng + n + g] = out[ng + n + g - 1] * (e[n] / e[n - 1]);
    } else {
      out[ng - g] = out[ng - g + 1] - (e[1] - e[0]);
      out[ng + n + g] = out[ng + n + g - 1] + (e[n] - e[n - 1]);
    }
  }
  return out;
}

/// A hand-built spec (tests, set-ups) must hold nr + 1 and ntheta + 1 edges;
/// the deck's are checked with the deck.
void check_spec_sizes(const GridSpec& spec) {
  if (spec.nr < 1 || spec.ntheta < 1 || spec.r_edges.size() != size_t(spec.nr) + 1 ||
      spec.theta_edges.size() != size_t(spec.ntheta) + 1)
    throw std::invalid_argument(logging::cat("GridSpec: ", spec.nr, " x ", spec.ntheta, " cells need ", spec.nr + 1,
                                             " radial and ", spec.ntheta + 1, " theta edges, got ", spec.r_edges.size(),
                                             " and ", spec.theta_edges.size()));
}

/// Every theta edge, ghosts included, must lie inside (-pi/2, pi/2): beyond the
/// pole tan(theta) changes sign and a ghost cell's volume and face area with it.
void check_theta_ghosts(const std::vector<double>& t) {
  const double reach = std::max(-t.front(), t.back()), pole = 0.5 * M_PI;
  if (reach >= pole)
    throw core::DeckError(logging::cat(
        "grid: the theta ghost cells (the last cell's width continued) would reach ", reach,
        " rad, at or beyond the pole (pi/2); lower grid.theta_max (or raise grid.theta_min) or use more theta cells"));
}

RealView1 to_device(const std::string& name, const std::vector<double>& v) {
  RealView1 d(name, v.size());
  Kokkos::deep_copy(d, UnmanagedHostView<Real*>(const_cast<double*>(v.data()), v.size()));
  return d;
}

/// Cell volumes V, face areas AR and AZ and centre heights Zc of `g` from its
/// 1D edges (RBO24 app. A). A free function: nvcc does not allow extended
/// lambdas in constructors.
void fill_cell_geometry(Grid& g) {
  const int NI = g.nr_total(), NJ = g.nt_total();
  g.V = RealView2("grid::V", NI, NJ);
  g.AR = RealView2("grid::AR", NI + 1, NJ);
  g.AZ = RealView2("grid::AZ", NI, NJ + 1);
  g.Zc = RealView2("grid::Zc", NI, NJ);
  auto V_ = g.V, AR_ = g.AR, AZ_ = g.AZ, Zc_ = g.Zc;
  auto Re_ = g.Re, Rc_ = g.Rc, tte = g.tan_te, ttc = g.tan_tc, cte = g.cos_te;
  const bool planar = g.geometry == Geometry::Planar;
  par_for(
      "mesh::grid_geometry", 0, NI + 1, 0, NJ + 1, KOKKOS_LAMBDA(int i, int j) {
        const Real r0 = Re_(i);
        if (i < NI && j < NJ) {
          const Real r1 = Re_(i + 1), dtan = tte(j + 1) - tte(j);
          V_(i, j) = planar ? 0.5 * (r1 * r1 - r0 * r0) * dtan : (r1 * r1 * r1 - r0 * r0 * r0) * dtan / 3.0;
          Zc_(i, j) = Rc_(i) * ttc(j);
        }
        if (j < NJ) {
          const Real dtan = tte(j + 1) - tte(j);
          AR_(i, j) = planar ? r0 * dtan : r0 * r0 * dtan;
        }
        if (i < NI) {
          const Real r1 = Re_(i + 1);
          AZ_(i, j) = planar ? (r1 - r0) / cte(j) : 0.5 * (r1 * r1 - r0 * r0) / cte(j);
        }
      });
}

}  // namespace

Grid::Grid(const GridSpec& spec, const core::Comm& comm) : comm_(comm), rank_(comm.rank()), size_(comm.size()) {
  ng = spec.ghosts;
  geometry = spec.geometry;
  nr_global = spec.nr;
  nt = spec.ntheta;
  const int base = nr_global / size_, extra = nr_global % size_;
  nr = base + (rank_ < extra ? 1 : 0);
  i_offset = rank_ * base + std::min(rank_, extra);
  if (base < ng)  // the fewest cells of any rank: every rank refuses, none waits for the others
    throw core::DeckError(logging::cat("grid.nr = ", nr_global, " gives ranks fewer than ", ng, " radial cells on ",
                                       size_, " ranks; increase grid.nr or use fewer ranks"));
  check_spec_sizes(spec);
  r_edges_global = spec.r_edges;
  theta_edges_global = spec.theta_edges;

  // Radial edges of this slab with ghosts: taken from the global edges where
  // they exist, continued outside the domain with the boundary spacing.
  const auto all_r = with_ghosts(spec.r_edges, ng, spec.r_log && spec.r_edges.front() > 0);
  if (geometry == Geometry::Cylindrical && all_r.front() < 0)
    throw core::DeckError("grid: the inner ghost cells would reach R < 0; use log spacing or a larger grid.R_in");
  std::vector<double> re(nr + 2 * ng + 1);
  for (int k = 0; k <= nr + 2 * ng; ++k) re[k] = all_r[i_offset + k];
  const auto t = with_ghosts(spec.theta_edges, ng, false);
  check_theta_ghosts(t);

  std::vector<double> rc(nr + 2 * ng), dr(nr + 2 * ng), tcv(nt + 2 * ng);
  for (int i = 0; i < nr + 2 * ng; ++i) {
    rc[i] = 0.5 * (re[i] + re[i + 1]);
    dr[i] = re[i + 1] - re[i];
  }
  for (int j = 0; j < nt + 2 * ng; ++j) tcv[j] = 0.5 * (t[j] + t[j + 1]);
  std::vector<double> tan_tev(t.size()), sin_tev(t.size()), cos_tev(t.size()), tan_tcv(tcv.size());
  for (size_t j = 0; j < t.size(); ++j) {
    tan_tev[j] = std::tan(t[j]);
    sin_tev[j] = std::sin(t[j]);
    cos_tev[j] = std::cos(t[j]);
  }
  for (size_t j = 0; j < tcv.size(); ++j) tan_tcv[j] = std::tan(tcv[j]);

  Re = to_device("grid::Re", re);
  Rc = to_device("grid::Rc", rc);
  dR = to_device("grid::dR", dr);
  te = to_device("grid::te", t);
  tc = to_device("grid::tc", tcv);
  tan_te = to_device("grid::tan_te", tan_tev);
  tan_tc = to_device("grid::tan_tc", tan_tcv);
  sin_te = to_device("grid::sin_te", sin_tev);
  cos_te = to_device("grid::cos_te", cos_tev);

  fill_cell_geometry(*this);
  Re_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Re);
  Rc_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Rc);
  te_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), te);
  tc_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), tc);
  V_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), V);
}

}  // namespace mote::mesh
