// Multi-species pressureless dust dynamics on the (R, theta) grid: RBO24
// sec. 3 and 3.1 (eq. 4-19); see include/mote/disc/dust_dynamics.hpp.
#include "mote/disc/dust_dynamics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/disc/dust_riemann.hpp"
#include "mote/dust/stopping_time.hpp"

namespace mote::disc {

namespace {

/// At least one species, a size range that is one, and one Schmidt number per
/// species (or none: all 1).
void check_species(const core::Deck& d, core::DeckCheck& check) {
  const bool list = d.string("dust.sizes_from") == "list";
  const std::string count_key = list ? "dust.sizes" : "dust.species";
  const size_t ns = list ? d.real_array("dust.sizes").size() : static_cast<size_t>(d.integer("dust.species"));
  const size_t nsc = d.real_array("dust.schmidt").size();
  if (list && ns == 0) check.fail("dust.sizes", "at least one species is needed (or dust.sizes_from = \"log\")");
  if (!list && !d.real_array("dust.sizes").empty())
    check.fail("dust.sizes", "is a list of sizes; with " + check.quote("dust.sizes_from") + " leave it out");
  if (!list && ns > 1 && !(d.real("dust.a_max") > d.real("dust.a_min")))
    check.fail("dust.a_max", "must exceed " + check.quote("dust.a_min"));
  if (nsc != 0 && nsc != ns)
    check.fail("dust.schmidt",
               logging::cat("has ", nsc, " values for ", ns, " species (", check.quote(count_key), ")"));
}

using View4 = View<Real****>;

/// Longest step for which an acceleration a moves dust with stopping time t_s by at
/// most the fraction c of a cell dx, as the velocity limit c dx / |v| does for a
/// velocity: a dt^2 / 2 <= c dx while dt < t_s (dust starting at rest), a t_s dt <=
/// c dx beyond (the terminal velocity a t_s).
KOKKOS_INLINE_FUNCTION Real source_step_limit(Real c, Real dx, Real a, Real ts) {
  return math::max(math::sqrt(2 * c * dx / a), c * dx / (a * ts));
}

/// MDRange over (i, j, s) in [i0, i1) x [j0, j1) x [0, ns).
template <class F>
void for_cells(const std::string& name, int i0, int i1, int j0, int j1, int ns, const F& f) {
  par_for(name, i0, i1, j0, j1, 0, ns, f);
}

/// A ghost on a theta side (outward along +theta when `side` = +1, -theta when -1)
/// holding a copy of its edge cell: its velocity becomes its mirror image in the face,
/// (sn, cn) the face's (sin, cos), so the normal component changes sign and the
/// tangential one stays; always (`always`, a closed side: a mirror) or only where the
/// edge cell moves into the grid (an outflow side: nothing flows in).
template <class W>
KOKKOS_INLINE_FUNCTION void mirror_ghost(const W& w, int i, int j, int s, Real sn, Real cn, int side, bool always) {
  const Real vn = -w(i, j, s, kVR) * sn + w(i, j, s, kVZ) * cn;
  if (!always && vn * side >= 0) return;
  w(i, j, s, kVR) += 2.0 * vn * sn;
  w(i, j, s, kVZ) -= 2.0 * vn * cn;
}

/// Per-cell reconstruction geometry along one direction from cell centres xc and
/// edges xe: inv_dp, inv_dm, c_F, c_B (Mignone 2014, as RBO24 sec. 3.1 uses it), with
/// the grid's centres (midpoints, mesh/grid.hpp) for Mignone's centroids. A free function:
/// nvcc does not allow extended lambdas in constructors.
RealView2 slope_geometry(const std::string& name, const RealView1& xc, const RealView1& xe) {
  const int n = static_cast<int>(xc.extent(0));
  RealView2 g(name, n, 4);
  par_for(
      name, 1, n - 1, KOKKOS_LAMBDA(int i) {
        g(i, 0) = 1.0 / (xc(i + 1) - xc(i));
        g(i, 1) = 1.0 / (xc(i) - xc(i - 1));
        g(i, 2) = (xc(i + 1) - xc(i)) / (xe(i + 1) - xc(i));
        g(i, 3) = (xc(i) - xc(i - 1)) / (xc(i) - xe(i));
      });
  return g;
}

/// Stellar gravity (g_R, g_Z) at every cell centre, ghosts included (a free
/// function for the same reason).
RealView3 cell_gravity(const mesh::Grid& grid, const StellarGravity& star) {
  RealView3 g("dust::gravity", grid.nr_total(), grid.nt_total(), 2);
  auto Rc = grid.Rc;
  auto Zc = grid.Zc;
  par_for(
      "disc::dust_cell_gravity", 0, grid.nr_total(), 0, grid.nt_total(),
      KOKKOS_LAMBDA(int i, int j) { star.acceleration(Rc(i), Zc(i, j), g(i, j, 0), g(i, j, 1)); });
  return g;
}

}  // namespace

std::vector<double> grain_sizes_cm(const core::Deck& d) {
  if (d.string("dust.sizes_from") == "list") return d.real_array("dust.sizes");
  const long long n = d.integer("dust.species");
  const double a0 = d.real("dust.a_min"), a1 = d.real("dust.a_max");
  std::vector<double> a(static_cast<size_t>(n), a0);
  for (long long s = 1; s < n; ++s)
    a[static_cast<size_t>(s)] = a0 * std::pow(a1 / a0, static_cast<double>(s) / static_cast<double>(n - 1));
  return a;
}

void DustSettings::declare(core::DeckSchema& s) {
  s.table("dust", "Pressureless dust species on the grid (RBO24 sec. 3).");
  s.string("dust.sizes_from")
      .default_value(std::string("list"))
      .one_of({"list", "log"})
      .doc("Grain radii from the list dust.sizes, or dust.species radii log-spaced from dust.a_min to dust.a_max.");
  s.real_array("dust.sizes")
      .default_value(std::vector<double>{})
      .greater_than(0.0)
      .unit("cm")
      .doc("Grain radius of each species (sizes_from = \"list\").");
  s.integer("dust.species")
      .sets_state_size()
      .default_value(1LL)
      .min(1)
      .doc("Number of species (sizes_from = \"log\").");
  s.real("dust.a_min").default_value(1e-5).greater_than(0.0).unit("cm").doc("Smallest radius (sizes_from = \"log\").");
  s.real("dust.a_max").default_value(0.1).greater_than(0.0).unit("cm").doc("Largest radius (sizes_from = \"log\").");
  s.real("dust.rho_grain").default_value(1.6).greater_than(0.0).unit("g cm^-3").doc("Grain material density.");
  s.real_array("dust.schmidt")
      .default_value(std::vector<double>{})
      .greater_than(0.0)
      .doc("Schmidt number per species (eq. 15); empty = 1 for every species.");
  s.real("dust.floor").default_value(1e-40).greater_than(0.0).unit("code density").doc("Density floor.");
  s.real("dust.floor_ratio")
      .default_value(0.0)
      .min(0.0)
      .less_than(1.0)
      .doc(
          "Dust-to-gas floor: the floor of a cell is max(dust.floor, floor_ratio rho_g); cells below 10 x their floor "
          "do not limit the time-step (cuDisc: 1e-10).");
  s.real("dust.trace_ratio")
      .default_value(0.0)
      .min(0.0)
      .less_than(1.0)
      .doc(
          "Dust-to-gas ratio (per species) below which a cell holds only a trace of that species: it does not limit "
          "the time-step, and its (v_R, v_Z), as those of every cell the step skips (within 10 x the floor too), "
          "are scaled down so that a step carries at most dust.cfl_advection of the cell's dust out through its "
          "faces (a velocity ceiling), which keeps it stable at any step. 0: no trace cells (RBO24).");
  s.real("dust.cfl_advection").default_value(0.4).greater_than(0.0).max(1.0).doc("C_adv of eq. 18.");
  s.real("dust.cfl_diffusion").default_value(0.2).greater_than(0.0).max(1.0).doc("C_diff of eq. 19.");
  s.boolean("dust.diffusion").default_value(true).doc("Turbulent diffusion (eq. 15-16).");
  s.boolean("dust.drag").default_value(true).doc("Implicit gas drag (eq. 13-14).");
  s.boolean("dust.gravity").default_value(true).doc("Stellar gravity and curvature sources (eq. 6).");
  s.boolean("dust.radial_fluxes")
      .default_value(true)
      .doc(
          "Fluxes through the radial faces; false: every column evolves alone (vertical settling tests, RBO24 sec. "
          "3.6).");
  s.rule(check_species);
}

DustSettings DustSettings::from_deck(const core::Deck& d, const units::UnitSystem& u, const StellarGravity& star) {
  DustSettings st;
  for (double a : grain_sizes_cm(d)) st.sizes.push_back(a / u.length);
  st.schmidt = d.real_array("dust.schmidt");
  if (st.schmidt.empty()) st.schmidt.assign(st.sizes.size(), 1.0);
  st.rho_grain = d.real("dust.rho_grain") / u.density();
  st.floor = d.real("dust.floor");
  st.floor_ratio = d.real("dust.floor_ratio");
  st.trace_ratio = d.real("dust.trace_ratio");
  st.cfl_advection = d.real("dust.cfl_advection");
  st.cfl_diffusion = d.real("dust.cfl_diffusion");
  st.diffusion = d.boolean("dust.diffusion");
  st.drag = d.boolean("dust.drag");
  st.gravity = d.boolean("dust.gravity");
  st.radial_fluxes = d.boolean("dust.radial_fluxes");
  st.star = star;
  st.boundaries = mesh::Boundaries::from_deck(d);
  return st;
}

DustDynamics::DustDynamics(const mesh::Grid& grid, DustSettings settings)
    : grid_(grid), settings_(std::move(settings)), ns_(static_cast<int>(settings_.sizes.size())), halo_(grid) {
  const int NI = grid.nr_total(), NJ = grid.nt_total();
  Q = View4("dust::Q", NI, NJ, ns_, kDustVars);
  budget = View4("dust::mass_budget", NI, NJ, ns_, 2);
  W = View4("dust::W", NI, NJ, ns_, kDustVars);
  W_half_ = View4("dust::W_half", NI, NJ, ns_, kDustVars);
  flux_R_ = View4("dust::flux_R", NI + 1, NJ, ns_, kDustVars);
  flux_Z_ = View4("dust::flux_Z", NI, NJ + 1, ns_, kDustVars);
  slope_ = View4("dust::slope", NI, NJ, ns_, kDustVars);
  gas_ = GasFields(NI, NJ);
  gas_D_ = RealView2("dust::gas_D", NI, NJ);
  inv_rho_g_ = RealView2("dust::inv_rho_g", NI, NJ);
  Kokkos::deep_copy(inv_rho_g_, 1.0);
  gravity_ = cell_gravity(grid, settings_.star);
  stopping_time_ = View<Real***>("dust::stopping_time", NI, NJ, ns_);
  slope_R_ = slope_geometry("disc::dust_slope_geometry_R", grid.Rc, grid.Re);
  slope_Z_ = slope_geometry("disc::dust_slope_geometry_Z", grid.tan_tc, grid.tan_te);
  schmidt_ = RealView1("dust::schmidt", ns_);
  sizes_ = RealView1("dust::sizes", ns_);
  auto sc_h = Kokkos::create_mirror_view(schmidt_);
  auto sz_h = Kokkos::create_mirror_view(sizes_);
  for (int s = 0; s < ns_; ++s) {
    sc_h(s) = settings_.schmidt[s];
    sz_h(s) = settings_.sizes[s];
  }
  Kokkos::deep_copy(schmidt_, sc_h);
  Kokkos::deep_copy(sizes_, sz_h);
  Kokkos::deep_copy(gas_D_, 1.0);
  diffusion_ = mesh::diffusion_coefficients(grid, gas_D_);
}

void DustDynamics::set_gas(const GasFields& gas) {
  gas_ = gas;
  auto D = gas_D_, inv_rho = inv_rho_g_;
  auto rho = gas.rho, nu = gas.nu;
  par_for(
      "disc::dust_diffusivity", 0, grid_.nr_total(), 0, grid_.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        D(i, j) = rho(i, j) * nu(i, j);
        inv_rho(i, j) = 1.0 / rho(i, j);
      });
  mesh::update_diffusion_coefficients(grid_, gas_D_, diffusion_);
  auto ts = stopping_time_;
  auto cs2 = gas.cs2;
  auto sizes = sizes_;
  const Real rho_m = settings_.rho_grain;
  for_cells(
      "disc::dust_stopping_times", 0, grid_.nr_total(), 0, grid_.nt_total(), ns_, KOKKOS_LAMBDA(int i, int j, int s) {
        ts(i, j, s) = dust::epstein_stopping_time(rho_m, sizes(s), rho(i, j), math::sqrt(cs2(i, j)));
      });
}

