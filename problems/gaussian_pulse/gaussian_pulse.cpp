// gaussian_pulse: advection and diffusion of a Gaussian pulse on a periodic
// 2D Cartesian grid, the foundation's end-to-end problem (deck -> run ->
// HDF5/XDMF -> python check) with an analytic solution.
//
//   d rho/dt + div(rho v) = D lap(rho),   v, D constant,
//   rho(x, t) = rho_bg + (A / t) exp(-|x - x_p - v (t - t0)|^2 / (4 D t))
// (the pulse of RBO24 sec. 3.3 / VALIDATION C1, on a periodic Cartesian box
// instead of the (R, theta) mesh; periodic images are summed).
//
// Method: finite volumes, slab-decomposed in y across MPI ranks with two ghost
// rows; piecewise-linear reconstruction (limiter: none = Fromm, van Leer or
// MC) with upwind advective fluxes, central diffusive fluxes, SSP-RK2 in time.
#include <algorithm>
#include <climits>
#include <cmath>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/kokkos_types.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/io/problem_main.hpp"

namespace {

using mote::Real;
using mote::RealView2;
namespace math = mote::math;

constexpr int kGhost = 2;
enum class Limiter { None, VanLeer, MC };

KOKKOS_INLINE_FUNCTION Real limited_slope(Real dl, Real dr, Limiter limiter) {
  switch (limiter) {
    case Limiter::None:
      return 0.5 * (dl + dr);
    case Limiter::VanLeer:
      return dl * dr > 0 ? 2.0 * dl * dr / (dl + dr) : 0.0;
    case Limiter::MC:
      if (dl * dr <= 0) return 0.0;
      return (dl > 0 ? 1.0 : -1.0) *
             math::min(math::min(2.0 * math::fabs(dl), 2.0 * math::fabs(dr)), 0.5 * math::fabs(dl + dr));
  }
  return 0.0;
}

/// Upwind flux v * q_face of a linearly reconstructed quantity through the face
/// between cells with values (qmm, qm | qp, qpp); plus the diffusive flux.
KOKKOS_INLINE_FUNCTION Real face_flux(Real qmm, Real qm, Real qp, Real qpp, Real v, Real D, Real h, Limiter lim) {
  const Real left = qm + 0.5 * limited_slope(qm - qmm, qp - qm, lim);
  const Real right = qp - 0.5 * limited_slope(qp - qm, qpp - qp, lim);
  return (v > 0 ? v * left : v * right) - D * (qp - qm) / h;
}

struct Params {
  int nx = 0, ny = 0;
  Real x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  Real vx = 0, vy = 0, D = 0;
  Real amplitude = 1, t0 = 1, x0 = 0.5, y0 = 0.5, background = 0;
  Real cfl = 0.4;
  Limiter limiter = Limiter::None;
  KOKKOS_INLINE_FUNCTION Real dx() const { return (x_max - x_min) / nx; }
  KOKKOS_INLINE_FUNCTION Real dy() const { return (y_max - y_min) / ny; }
};

/// Analytic solution at cell centre (x, y) and run time tau (pulse time t0 + tau).
KOKKOS_INLINE_FUNCTION Real analytic(const Params& p, Real x, Real y, Real tau) {
  const Real t = p.t0 + tau, Lx = p.x_max - p.x_min, Ly = p.y_max - p.y_min;
  const Real xc = p.x0 + p.vx * tau, yc = p.y0 + p.vy * tau;
  // Nearest periodic image of the centre, then the 3x3 neighbouring images.
  const Real ddx = x - xc - Lx * math::floor((x - xc) / Lx + 0.5);
  const Real ddy = y - yc - Ly * math::floor((y - yc) / Ly + 0.5);
  Real sum = 0;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      sum += math::exp(-(math::square(ddx + a * Lx) + math::square(ddy + b * Ly)) / (4.0 * p.D * t));
  return p.background + p.amplitude / t * sum;
}

class GaussianPulse final : public mote::io::Simulation {
 public:
  GaussianPulse(const Params& p, const mote::core::Comm& comm) : p_(p), comm_(comm) {
    const int base = p.ny / comm.size(), extra = p.ny % comm.size();
    rows_ = base + (comm.rank() < extra ? 1 : 0);
    row_begin_ = comm.rank() * base + std::min(comm.rank(), extra);
    if (base < kGhost)  // the fewest rows of any rank: every rank refuses, none waits for the others
      throw mote::core::DeckError(mote::logging::cat("grid.ny = ", p.ny, " gives fewer than ", kGhost,
                                                     " rows on each of ", comm.size(),
                                                     " ranks; increase grid.ny or use fewer ranks"));
    rho_ = RealView2("density", rows_ + 2 * kGhost, p.nx + 2 * kGhost);
    stage_ = RealView2("density_stage", rows_ + 2 * kGhost, p.nx + 2 * kGhost);
    rhs_ = RealView2("rhs", rows_, p.nx);
    halo_send_ = mote::RealView1("halo_send", 2 * kGhost * (p.nx + 2 * kGhost));
    halo_recv_ = mote::RealView1("halo_recv", 2 * kGhost * (p.nx + 2 * kGhost));
    halo_send_h_ = Kokkos::create_mirror_view(halo_send_);
    halo_recv_h_ = Kokkos::create_mirror_view(halo_recv_);
    set_initial_density();
  }

