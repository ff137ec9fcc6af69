// The Bogacki-Shampine 3(2) integrator (VALIDATION E4): observed order 3 with
// fixed steps on a smooth ODE, step rejection and error control with adaptive
// steps, conservation of the sum of components.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mote/coagulation/bs32.hpp"

namespace coag = mote::coagulation;
using mote::Real;

namespace {

/// y0' = r y0 (1 - y0), y1' = -r y0 (1 - y0): logistic growth, y0 + y1 constant.
struct Logistic {
  Real r = 1.0;
  template <class Team, class V>
  KOKKOS_INLINE_FUNCTION void operator()(const Team& team, const V& y, const V& f) const {
    Kokkos::single(Kokkos::PerTeam(team), [&]() {
      const Real g = r * y(0) * (1.0 - y(0));
      f(0) = g;
      f(1) = -g;
    });
    team.team_barrier();
  }
};

double logistic_exact(double y0, double r, double t) { return 1.0 / (1.0 + (1.0 / y0 - 1.0) * std::exp(-r * t)); }

/// Runs bs32_integrate on one team; returns (y0, y1, accepted, rejected, h_next, ok).
std::vector<double> run_bs32(double y0, double r, double span, coag::Bs32Options opt) {
  using Policy = Kokkos::TeamPolicy<mote::ExecSpace>;
  using Scratch = Kokkos::View<Real*, mote::ExecSpace::scratch_memory_space, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;
  mote::RealView1 out("out", 6);
  const Logistic rhs{r};
  const int n = 2;
  const auto policy = Policy(1, Kokkos::AUTO).set_scratch_size(0, Kokkos::PerTeam(7 * Scratch::shmem_size(n)));
  Kokkos::parallel_for(
      "test::bs32", policy, KOKKOS_LAMBDA(const Policy::member_type& team) {
        const auto& s = team.team_scratch(0);
        const Scratch y(s, n);
        const coag::Bs32Work<Scratch> w{Scratch(s, n), Scratch(s, n), Scratch(s, n),
                                        Scratch(s, n), Scratch(s, n), Scratch(s, n)};
        Kokkos::single(Kokkos::PerTeam(team), [&]() {
          y(0) = y0;
          y(1) = 1.0 - y0;
        });
        team.team_barrier();
        const auto res = coag::bs32_integrate(team, n, y, span, opt, w, rhs);
        Kokkos::single(Kokkos::PerTeam(team), [&]() {
          out(0) = y(0);
          out(1) = y(1);
          out(2) = res.accepted;
          out(3) = res.rejected;
          out(4) = res.h_next;
          out(5) = res.ok ? 1.0 : 0.0;
        });
      });
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
  return {h(0), h(1), h(2), h(3), h(4), h(5)};
}

}  // namespace

TEST(CoagulationBs32, ObservedOrderThreeWithFixedSteps) {
  std::vector<double> err;
  const std::vector<int> steps = {10, 20, 40, 80};
  for (int s : steps) {
    coag::Bs32Options o;
    o.h_fixed = 3.0 / s;
    const auto r = run_bs32(0.1, 2.0, 3.0, o);
    EXPECT_EQ(static_cast<int>(r[2]), s);
    err.push_back(std::fabs(r[0] - logistic_exact(0.1, 2.0, 3.0)));
  }
  // Least-squares slope of log(err) against log(h).
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < err.size(); ++i) {
    const double x = std::log(3.0 / steps[i]), y = std::log(err[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double m = static_cast<double>(err.size());
  const double order = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  RecordProperty("observed_order", std::to_string(order));
  std::printf("BS32 fixed-step errors: %.3e %.3e %.3e %.3e, observed order %.3f\n", err[0], err[1], err[2], err[3],
              order);
  EXPECT_GE(order, 2.8);
  EXPECT_LE(order, 3.3);
}

TEST(CoagulationBs32, RejectsTooLargeStepsAndMeetsTolerance) {
  coag::Bs32Options o;
  o.rel_tol = 1e-4;
  o.abs_tol = 1e-10;
  o.h_init = 5.0;  // the whole interval: must be rejected
  const double r = 20.0, span = 1.0, y0 = 1e-3;
  const auto res = run_bs32(y0, r, span, o);
  std::printf("BS32 adaptive: %g accepted, %g rejected, error %.3e\n", res[2], res[3],
              std::fabs(res[0] - logistic_exact(y0, r, span)));
  EXPECT_GT(res[3], 0.0);
  EXPECT_GT(res[2], 5.0);
  EXPECT_LT(std::fabs(res[0] - logistic_exact(y0, r, span)), 50 * o.rel_tol);
  EXPECT_NEAR(res[0] + res[1], 1.0, 1e-14);
  EXPECT_GT(res[4], 0.0);
  // Tighter tolerance, smaller error and more steps.
  o.rel_tol = 1e-7;
  const auto tight = run_bs32(y0, r, span, o);
  EXPECT_GT(tight[2], res[2]);
  EXPECT_LT(std::fabs(tight[0] - logistic_exact(y0, r, span)), std::fabs(res[0] - logistic_exact(y0, r, span)));
}

TEST(CoagulationBs32, GivesUpAfterMaxSteps) {
  coag::Bs32Options o;
  o.rel_tol = 1e-10;
  o.abs_tol = 1e-14;
  o.max_steps = 5;
  const auto res = run_bs32(1e-3, 20.0, 1.0, o);
  EXPECT_LE(res[2] + res[3], 5.0);
  EXPECT_EQ(res[5], 0.0);  // reported as failed: the span is not covered
  EXPECT_GT(std::fabs(res[0] - logistic_exact(1e-3, 20.0, 1.0)), 0.1);
  o.max_steps = 100000;  // the same span with room: covered, and reported so
  const auto done = run_bs32(1e-3, 20.0, 1.0, o);
  EXPECT_EQ(done[5], 1.0);
  EXPECT_NEAR(done[0], logistic_exact(1e-3, 20.0, 1.0), 1e-6);
}