void DustDynamics::initialise_from_primitives() {
  auto Q_ = Q, W_ = W;
  auto Rc = grid_.Rc;
  auto rho_g = gas_.rho;
  const Real floor = settings_.floor, floor_ratio = settings_.floor_ratio;
  for_cells(
      "disc::dust_initial_floor", grid_.i_begin(), grid_.i_end(), grid_.j_begin(), grid_.j_end(), ns_,
      KOKKOS_LAMBDA(int i, int j, int s) {
        W_(i, j, s, kRho) = math::max(W_(i, j, s, kRho), dust_floor(floor, floor_ratio, rho_g(i, j)));
      });
  fill_ghosts(W);
  for_cells(
      "disc::dust_prim_to_cons", 0, grid_.nr_total(), 0, grid_.nt_total(), ns_, KOKKOS_LAMBDA(int i, int j, int s) {
        const Real rho = W_(i, j, s, kRho);
        Q_(i, j, s, kRho) = rho;
        Q_(i, j, s, kMomR) = rho * W_(i, j, s, kVR);
        Q_(i, j, s, kAngMom) = rho * W_(i, j, s, kVphi) * Rc(i);
        Q_(i, j, s, kMomZ) = rho * W_(i, j, s, kVZ);
      });
}

void DustDynamics::fill_ghosts(const View4& w) {
  halo_.exchange(w);
  const int ng = grid_.ng, nr = grid_.nr, nt = grid_.nt, NI = grid_.nr_total(), ns = ns_;
  const Real floor = settings_.floor;
  const auto& b = settings_.boundaries;
  // Radial sides first (active rows j), then theta sides over all i, which fills the corners.
  // Outflow sides let dust leave and none enter (as cuDisc's open boundaries): where the
  // edge cell moves into the grid, the ghost takes its mirror velocity, so the face flux
  // is that of two diverging states, zero. Closed sides are mirrors: the ghost's normal
  // velocity is always reversed (compute_fluxes gives their faces the mirror's flux).
  if (grid_.has_inner_boundary() || grid_.has_outer_boundary()) {
    const bool do_in = grid_.has_inner_boundary(), do_out = grid_.has_outer_boundary();
    const bool zero_in = b.inner == mesh::BoundaryKind::Zero, zero_out = b.outer == mesh::BoundaryKind::Zero;
    const bool open_in = b.inner == mesh::BoundaryKind::Outflow, open_out = b.outer == mesh::BoundaryKind::Outflow;
    const bool shut_in = b.inner == mesh::BoundaryKind::Closed, shut_out = b.outer == mesh::BoundaryKind::Closed;
    par_for(
        "disc::dust_bc_radial", 0, ng, ng, ng + nt, 0, ns, KOKKOS_LAMBDA(int g, int j, int s) {
          for (int k = 0; k < kDustVars; ++k) {
            if (do_in) w(g, j, s, k) = w(ng, j, s, k);
            if (do_out) w(ng + nr + g, j, s, k) = w(ng + nr - 1, j, s, k);
          }
          if (do_in && zero_in) w(g, j, s, kRho) = floor;
          if (do_out && zero_out) w(ng + nr + g, j, s, kRho) = floor;
          if (do_in && (shut_in || (open_in && w(ng, j, s, kVR) > 0))) w(g, j, s, kVR) = -w(ng, j, s, kVR);
          if (do_out && (shut_out || (open_out && w(ng + nr - 1, j, s, kVR) < 0)))
            w(ng + nr + g, j, s, kVR) = -w(ng + nr - 1, j, s, kVR);
        });
  }
  const bool zero_lo = b.lower == mesh::BoundaryKind::Zero, zero_hi = b.upper == mesh::BoundaryKind::Zero;
  const bool open_lo = b.lower == mesh::BoundaryKind::Outflow, open_hi = b.upper == mesh::BoundaryKind::Outflow;
  const bool shut_lo = b.lower == mesh::BoundaryKind::Closed, shut_hi = b.upper == mesh::BoundaryKind::Closed;
  // The theta faces' normal, (-sin, cos) in (R, Z), as compute_fluxes takes it.
  const bool radial = settings_.radial_fluxes;
  auto sin_te = grid_.sin_te, cos_te = grid_.cos_te;
  par_for(
      "disc::dust_bc_theta", 0, NI, 0, ng, 0, ns, KOKKOS_LAMBDA(int i, int g, int s) {
        for (int k = 0; k < kDustVars; ++k) {
          w(i, g, s, k) = w(i, ng, s, k);
          w(i, ng + nt + g, s, k) = w(i, ng + nt - 1, s, k);
        }
        if (zero_lo) w(i, g, s, kRho) = floor;
        if (zero_hi) w(i, ng + nt + g, s, kRho) = floor;
        if (open_lo || shut_lo) mirror_ghost(w, i, g, s, radial ? sin_te(ng) : Real(0), cos_te(ng), -1, shut_lo);
        if (open_hi || shut_hi)
          mirror_ghost(w, i, ng + nt + g, s, radial ? sin_te(ng + nt) : Real(0), cos_te(ng + nt), +1, shut_hi);
      });
}