  // Kernels live in public member functions: nvcc does not allow extended
  // lambdas in constructors or in private member functions.

  /// The analytic solution at t = 0 on the interior.
  void set_initial_density() {
    const Params q = p_;
    const int j0 = row_begin_;
    auto rho = rho_;
    mote::par_for(
        "gaussian_pulse::init", 0, rows_, 0, q.nx, KOKKOS_LAMBDA(int j, int i) {
          const Real x = q.x_min + (i + 0.5) * q.dx(), y = q.y_min + (j0 + j + 0.5) * q.dy();
          rho(j + kGhost, i + kGhost) = analytic(q, x, y, 0.0);
        });
  }

  double max_dt() override {
    const Real rate = math::fabs(p_.vx) / p_.dx() + math::fabs(p_.vy) / p_.dy() +
                      2.0 * p_.D * (1.0 / (p_.dx() * p_.dx()) + 1.0 / (p_.dy() * p_.dy()));
    return rate > 0 ? p_.cfl / rate : 1e30;
  }
  std::string dt_limit() const override { return "advection-diffusion CFL (scheme.cfl)"; }

  void advance(double /*time*/, double dt) override {
    // SSP-RK2: u1 = u + dt L(u);  u_new = (u + u1 + dt L(u1)) / 2
    compute_rhs(rho_);
    combine(stage_, rho_, rho_, 0.0, dt);
    compute_rhs(stage_);
    combine(rho_, rho_, stage_, 0.5, 0.5 * dt);
    tau_ += dt;
  }

  void write_snapshot(mote::io::SnapshotWriter& out) const override {
    std::vector<double> xn(p_.nx + 1), yn(p_.ny + 1);
    for (int i = 0; i <= p_.nx; ++i) xn[i] = p_.x_min + i * p_.dx();
    for (int j = 0; j <= p_.ny; ++j) yn[j] = p_.y_min + j * p_.dy();
    out.rectilinear_2d(xn, yn, row_begin_, rows_);
    const auto rho = interior_to_host(rho_);
    std::vector<double> ref(rho.size());
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < p_.nx; ++i)
        ref[j * p_.nx + i] =
            analytic(p_, p_.x_min + (i + 0.5) * p_.dx(), p_.y_min + (row_begin_ + j + 0.5) * p_.dy(), tau_);
    out.cell_field("density", rho.data(), {"code density", 1.0});
    out.cell_field("analytic", ref.data(), {"code density", 1.0});
  }

  void save_state(mote::io::H5File& file) const override {
    const auto rho = interior_to_host(rho_);
    file.write("/state/density", block(), rho.data());
    file.write_attribute("/state", "tau", tau_);
  }

