// disc_pulse: RBO24 sec. 3.6 / VALIDATION C1. A Gaussian pulse of one dust
// species advected with constant velocity and diffused with constant D on the
// non-orthogonal (R, theta) grid with planar areas and volumes:
//   rho(x, y, t) = (A / t) exp(-((x - x_p(t))^2 + (y - y_p(t))^2) / (4 D t)),  (eq. 38)
//   x_p = x0 + v_x (t - t0), y_p = y0 + v_y (t - t0),  x = R, y = Z.
// Run time tau = t - t0. Gas: rho_g = 1, nu = D, Sc = 1 (eq. 15 reduces to
// -D grad rho); no drag, no gravity. The L2 norm of RBO24 (sqrt(sum (rho -
// rho_an)^2 / N^2)) is printed at the end.
#include <cmath>
#include <limits>

#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/disc/dust_dynamics.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/mesh/grid_output.hpp"

namespace {

using namespace mote;

struct Pulse {
  double A = 1, D = 1, x0 = 30, y0 = 0, t0 = 0.1, vx = 5, vy = 2;
  KOKKOS_INLINE_FUNCTION Real operator()(Real x, Real y, Real tau) const {
    const Real t = t0 + tau, xp = x0 + vx * tau, yp = y0 + vy * tau;
    return A / t * math::exp(-(math::square(x - xp) + math::square(y - yp)) / (4.0 * D * t));
  }
};

class DiscPulse final : public io::Simulation {
 public:
  DiscPulse(const mesh::GridSpec& spec, disc::DustSettings dust, const Pulse& pulse, const core::Comm& comm)
      : grid_(spec, comm), dust_(grid_, std::move(dust)), pulse_(pulse) {
    disc::GasFields gas(grid_.nr_total(), grid_.nt_total());
    Kokkos::deep_copy(gas.rho, 1.0);
    Kokkos::deep_copy(gas.cs2, 1.0);
    Kokkos::deep_copy(gas.nu, pulse.D);
    dust_.set_gas(gas);
    set_initial_pulse();
  }

  /// The pulse of eq. 38 at t = 0 in every cell (above the floor). Not in the
  /// constructor: nvcc does not allow extended lambdas there.
  void set_initial_pulse() {
    auto W = dust_.W;
    auto Rc = grid_.Rc, tan_tc = grid_.tan_tc;
    const Pulse p = pulse_;
    const Real floor = dust_.settings().floor;
    par_for(
        "disc_pulse::init", 0, grid_.nr_total(), 0, grid_.nt_total(), KOKKOS_LAMBDA(int i, int j) {
          W(i, j, 0, disc::kRho) = math::max(p(Rc(i), Rc(i) * tan_tc(j), 0.0), floor);
          W(i, j, 0, disc::kVR) = p.vx;
          W(i, j, 0, disc::kVphi) = 0.0;
          W(i, j, 0, disc::kVZ) = p.vy;
        });
    dust_.initialise_from_primitives();
  }

  double max_dt() override { return dust_.max_dt(); }
  void advance(double, double dt) override {
    dust_.step(dt);
    tau_ += dt;
  }

  void write_snapshot(io::SnapshotWriter& out) const override {
    mesh::describe_grid(out, grid_);
    const auto rho = mesh::active_cells(grid_, dust_.W, 0, disc::kRho);
    out.cell_field("dust_density", rho.data(), {"code density", 1.0});
    const auto ref = analytic();
    out.cell_field("analytic", ref.data(), {"code density", 1.0});
  }

  void save_state(io::H5File& f) const override {
    mesh::write_state(f, "/state/dust_Q", grid_, dust_.Q);
    mesh::write_state(f, "/state/dust_W", grid_, dust_.W);
    f.write_attribute("/state", "tau", tau_);
  }
  void load_state(const io::H5File& f) override {
    mesh::read_state(f, "/state/dust_Q", grid_, dust_.Q);
    mesh::read_state(f, "/state/dust_W", grid_, dust_.W);
    tau_ = f.read_attribute_real("/state", "tau");
  }

  std::vector<io::Diagnostic> diagnostics() const override { return {{"dust_mass", dust_.mass(0)}}; }

  std::optional<io::NonFinite> find_non_finite() const override {
    auto Q = dust_.Q;
    const int ng = grid_.ng, nt = grid_.nt;
    int first = std::numeric_limits<int>::max();
    par_reduce(
        "disc_pulse::non_finite", ng, ng + grid_.nr, ng, ng + nt,
        KOKKOS_LAMBDA(int i, int j, int& f) {
          for (int k = 0; k < disc::kDustVars; ++k)
            if (!math::isfinite(Q(i, j, 0, k))) f = math::min(f, (i - ng) * nt + (j - ng));
        },
        Kokkos::Min<int>(first));
    if (first == std::numeric_limits<int>::max()) return std::nullopt;
    return io::NonFinite{"dust Q", logging::format("cell (i, j) = (%d, %d)", first / nt + grid_.i_offset, first % nt)};
  }