void DustDynamics::compute_slopes(const View4& w, bool radial) {
  const int ng = grid_.ng, nr = grid_.nr, nt = grid_.nt;
  auto sl = slope_;
  if (radial) {
    auto g = slope_R_;
    for_cells(
        "disc::dust_slopes_radial", ng - 1, ng + nr + 1, ng, ng + nt, ns_, KOKKOS_LAMBDA(int i, int j, int s) {
          for (int k = 0; k < kDustVars; ++k)
            sl(i, j, s, k) =
                mignone_slope(w(i - 1, j, s, k), w(i, j, s, k), w(i + 1, j, s, k), g(i, 0), g(i, 1), g(i, 2), g(i, 3));
        });
  } else {
    auto g = slope_Z_;
    for_cells(
        "disc::dust_slopes_theta", ng, ng + nr, ng - 1, ng + nt + 1, ns_, KOKKOS_LAMBDA(int i, int j, int s) {
          for (int k = 0; k < kDustVars; ++k)
            sl(i, j, s, k) =
                mignone_slope(w(i, j - 1, s, k), w(i, j, s, k), w(i, j + 1, s, k), g(j, 0), g(j, 1), g(j, 2), g(j, 3));
        });
  }
}

template <bool SecondOrder>
void DustDynamics::compute_fluxes(const View4& w) {
  const int ng = grid_.ng, nr = grid_.nr, nt = grid_.nt, ns = ns_;
  auto FR = flux_R_, FZ = flux_Z_;
  auto Rc = grid_.Rc, Re = grid_.Re, tan_tc = grid_.tan_tc, tan_te = grid_.tan_te;
  auto sin_te = grid_.sin_te, cos_te = grid_.cos_te;
  auto AR = grid_.AR, AZ = grid_.AZ;
  auto inv_rho_g = inv_rho_g_, gas_D = gas_D_, rho_g = gas_.rho;
  auto slope = slope_;
  auto sc = schmidt_;
  const auto coef = diffusion_;
  // No turbulent diffusion into or out of gas at its floor (an evacuated cavity):
  // dust diffused there would be decoupled and fall freely (as cuDisc).
  const Real gas_cut = kGasFloorDiffusionFactor * settings_.gas_floor;
  const bool diffuse = settings_.diffusion, radial = settings_.radial_fluxes;
  const auto& b = settings_.boundaries;
  const bool closed_in = grid_.has_inner_boundary() && b.inner == mesh::BoundaryKind::Closed;
  const bool closed_out = grid_.has_outer_boundary() && b.outer == mesh::BoundaryKind::Closed;
  const bool closed_lo = b.lower == mesh::BoundaryKind::Closed, closed_hi = b.upper == mesh::BoundaryKind::Closed;
  // No turbulent diffusion through the grid's own sides either (as cuDisc): the copied
  // ghost densities over the gas's ghosts would diffuse dust in wherever the gas thins
  // outwards.
  const bool edge_in = grid_.has_inner_boundary(), edge_out = grid_.has_outer_boundary();

  // Radial faces at Re(i), i in [ng, ng + nr]; cells L = i-1, R = i.
  if constexpr (SecondOrder) compute_slopes(w, true);
  for_cells(
      "disc::dust_flux_radial", ng, ng + nr + 1, ng, ng + nt, ns, KOKKOS_LAMBDA(int i, int j, int s) {
        Real ql[kDustVars], qr[kDustVars];
        for (int k = 0; k < kDustVars; ++k) {
          ql[k] = w(i - 1, j, s, k);
          qr[k] = w(i, j, s, k);
          if (SecondOrder) {  // a constant: nvcc 11.8 refuses first captures under if constexpr
            ql[k] += slope(i - 1, j, s, k) * (Re(i) - Rc(i - 1));
            qr[k] += slope(i, j, s, k) * (Re(i) - Rc(i));
          }
        }
        Real f[kDustVars] = {0, 0, 0, 0};
        const bool wall = (i == ng && closed_in) || (i == ng + nr && closed_out);
        if (radial && wall) {
          // A closed side is a mirror: the edge state moving into it meets its mirror
          // image, whose Roe average (eq. 11) is zero, so the face carries no mass and
          // the normal momentum rho v_n^2 (eq. 12, the mean of the two states).
          const Real* in = i == ng ? qr : ql;
          const Real vn = in[kVR];
          if (i == ng ? vn < 0 : vn > 0) f[kMomR] = in[kRho] * vn * vn * AR(i, j);
        } else if (radial) {
          const Real vl = ql[kVR], vr = qr[kVR];  // normal = R_hat
          const int side = upwind_side(ql[kRho], vl, qr[kRho], vr);
          const Real R = Re(i);
          f[kRho] = upwind_flux(side, ql[kRho], vl, qr[kRho], vr);
          f[kMomR] = upwind_flux(side, ql[kRho] * ql[kVR], vl, qr[kRho] * qr[kVR], vr);
          f[kAngMom] = upwind_flux(side, ql[kRho] * ql[kVphi] * R, vl, qr[kRho] * qr[kVphi] * R, vr);
          f[kMomZ] = upwind_flux(side, ql[kRho] * ql[kVZ], vl, qr[kRho] * qr[kVZ], vr);
          for (int k = 0; k < kDustVars; ++k) f[k] *= AR(i, j);
          const bool on_edge = (i == ng && edge_in) || (i == ng + nr && edge_out);
          if (diffuse && !on_edge && rho_g(i - 1, j) > gas_cut && rho_g(i, j) > gas_cut) {
            const auto u = [&](int a, int c) { return w(a, c, s, kRho) * inv_rho_g(a, c); };
            const Real fd = coef.radial_flux(u, i, j) / sc(s);  // already x area
            const Real* up = fd > 0 ? ql : qr;
            f[kRho] += fd;
            f[kMomR] += fd * up[kVR];
            f[kAngMom] += fd * up[kVphi] * R;
            f[kMomZ] += fd * up[kVZ];
          }
        }
        for (int k = 0; k < kDustVars; ++k) FR(i, j, s, k) = f[k];
      });

  // Theta faces at te(j), j in [ng, ng + nt]; cells L = j-1 (below), R = j; coordinate tan(theta).
  if constexpr (SecondOrder) compute_slopes(w, false);
  for_cells(
      "disc::dust_flux_theta", ng, ng + nr, ng, ng + nt + 1, ns, KOKKOS_LAMBDA(int i, int j, int s) {
        Real ql[kDustVars], qr[kDustVars];
        for (int k = 0; k < kDustVars; ++k) {
          ql[k] = w(i, j - 1, s, k);
          qr[k] = w(i, j, s, k);
          if (SecondOrder) {  // a constant: nvcc 11.8 refuses first captures under if constexpr
            ql[k] += slope(i, j - 1, s, k) * (tan_te(j) - tan_tc(j - 1));
            qr[k] += slope(i, j, s, k) * (tan_te(j) - tan_tc(j));
          }
        }
        Real f[kDustVars] = {0, 0, 0, 0};
        // Without radial fluxes the radial velocity is not transported through
        // the (tilted) theta faces either: only v_Z moves mass along a column.
        const Real sn = radial ? sin_te(j) : Real(0), cn = cos_te(j);
        const bool wall = (j == ng && closed_lo) || (j == ng + nt && closed_hi);
        if (wall) {
          // A closed side is a mirror (as the radial faces above): normal momentum only.
          const Real* in = j == ng ? qr : ql;
          const Real vn = -in[kVR] * sn + in[kVZ] * cn;
          if (j == ng ? vn < 0 : vn > 0) {
            const Real p = in[kRho] * vn * vn * AZ(i, j);
            f[kMomR] = -p * sn;
            f[kMomZ] = p * cn;
          }
        } else {
          const Real vl = -ql[kVR] * sn + ql[kVZ] * cn, vr = -qr[kVR] * sn + qr[kVZ] * cn;
          const int side = upwind_side(ql[kRho], vl, qr[kRho], vr);
          const Real R = Rc(i);
          f[kRho] = upwind_flux(side, ql[kRho], vl, qr[kRho], vr);
          f[kMomR] = upwind_flux(side, ql[kRho] * ql[kVR], vl, qr[kRho] * qr[kVR], vr);
          f[kAngMom] = upwind_flux(side, ql[kRho] * ql[kVphi] * R, vl, qr[kRho] * qr[kVphi] * R, vr);
          f[kMomZ] = upwind_flux(side, ql[kRho] * ql[kVZ], vl, qr[kRho] * qr[kVZ], vr);
          for (int k = 0; k < kDustVars; ++k) f[k] *= AZ(i, j);
          const bool on_edge = j == ng || j == ng + nt;
          if (diffuse && !on_edge && rho_g(i, j - 1) > gas_cut && rho_g(i, j) > gas_cut) {
            const auto u = [&](int a, int c) { return w(a, c, s, kRho) * inv_rho_g(a, c); };
            Real fd;
            if (radial) {
              fd = coef.theta_flux(u, i, j) / sc(s);
            } else {
              // Independent columns: two-point flux -D du/dZ along the column (harmonic
              // face D, as the Wu weights), through the horizontal projection of the face.
              const Real Za = R * tan_tc(j - 1), Zl = R * tan_tc(j), Zf = R * tan_te(j);
              const Real Da = gas_D(i, j - 1), Dl = gas_D(i, j);
              const Real k_face = Da * Dl / (Da * (Zl - Zf) + Dl * (Zf - Za));
              fd = -k_face * (u(i, j) - u(i, j - 1)) * AZ(i, j) * cn / sc(s);
            }
            const Real* up = fd > 0 ? ql : qr;
            f[kRho] += fd;
            f[kMomR] += fd * up[kVR];
            f[kAngMom] += fd * up[kVphi] * R;
            f[kMomZ] += fd * up[kVZ];
          }
        }
        for (int k = 0; k < kDustVars; ++k) FZ(i, j, s, k) = f[k];
      });
}