  void load_state(const mote::io::H5File& file) override {
    std::vector<double> rho(static_cast<size_t>(rows_) * p_.nx);
    file.read("/state/density", block(), rho.data());
    tau_ = file.read_attribute_real("/state", "tau");
    auto host = Kokkos::create_mirror_view(rho_);
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < p_.nx; ++i) host(j + kGhost, i + kGhost) = rho[j * p_.nx + i];
    Kokkos::deep_copy(rho_, host);
  }

  std::vector<mote::io::Diagnostic> diagnostics() const override {
    auto rho = rho_;
    Real mass = 0, peak = 0;
    mote::par_reduce(
        "gaussian_pulse::mass", kGhost, rows_ + kGhost, kGhost, p_.nx + kGhost,
        KOKKOS_LAMBDA(int j, int i, Real& m) { m += rho(j, i); }, mass);
    mote::par_reduce(
        "gaussian_pulse::peak", kGhost, rows_ + kGhost, kGhost, p_.nx + kGhost,
        KOKKOS_LAMBDA(int j, int i, Real& m) { m = math::max(m, rho(j, i)); }, Kokkos::Max<Real>(peak));
    return {{"mass", comm_.sum(mass * p_.dx() * p_.dy())}, {"max_density", comm_.max(peak)}};
  }

  std::optional<mote::io::NonFinite> find_non_finite() const override {
    auto rho = rho_;
    const int nx = p_.nx;
    int first = INT_MAX;
    mote::par_reduce(
        "gaussian_pulse::find_non_finite", kGhost, rows_ + kGhost, kGhost, nx + kGhost,
        KOKKOS_LAMBDA(int j, int i, int& f) {
          if (!math::isfinite(rho(j, i))) f = math::min(f, (j - kGhost) * nx + (i - kGhost));
        },
        Kokkos::Min<int>(first));
    if (first == INT_MAX) return std::nullopt;
    const int j = first / nx + row_begin_, i = first % nx;
    return mote::io::NonFinite{
        "density", mote::logging::format("cell (i, j) = (%d, %d), x = %g, y = %g", i, j, p_.x_min + (i + 0.5) * p_.dx(),
                                         p_.y_min + (j + 0.5) * p_.dy())};
  }

  void finish(double) override {
    const auto rho = interior_to_host(rho_);
    double sq = 0, peak = 0;
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < p_.nx; ++i) {
        const double ref =
            analytic(p_, p_.x_min + (i + 0.5) * p_.dx(), p_.y_min + (row_begin_ + j + 0.5) * p_.dy(), tau_);
        sq += (rho[j * p_.nx + i] - ref) * (rho[j * p_.nx + i] - ref);
        peak = std::max(peak, std::fabs(ref));
      }
    const double l2 = std::sqrt(comm_.sum(sq) / (double(p_.nx) * p_.ny)) / comm_.max(peak);
    mote::logging::info(
        mote::logging::format("L2_rel error against the analytic solution: %.6e (nx = %d, ny = %d)", l2, p_.nx, p_.ny));
  }

  /// Fills ghost columns (periodic in x, local) and ghost rows (periodic in y, via neighbours).
  void fill_ghosts(const RealView2& u) {
    const int nx = p_.nx, rows = rows_, width = nx + 2 * kGhost;
    mote::par_for(
        "gaussian_pulse::ghost_x", kGhost, rows + kGhost, 0, kGhost, KOKKOS_LAMBDA(int j, int g) {
          u(j, g) = u(j, nx + g);
          u(j, nx + kGhost + g) = u(j, kGhost + g);
        });
    auto send = halo_send_;
    // send[0..): my first kGhost interior rows (to the rank below), then my last kGhost rows (to the rank above)
    mote::par_for(
        "gaussian_pulse::pack_halo", 0, kGhost, 0, width, KOKKOS_LAMBDA(int g, int i) {
          send(g * width + i) = u(kGhost + g, i);
          send((kGhost + g) * width + i) = u(rows + g, i);
        });
    auto recv = halo_recv_;
    const int half = kGhost * width;
    if (comm_.size() == 1) {  // periodic onto itself: stays on the device
      mote::par_for(
          "gaussian_pulse::wrap_halo", 0, half, KOKKOS_LAMBDA(int k) {
            recv(k) = send(half + k);
            recv(half + k) = send(k);
          });
    } else {  // the buffers travel through host memory (no GPU-aware MPI needed)
      Kokkos::deep_copy(halo_send_h_, send);
      const int below = (comm_.rank() - 1 + comm_.size()) % comm_.size(), above = (comm_.rank() + 1) % comm_.size();
      // My low rows go down and I receive the upper rank's low rows; my high rows go up.
      comm_.sendrecv(halo_send_h_.data(), half, below, halo_recv_h_.data() + half, half, above, 11);
      comm_.sendrecv(halo_send_h_.data() + half, half, above, halo_recv_h_.data(), half, below, 12);
      Kokkos::deep_copy(recv, halo_recv_h_);
    }
    mote::par_for(
        "gaussian_pulse::unpack_halo", 0, kGhost, 0, width, KOKKOS_LAMBDA(int g, int i) {
          u(g, i) = recv(g * width + i);
          u(rows + kGhost + g, i) = recv((kGhost + g) * width + i);
        });
  }

  void compute_rhs(const RealView2& u) {
    fill_ghosts(u);
    const Params q = p_;
    auto rhs = rhs_;
    const Real dx = q.dx(), dy = q.dy();
    mote::par_for(
        "gaussian_pulse::rhs", 0, rows_, 0, q.nx, KOKKOS_LAMBDA(int jj, int ii) {
          const int j = jj + kGhost, i = ii + kGhost;
          const Real fxm = face_flux(u(j, i - 2), u(j, i - 1), u(j, i), u(j, i + 1), q.vx, q.D, dx, q.limiter);
          const Real fxp = face_flux(u(j, i - 1), u(j, i), u(j, i + 1), u(j, i + 2), q.vx, q.D, dx, q.limiter);
          const Real fym = face_flux(u(j - 2, i), u(j - 1, i), u(j, i), u(j + 1, i), q.vy, q.D, dy, q.limiter);
          const Real fyp = face_flux(u(j - 1, i), u(j, i), u(j + 1, i), u(j + 2, i), q.vy, q.D, dy, q.limiter);
          rhs(jj, ii) = -(fxp - fxm) / dx - (fyp - fym) / dy;
        });
  }

  /// out = (1 - w) a + w b + c dt rhs, on the interior.
  void combine(const RealView2& out, const RealView2& a, const RealView2& b, Real w, Real c_dt) {
    auto rhs = rhs_;
    mote::par_for(
        "gaussian_pulse::update", 0, rows_, 0, p_.nx, KOKKOS_LAMBDA(int jj, int ii) {
          const int j = jj + kGhost, i = ii + kGhost;
          out(j, i) = (1.0 - w) * a(j, i) + w * b(j, i) + c_dt * rhs(jj, ii);
        });
  }

 private:
  mote::io::Block block() const {
    mote::io::Block b;
    b.global_dims = {hsize_t(p_.ny), hsize_t(p_.nx)};
    b.offset = {hsize_t(row_begin_), 0};
    b.count = {hsize_t(rows_), hsize_t(p_.nx)};
    return b;
  }

  std::vector<double> interior_to_host(const RealView2& v) const {
    auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
    std::vector<double> out(static_cast<size_t>(rows_) * p_.nx);
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < p_.nx; ++i) out[j * p_.nx + i] = host(j + kGhost, i + kGhost);
    return out;
  }

  Params p_;
  mote::core::Comm comm_;
  int rows_ = 0, row_begin_ = 0;
  double tau_ = 0.0;
  RealView2 rho_, stage_, rhs_;
  mote::RealView1 halo_send_, halo_recv_;
  mote::HostView<Real*> halo_send_h_, halo_recv_h_;
};