  void finish(double) override {
    logging::info(logging::format("L2 error (RBO24 sec. 3.6 norm): %.6e on %d x %d cells", l2_error(), grid_.nr_global,
                                  grid_.nt));
  }

 private:
  std::vector<double> analytic() const {
    std::vector<double> ref(static_cast<size_t>(grid_.nr) * grid_.nt);
    for (int i = 0; i < grid_.nr; ++i)
      for (int j = 0; j < grid_.nt; ++j) {
        const double R = grid_.Rc_h(grid_.ng + i), Z = R * std::tan(grid_.tc_h(grid_.ng + j));
        ref[i * grid_.nt + j] = pulse_(R, Z, tau_);
      }
    return ref;
  }

  double l2_error() const {
    const auto rho = mesh::active_cells(grid_, dust_.W, 0, disc::kRho);
    const auto ref = analytic();
    double sq = 0;
    for (size_t n = 0; n < rho.size(); ++n) sq += (rho[n] - ref[n]) * (rho[n] - ref[n]);
    return std::sqrt(grid_.comm().sum(sq) / (double(grid_.nr_global) * grid_.nt));
  }

  mesh::Grid grid_;
  disc::DustDynamics dust_;
  Pulse pulse_;
  double tau_ = 0.0;
};

/// The analytic pulse (eq. 38) is one species advected and diffused with D in both
/// directions on a planar grid, with no drag and no gravity.
void check_pure_transport(const core::Deck& d, core::DeckCheck& check) {
  if (disc::grain_sizes_cm(d).size() != 1) check.fail("dust.sizes", "disc_pulse evolves one dust species");
  for (const char* key : {"dust.drag", "dust.gravity"})
    if (d.boolean(key)) check.fail(key, "disc_pulse needs false");
  for (const char* key : {"dust.diffusion", "dust.radial_fluxes"})
    if (!d.boolean(key)) check.fail(key, "disc_pulse needs true (eq. 38 advects and diffuses in R and Z)");
  if (d.string("grid.geometry") != "planar")
    check.fail("grid.geometry", "disc_pulse needs \"planar\" (eq. 38 is the planar solution)");
  for (double sc : d.real_array("dust.schmidt"))
    if (sc != 1.0) check.fail("dust.schmidt", "disc_pulse needs 1 (D = pulse.diffusivity)");
}

void declare(core::DeckSchema& s) {
  mesh::GridSpec::declare(s);
  mesh::Boundaries::declare(s);
  disc::DustSettings::declare(s);
  s.table("pulse", "Gaussian pulse of RBO24 eq. 38.");
  s.real("pulse.amplitude").default_value(1.0).greater_than(0.0).doc("A.");
  s.real("pulse.diffusivity")
      .default_value(1.0)
      .greater_than(0.0)
      .unit("code length^2 / code time")
      .doc("D (= nu with rho_g = 1, Sc = 1).");
  s.real("pulse.x0").default_value(30.0).unit("code length").doc("Initial centre R.");
  s.real("pulse.y0").default_value(0.0).unit("code length").doc("Initial centre Z.");
  s.real("pulse.t0").default_value(0.1).greater_than(0.0).unit("code time").doc("Pulse time at the start of the run.");
  s.real("pulse.vx").default_value(5.0).unit("code velocity").doc("Velocity in R.");
  s.real("pulse.vy").default_value(2.0).unit("code velocity").doc("Velocity in Z.");
  s.rule(check_pure_transport);
}

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  const auto spec = mesh::GridSpec::from_deck(d);
  auto dust = disc::DustSettings::from_deck(d, ctx.units, disc::StellarGravity{0.0, false});
  Pulse p;
  p.A = d.real("pulse.amplitude");
  p.D = d.real("pulse.diffusivity");
  p.x0 = d.real("pulse.x0");
  p.y0 = d.real("pulse.y0");
  p.t0 = d.real("pulse.t0");
  p.vx = d.real("pulse.vx");
  p.vy = d.real("pulse.vy");
  return std::make_unique<DiscPulse>(spec, std::move(dust), p, ctx.comm);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"disc_pulse", "RBO24 C1: advection-diffusion of a Gaussian pulse on the (R, theta) grid", declare, create});
}