void DustDynamics::advance_stage(const View4& w_source, double dt_stage, double source_lead, double dt_step,
                                 const View4& w_out, bool update_q) {
  const int ng = grid_.ng, nr = grid_.nr, nt = grid_.nt, ns = ns_;
  auto Q_ = Q, FR = flux_R_, FZ = flux_Z_, B = budget;
  auto V = grid_.V;
  auto Rc = grid_.Rc, dR = grid_.dR, tan_te = grid_.tan_te;
  auto rho_g = gas_.rho, vgR = gas_.vR, vgphi = gas_.vphi, vgZ = gas_.vZ;
  auto grav = gravity_;
  auto stopping_time = stopping_time_;
  const Real dt = dt_stage, lead = source_lead, floor = settings_.floor, floor_ratio = settings_.floor_ratio;
  const Real trace = settings_.trace_ratio, ca = settings_.cfl_advection, h = dt_step;
  const bool gravity = settings_.gravity, drag = settings_.drag;
  const bool curvature = settings_.gravity && grid_.geometry == mesh::Geometry::Cylindrical;
  for_cells(
      "disc::dust_stage", ng, ng + nr, ng, ng + nt, ns, KOKKOS_LAMBDA(int i, int j, int s) {
        // Flux divergence (eq. 8-9) from Q^n.
        Real q[kDustVars];
        const Real inv_v = dt / V(i, j);
        const Real rho_n = Q_(i, j, s, kRho);
        for (int k = 0; k < kDustVars; ++k)
          q[k] = Q_(i, j, s, k) - inv_v * (FR(i + 1, j, s, k) - FR(i, j, s, k) + FZ(i, j + 1, s, k) - FZ(i, j, s, k));
        // Explicit sources (eq. 6) evaluated with the source-stage primitives.
        const Real R = Rc(i);
        const Real rs = w_source(i, j, s, kRho);
        Real aR = 0, aZ = 0;
        if (gravity) {
          aR = grav(i, j, 0);
          aZ = grav(i, j, 1);
        }
        if (curvature) aR += math::square(w_source(i, j, s, kVphi)) / R;
        // Conserved -> primitive (steps iii, vii). The transported specific momenta
        // are kept within the range of the 3 x 3 neighbourhood at the source stage:
        // transport (advection and eq. 16 diffusion) only averages velocities, and
        // this bound stops round-off in near-empty cells from creating huge
        // velocities there (which would collapse the time-step). The source-stage
        // velocities of the full step already hold the half step's sources, which
        // the momenta carried from t^n do not: the range holds each neighbour's
        // velocity before the half step's drag (backward Euler inverted, eq. 13
        // over source_lead) and is widened by the half step's kick, source_lead |a|.
        // Without them, dust at rest would be lifted to dt a / 2 before the step's
        // dt a is added (1.5 dt a per step for decoupled dust), and drifting dust
        // pulled to its half-step velocity before the step's drag (a decay factor
        // ts / (dt / 2 + ts) too many per step).
        const Real f = dust_floor(floor, floor_ratio, rho_g(i, j));
        const Real rho = math::max(q[kRho], f);
        Real vR, vphi, vZ;
        if (q[kRho] > f) {
          Real lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
          for (int a = i - 1; a <= i + 1; ++a)
            for (int c = j - 1; c <= j + 1; ++c) {
              const Real v3[3] = {w_source(a, c, s, kVR), w_source(a, c, s, kVphi) * Rc(a), w_source(a, c, s, kVZ)};
              const Real g3[3] = {vgR(a, c), vgphi(a, c) * Rc(a), vgZ(a, c)};
              const Real undo = drag ? lead / stopping_time(a, c, s) : 0;
              for (int k = 0; k < 3; ++k) {
                const Real before_drag = v3[k] + undo * (v3[k] - g3[k]);
                lo[k] = math::min(lo[k], math::min(v3[k], before_drag));
                hi[k] = math::max(hi[k], math::max(v3[k], before_drag));
              }
            }
          const Real kick[3] = {lead * math::fabs(aR), 0, lead * math::fabs(aZ)};
          for (int k = 0; k < 3; ++k) {
            lo[k] -= kick[k];
            hi[k] += kick[k];
          }
          const Real inv = 1.0 / q[kRho];
          vR = math::min(math::max(q[kMomR] * inv, lo[0]), hi[0]) + dt * aR * rs * inv;
          vphi = math::min(math::max(q[kAngMom] * inv, lo[1]), hi[1]) / R;
          vZ = math::min(math::max(q[kMomZ] * inv, lo[2]), hi[2]) + dt * aZ * rs * inv;
        } else {
          // An empty cell (at the floor) carries no dust and takes the gas velocity: kept
          // ballistic, its velocity would grow by dt a every step at a fixed place, without
          // bound (decoupled floor dust in a cavity reached 28 v_K and collapsed the step).
          vR = vgR(i, j);
          vphi = vgphi(i, j);
          vZ = vgZ(i, j);
        }
        if (drag) {
          const Real ts = stopping_time(i, j, s);
          vR = dust::implicit_drag(vR, vgR(i, j), dt, ts);
          vphi = dust::implicit_drag(vphi, vgphi(i, j), dt, ts);
          vZ = dust::implicit_drag(vZ, vgZ(i, j), dt, ts);
        }
        // With trace cells on, dust the step skipped at t^n or skips now stays below its ceiling.
        const bool skipped =
            skips_step_limit(rho_n, f, trace, rho_g(i, j)) || skips_step_limit(rho, f, trace, rho_g(i, j));
        if (trace > 0 && skipped)
          trace_ceiling(vR, vZ, ca, dR(i), Rc(i) * (tan_te(j + 1) - tan_te(j)),
                        math::max(math::fabs(tan_te(j)), math::fabs(tan_te(j + 1))), h);
        w_out(i, j, s, kRho) = rho;
        w_out(i, j, s, kVR) = vR;
        w_out(i, j, s, kVphi) = vphi;
        w_out(i, j, s, kVZ) = vZ;
        if (update_q) {
          if (q[kRho] < f) B(i, j, s, 0) += (f - q[kRho]) * V(i, j);
          Q_(i, j, s, kRho) = rho;
          Q_(i, j, s, kMomR) = rho * vR;
          Q_(i, j, s, kAngMom) = rho * vphi * R;
          Q_(i, j, s, kMomZ) = rho * vZ;
        }
      });
}