/// The domain must have a positive extent in x and y.
void check_extent(const mote::core::Deck& d, mote::core::DeckCheck& check) {
  if (!(d.real("grid.x_max") > d.real("grid.x_min")))
    check.fail("grid.x_max", "must exceed " + check.quote("grid.x_min"));
  if (!(d.real("grid.y_max") > d.real("grid.y_min")))
    check.fail("grid.y_max", "must exceed " + check.quote("grid.y_min"));
}

void declare(mote::core::DeckSchema& s) {
  s.table("grid", "Periodic 2D Cartesian grid.");
  s.integer("grid.nx").sets_state_size().default_value(128LL).min(4).doc("Cells in x.");
  s.integer("grid.ny").sets_state_size().default_value(128LL).min(4).doc("Cells in y (split across MPI ranks).");
  s.real("grid.x_min").default_value(0.0).unit("code length").doc("Lower x edge.");
  s.real("grid.x_max").default_value(1.0).unit("code length").doc("Upper x edge (> x_min).");
  s.real("grid.y_min").default_value(0.0).unit("code length").doc("Lower y edge.");
  s.real("grid.y_max").default_value(1.0).unit("code length").doc("Upper y edge (> y_min).");
  s.table("transport", "Constant advection velocity and diffusivity.");
  s.real("transport.vx").default_value(1.0).unit("code velocity").doc("Advection velocity in x.");
  s.real("transport.vy").default_value(0.5).unit("code velocity").doc("Advection velocity in y.");
  s.real("transport.diffusivity").greater_than(0.0).unit("code length^2 / code time").doc("Diffusion coefficient D.");
  s.table("pulse", "Initial Gaussian: rho = background + (A / t0) exp(-r^2 / (4 D t0)).");
  s.real("pulse.amplitude").default_value(1.0).greater_than(0.0).unit("code density x code time").doc("A.");
  s.real("pulse.t0")
      .greater_than(0.0)
      .unit("code time")
      .doc("Age of the pulse at the start of the run (sets its width).");
  s.real("pulse.x0").default_value(0.5).unit("code length").doc("Initial centre x.");
  s.real("pulse.y0").default_value(0.5).unit("code length").doc("Initial centre y.");
  s.real("pulse.background").default_value(0.0).min(0.0).unit("code density").doc("Uniform background density.");
  s.table("scheme", "Numerical method.");
  s.real("scheme.cfl")
      .default_value(0.4)
      .greater_than(0.0)
      .max(1.0)
      .doc("Courant number of the combined advection-diffusion limit.");
  s.string("scheme.limiter")
      .default_value(std::string("none"))
      .one_of({"none", "vanleer", "mc"})
      .doc("Slope limiter (none = Fromm, unlimited second order).");
  s.rule(check_extent);
}