void DustDynamics::cap_trace_velocities(double dt) {
  auto W_ = W, Q_ = Q;
  auto Rc = grid_.Rc, dR = grid_.dR, tan_te = grid_.tan_te;
  auto rho_g = gas_.rho;
  const Real trace = settings_.trace_ratio, ca = settings_.cfl_advection, h = dt;
  const Real floor = settings_.floor, floor_ratio = settings_.floor_ratio;
  for_cells(
      "disc::dust_trace_ceiling", grid_.i_begin(), grid_.i_end(), grid_.j_begin(), grid_.j_end(), ns_,
      KOKKOS_LAMBDA(int i, int j, int s) {
        const Real rho = W_(i, j, s, kRho);
        if (!skips_step_limit(rho, dust_floor(floor, floor_ratio, rho_g(i, j)), trace, rho_g(i, j))) return;
        Real vR = W_(i, j, s, kVR), vZ = W_(i, j, s, kVZ);
        trace_ceiling(vR, vZ, ca, dR(i), Rc(i) * (tan_te(j + 1) - tan_te(j)),
                      math::max(math::fabs(tan_te(j)), math::fabs(tan_te(j + 1))), h);
        W_(i, j, s, kVR) = vR;
        W_(i, j, s, kVZ) = vZ;
        Q_(i, j, s, kMomR) = rho * vR;
        Q_(i, j, s, kMomZ) = rho * vZ;
      });
}

void DustDynamics::step(double dt) {
  // The velocity ceiling of the cells the step skipped (trace cells on); then (i) first-order
  // fluxes at t^n; (ii) half-step sources from P^n; (iii, iv) primitives + drag.
  if (settings_.trace_ratio > 0) cap_trace_velocities(dt);
  fill_ghosts(W);
  compute_fluxes<false>(W);
  advance_stage(W, 0.5 * dt, 0.0, dt, W_half_, false);
  // Boundary conditions again after step (iv); (v-viii) second-order fluxes at t^{n+1/2}.
  fill_ghosts(W_half_);
  compute_fluxes<true>(W_half_);
  account_outflow(dt);
  advance_stage(W_half_, dt, 0.5 * dt, dt, W, true);
  fill_ghosts(W);
}

namespace {

/// The step limits of one species in one cell, RBO24 eq. 17-19 with the
/// explicit-source limit (see dust_dynamics.hpp): their minimum and its kind.
struct CellStepLimit {
  using Kind = DustDynamics::StepLimit::Kind;
  View4 W;
  RealView1 dR, Rc, tan_te, sc;
  RealView2 nu, rho_g;
  RealView3 g, stopping_time;
  Real ca, cd, floor, floor_ratio, trace_ratio;
  bool drag, diffuse, radial, gravity, curvature;