std::unique_ptr<mote::io::Simulation> create(const mote::io::ProblemContext& ctx) {
  const auto& d = ctx.deck;
  Params p;
  p.nx = static_cast<int>(d.integer("grid.nx"));
  p.ny = static_cast<int>(d.integer("grid.ny"));
  p.x_min = d.real("grid.x_min");
  p.x_max = d.real("grid.x_max");
  p.y_min = d.real("grid.y_min");
  p.y_max = d.real("grid.y_max");
  p.vx = d.real("transport.vx");
  p.vy = d.real("transport.vy");
  p.D = d.real("transport.diffusivity");
  p.amplitude = d.real("pulse.amplitude");
  p.t0 = d.real("pulse.t0");
  p.x0 = d.real("pulse.x0");
  p.y0 = d.real("pulse.y0");
  p.background = d.real("pulse.background");
  p.cfl = d.real("scheme.cfl");
  const auto& lim = d.string("scheme.limiter");
  p.limiter = lim == "vanleer" ? Limiter::VanLeer : lim == "mc" ? Limiter::MC : Limiter::None;
  return std::make_unique<GaussianPulse>(p, ctx.comm);
}

}  // namespace

int main(int argc, char** argv) {
  return mote::io::run_problem(
      argc, argv, {"gaussian_pulse", "advection-diffusion of a Gaussian pulse on a periodic 2D grid", declare, create});
}