  KOKKOS_INLINE_FUNCTION static void keep(Real t, int k, Real& m, int& kind) {
    if (t < m) {
      m = t;
      kind = k;
    }
  }
  KOKKOS_INLINE_FUNCTION Real operator()(int i, int j, int s, int& kind) const {
    Real m = Kokkos::reduction_identity<Real>::min();
    kind = Kind::kNone;
    const Real dZ = Rc(i) * (tan_te(j + 1) - tan_te(j));
    if (diffuse) {
      const Real D = nu(i, j) / sc(s);
      const bool along_R = radial && dR(i) * dR(i) < dZ * dZ;
      const Real dx2 = along_R ? dR(i) * dR(i) : dZ * dZ;
      if (D > 0) keep(cd * dx2 / D, along_R ? Kind::kDiffusionR : Kind::kDiffusionZ, m, kind);
    }
    // Advection and sources only where there is dust (cells near the floor move with the
    // gas; trace dust is held below its velocity ceiling instead).
    if (skips_step_limit(W(i, j, s, kRho), dust_floor(floor, floor_ratio, rho_g(i, j)), trace_ratio, rho_g(i, j)))
      return m;
    const Real vR = math::fabs(W(i, j, s, kVR)), vZ = math::fabs(W(i, j, s, kVZ));
    if (radial && vR > 0) keep(ca * dR(i) / vR, Kind::kAdvectionR, m, kind);
    if (vZ > 0) keep(ca * dZ / vZ, Kind::kAdvectionZ, m, kind);
    if (gravity) {
      // Explicit sources (eq. 6; not in eq. 18, it matters when the dust starts at
      // rest or decoupled): a step moves the dust by about a dt min(dt, t_s), the
      // implicit drag capping its velocity at the terminal a t_s; this stays below
      // C_adv of a cell.
      Real aR = g(i, j, 0), aZ = g(i, j, 1);
      if (curvature) aR += math::square(W(i, j, s, kVphi)) / Rc(i);
      aR = math::fabs(aR);
      aZ = math::fabs(aZ);
      const Real ts = drag ? stopping_time(i, j, s) : Real(1e300);
      if (radial && aR > 0) keep(source_step_limit(ca, dR(i), aR, ts), Kind::kSourceR, m, kind);
      if (aZ > 0) keep(source_step_limit(ca, dZ, aZ, ts), Kind::kSourceZ, m, kind);
    }
    return m;
  }
};

CellStepLimit cell_step_limit(const mesh::Grid& grid, const DustSettings& st, const View4& W, const GasFields& gas,
                              const RealView1& schmidt, const RealView3& gravity, const RealView3& stopping_time) {
  return {W,
          grid.dR,
          grid.Rc,
          grid.tan_te,
          schmidt,
          gas.nu,
          gas.rho,
          gravity,
          stopping_time,
          st.cfl_advection,
          st.cfl_diffusion,
          st.floor,
          st.floor_ratio,
          st.trace_ratio,
          st.drag,
          st.diffusion,
          st.radial_fluxes,
          st.gravity,
          st.gravity && grid.geometry == mesh::Geometry::Cylindrical};
}

}  // namespace

double DustDynamics::max_dt() const {
  const int ng = grid_.ng, nr = grid_.nr, nt = grid_.nt, ns = ns_;
  const CellStepLimit limit = cell_step_limit(grid_, settings_, W, gas_, schmidt_, gravity_, stopping_time_);
  Real dt = std::numeric_limits<Real>::max();
  Kokkos::parallel_reduce(
      "disc::dust_max_dt", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>({ng, ng, 0}, {ng + nr, ng + nt, ns}),
      KOKKOS_LAMBDA(int i, int j, int s, Real& m) {
        int kind;
        m = math::min(m, limit(i, j, s, kind));
      },
      Kokkos::Min<Real>(dt));
  return grid_.comm().min(dt);
}

const char* DustDynamics::StepLimit::describe(int kind) {
  switch (kind) {
    case kDiffusionR:
      return "turbulent diffusion along R (dust.cfl_diffusion)";
    case kDiffusionZ:
      return "turbulent diffusion along theta (dust.cfl_diffusion)";
    case kAdvectionR:
      return "advection along R (dust.cfl_advection)";
    case kAdvectionZ:
      return "advection along theta (dust.cfl_advection)";
    case kSourceR:
      return "gravity and curvature along R (dust.cfl_advection)";
    case kSourceZ:
      return "gravity along Z (dust.cfl_advection)";
    default:
      return "nothing (no dust above 10 x its floor or its trace ratio, no diffusion)";
  }
}

DustDynamics::StepLimit DustDynamics::step_limit() const {
  const int ng = grid_.ng, nr = grid_.nr, nt = grid_.nt, ns = ns_;
  const CellStepLimit limit = cell_step_limit(grid_, settings_, W, gas_, schmidt_, gravity_, stopping_time_);
  using Reducer = Kokkos::MinLoc<Real, long long>;
  Reducer::value_type best;
  const long long kinds = StepLimit::kKinds + 1;  // kNone is stored as 0
  Kokkos::parallel_reduce(
      "disc::dust_step_limit", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>({ng, ng, 0}, {ng + nr, ng + nt, ns}),
      KOKKOS_LAMBDA(int i, int j, int s, Reducer::value_type& m) {
        int kind;
        const Real t = limit(i, j, s, kind);
        if (t < m.val) {
          m.val = t;
          m.loc = ((static_cast<long long>(i - ng) * nt + (j - ng)) * ns + s) * kinds + (kind + 1);
        }
      },
      Reducer(best));
  // The rank holding the global minimum (the lowest of them) reports where it is.
  const auto& comm = grid_.comm();
  StepLimit out;
  out.dt = comm.min(best.val);
  const int owner = comm.min(best.val == out.dt ? comm.rank() : comm.size());
  std::vector<double> where(6, 0.0);
  if (comm.rank() == owner && best.val < Kokkos::reduction_identity<Real>::min()) {
    const long long loc = best.loc / kinds;
    const int i = static_cast<int>(loc / ns / nt), j = static_cast<int>(loc / ns % nt);
    where = {static_cast<double>(best.loc % kinds),
             static_cast<double>(loc % ns),
             static_cast<double>(j),
             static_cast<double>(i + grid_.i_offset),
             grid_.Rc_h(i + ng),
             grid_.tc_h(j + ng)};
  }
  where = comm.sum(where);
  out.kind = static_cast<int>(where[0]) - 1;
  out.species = static_cast<int>(where[1]);
  out.j = static_cast<int>(where[2]);
  out.i = static_cast<int>(where[3]);
  out.R = where[4];
  out.theta = where[5];
  return out;
}

void DustDynamics::account_outflow(double dt) {
  const int ib = grid_.i_begin(), ie = grid_.i_end(), jb = grid_.j_begin(), je = grid_.j_end(), ns = ns_;
  const bool inner = grid_.i_offset == 0, outer = grid_.i_offset + grid_.nr == grid_.nr_global;
  auto B = budget, FR = flux_R_, FZ = flux_Z_;
  const Real h = dt;
  par_for(
      "disc::dust_outflow_R", jb, je, 0, ns, KOKKOS_LAMBDA(int j, int s) {
        if (inner) B(ib, j, s, 1) -= h * FR(ib, j, s, kRho);
        if (outer) B(ie - 1, j, s, 1) += h * FR(ie, j, s, kRho);
      });
  par_for(
      "disc::dust_outflow_Z", ib, ie, 0, ns, KOKKOS_LAMBDA(int i, int s) {
        B(i, jb, s, 1) -= h * FZ(i, jb, s, kRho);
        B(i, je - 1, s, 1) += h * FZ(i, je, s, kRho);
      });
}

DustDynamics::MassBudget DustDynamics::mass_budget() const {
  auto B = budget;
  const int ns = ns_;
  Real added = 0, out = 0;
  Kokkos::parallel_reduce(
      "disc::dust_mass_budget",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({grid_.i_begin(), grid_.j_begin()},
                                                        {grid_.i_end(), grid_.j_end()}),
      KOKKOS_LAMBDA(int i, int j, Real& a, Real& o) {
        for (int s = 0; s < ns; ++s) {
          a += B(i, j, s, 0);
          o += B(i, j, s, 1);
        }
      },
      added, out);
  return {grid_.comm().sum(added), grid_.comm().sum(out)};
}

double DustDynamics::mass(int s) const {
  auto Q_ = Q;
  auto V = grid_.V;
  Real m = 0;
  par_reduce(
      "disc::dust_mass", grid_.i_begin(), grid_.i_end(), grid_.j_begin(), grid_.j_end(),
      KOKKOS_LAMBDA(int i, int j, Real& acc) { acc += Q_(i, j, s, kRho) * V(i, j); }, m);
  return grid_.comm().sum(m);
}

namespace {

/// Sum over the active cells of Q(i, j, s, kRho) V(i, j) for every species s
/// at once: a Kokkos reduction over an array of runtime length (value_count).
struct SpeciesMassSum {
  using value_type = Real[];
  View<Real****> Q;
  RealView2 V;
  int ib, jb, nt;
  unsigned value_count;

  KOKKOS_INLINE_FUNCTION void operator()(int c, Real acc[]) const {
    const int i = ib + c / nt, j = jb + c % nt;
    for (unsigned s = 0; s < value_count; ++s) acc[s] += Q(i, j, s, kRho) * V(i, j);
  }
  KOKKOS_INLINE_FUNCTION void init(Real acc[]) const {
    for (unsigned s = 0; s < value_count; ++s) acc[s] = 0;
  }
  KOKKOS_INLINE_FUNCTION void join(Real dst[], const Real src[]) const {
    for (unsigned s = 0; s < value_count; ++s) dst[s] += src[s];
  }
#if KOKKOS_VERSION < 40000  // Kokkos 3 joins volatile partial results as well
  KOKKOS_INLINE_FUNCTION void join(volatile Real dst[], const volatile Real src[]) const {
    for (unsigned s = 0; s < value_count; ++s) dst[s] += src[s];
  }
#endif
};

}  // namespace

std::vector<double> DustDynamics::species_masses() const {
  const SpeciesMassSum sum{Q, grid_.V, grid_.i_begin(), grid_.j_begin(), grid_.nt, static_cast<unsigned>(ns_)};
  std::vector<Real> local(static_cast<size_t>(ns_), 0.0);
  const Kokkos::View<Real*, Kokkos::HostSpace, Kokkos::MemoryUnmanaged> result(local.data(), local.size());
  Kokkos::parallel_reduce("disc::dust_species_masses", Kokkos::RangePolicy<ExecSpace>(0, grid_.nr * grid_.nt), sum,
                          result);
  return grid_.comm().sum(std::vector<double>(local.begin(), local.end()));
}

}  // namespace mote::disc
