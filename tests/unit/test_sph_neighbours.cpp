// Unit tests of the O(N) SPH neighbour search: the interacting pairs
// (|r_ab| < R max(h_a, h_b)) found through the cell-binned symmetric list are
// identical to a brute-force search over all particles and periodic images on
// random particles with a 100x spread of h, in 1, 2 and 3D, periodic (supports
// up to ~1.5 box lengths: pairs and self-pairs through several images) and free,
// and on a 2D column periodic across a narrow width and free in height, where h
// grows away from the mid-plane to supports near the width; the rebuild
// criterion detects motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mote/core/exit_codes.hpp"
#include "mote/sph/neighbours.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

struct Cloud {
  Particles p;
  Box box;
};

Cloud random_cloud(int dim, int n, bool periodic, Real hmin, Real spread, unsigned seed) {
  Cloud c;
  c.box.dim = dim;
  for (int d = 0; d < dim; ++d) {
    c.box.lo[d] = 0.0;
    c.box.hi[d] = 1.0;
    c.box.periodic[d] = periodic;
  }
  c.p.allocate(n, dim);
  auto x = Kokkos::create_mirror_view(c.p.x);
  auto h = Kokkos::create_mirror_view(c.p.h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> uni(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) x(i, d) = uni(rng);
    h(i) = hmin * std::pow(spread, uni(rng));  // log-uniform in [hmin, spread hmin]
  }
  h(0) = hmin;
  h(1) = hmin * spread;
  Kokkos::deep_copy(c.p.x, x);
  Kokkos::deep_copy(c.p.h, h);
  return c;
}

/// Builds the list (optionally a second time after moving the particles and
/// scaling h, which exercises the single-traversal rebuild sized from the
/// previous list, or its overflow fallback) and compares with brute force.
void compare_with_brute_force(Cloud c, KernelType kernel, bool rebuild = false, Real h_scale = 1.0) {
  const int n = c.p.n, dim = c.p.dim;
  const Real R = kernel_radius(kernel);
  NeighbourList nl;
  nl.build(c.p, c.box, kernel, 0.1);
  if (rebuild) {
    auto xm = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.x);
    auto hm = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.h);
    std::mt19937 rng(99);
    std::uniform_real_distribution<Real> jit(-1.0, 1.0);
    Real hmin = hm(0);
    for (int i = 0; i < n; ++i) hmin = std::min(hmin, hm(i));
    for (int i = 0; i < n; ++i) {
      // Moves of the order of the list skin (may leave the box: build wraps).
      for (int d = 0; d < dim; ++d) xm(i, d) += 0.3 * hmin * jit(rng);
      hm(i) *= h_scale;
    }
    Kokkos::deep_copy(c.p.x, xm);
    Kokkos::deep_copy(c.p.h, hm);
    nl.build(c.p, c.box, kernel, 0.1);
    EXPECT_EQ(nl.builds(), 2);
    EXPECT_EQ(nl.exact_builds(), h_scale > 1.2 ? 2 : 1);  // single traversal unless the segments overflow
  }
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.x);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.h);
  auto off = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), nl.offsets);
  auto nb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), nl.neigh);
  auto img = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), nl.image);
  long long pairs = 0;
  int mismatches = 0;
  auto dist2 = [&](int a, int b, int code) {
    Real r2 = 0.0;
    for (int d = 0; d < dim; ++d) {
      const Real dx = c.box.separation(x(a, d), x(b, d), code, d);
      r2 += dx * dx;
    }
    return r2;
  };
  for (int a = 0; a < n; ++a) {
    std::set<std::pair<int, int>> brute, listed;
    std::vector<std::pair<int, int>> raw;
    for (int b = 0; b < n; ++b) {
      const Real hm = std::max(h(a), h(b));
      const Real rmax = R * hm;
      // Per direction, the image shifts (-2 .. 2 box lengths) that can be in range.
      std::vector<int> shifts[3];
      for (int d = 0; d < 3; ++d) {
        if (d >= dim || !c.box.periodic[d]) {
          shifts[d].push_back(0);
          continue;
        }
        for (int sd = -2; sd <= 2; ++sd) {
          const Real dx = x(a, d) - x(b, d) - sd * c.box.length(d);
          if (std::fabs(dx) < rmax) shifts[d].push_back(sd);
        }
      }
      for (int s2 : shifts[2])
        for (int s1 : shifts[1])
          for (int s0 : shifts[0]) {
            const int code = (s0 + 2) + 5 * (s1 + 2) + 25 * (s2 + 2);
            if (b == a && code == no_image()) continue;
            if (dist2(a, b, code) < rmax * rmax) brute.insert({b, code});
          }
    }
    for (int j = off(a); j < off(a + 1); ++j) {
      const int b = nb(j), code = img(j);
      raw.push_back({b, code});
      const Real hm = std::max(h(a), h(b));
      if (dist2(a, b, code) < R * R * hm * hm) listed.insert({b, code});
    }
    std::sort(raw.begin(), raw.end());
    EXPECT_TRUE(std::adjacent_find(raw.begin(), raw.end()) == raw.end()) << "duplicate entry for particle " << a;
    for (const auto& e : raw) EXPECT_FALSE(e.first == a && e.second == no_image()) << "self in list of " << a;
    if (brute != listed) ++mismatches;
    pairs += static_cast<long long>(brute.size());
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(pairs, n);  // the test is not vacuous
  std::printf("[sph neighbours] %dD %s: %d particles, %lld interacting pairs, %lld list entries, %d mismatches\n", dim,
              c.box.periodic[0] ? "periodic" : "free", n, pairs, nl.entries(), mismatches);
}

TEST(SphNeighbours, BruteForcePeriodic) {
  compare_with_brute_force(random_cloud(1, 400, true, 0.007, 100.0, 1), KernelType::M4);
  compare_with_brute_force(random_cloud(2, 1500, true, 0.003, 100.0, 2), KernelType::M4);
  compare_with_brute_force(random_cloud(3, 2000, true, 0.0025, 100.0, 3), KernelType::M6);
}

TEST(SphNeighbours, BruteForceFree) {
  compare_with_brute_force(random_cloud(1, 400, false, 0.0004, 100.0, 4), KernelType::WendlandC4);
  compare_with_brute_force(random_cloud(2, 1500, false, 0.002, 100.0, 5), KernelType::M6);
  compare_with_brute_force(random_cloud(3, 2000, false, 0.002, 100.0, 6), KernelType::M4);
}

TEST(SphNeighbours, MixedBoundaries) {
  Cloud c = random_cloud(3, 1500, true, 0.003, 100.0, 7);
  c.box.periodic[2] = false;
  compare_with_brute_force(c, KernelType::M4);
}

TEST(SphNeighbours, NarrowPeriodicColumn) {
  // A 2D column as perf/bench_sph's: periodic across a width of 0.5, free in
  // height, h growing 10x away from the mid-plane to supports near the width.
  Cloud c = random_cloud(2, 1500, true, 0.0156, 1.0, 15);
  c.box.hi[0] = 0.5;
  c.box.lo[1] = -0.75;
  c.box.hi[1] = 0.75;
  c.box.periodic[1] = false;
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.x);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.h);
  for (int i = 0; i < c.p.n; ++i) {
    x(i, 0) *= 0.5;
    x(i, 1) = 1.5 * x(i, 1) - 0.75;
    h(i) = 0.0156 * std::exp(x(i, 1) * x(i, 1) / (2.0 * 0.25 * 0.25) / 2.0);
  }
  Kokkos::deep_copy(c.p.x, x);
  Kokkos::deep_copy(c.p.h, h);
  compare_with_brute_force(c, KernelType::M6);
  compare_with_brute_force(c, KernelType::M6, true, 1.0);
}

TEST(SphNeighbours, RebuildSinglePassAndOverflow) {
  compare_with_brute_force(random_cloud(2, 1500, true, 0.003, 100.0, 12), KernelType::M4, true, 1.0);
  compare_with_brute_force(random_cloud(3, 2000, false, 0.002, 100.0, 13), KernelType::M6, true, 1.05);
  // h grows by 1.5: the segments sized from the old list overflow (exact path).
  compare_with_brute_force(random_cloud(3, 2000, true, 0.0025, 100.0, 14), KernelType::M4, true, 1.5);
}

TEST(SphNeighbours, RebuildCriterion) {
  Cloud c = random_cloud(2, 500, true, 0.01, 2.0, 8);
  NeighbourList nl;
  nl.build(c.p, c.box, KernelType::M4, 0.1);
  EXPECT_FALSE(nl.needs_rebuild(c.p, c.box));
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.x);
  x(3, 0) = c.box.wrap(x(3, 0) + 0.6 * nl.delta, 0);  // more than delta / 2
  Kokkos::deep_copy(c.p.x, x);
  EXPECT_TRUE(nl.needs_rebuild(c.p, c.box));
}

TEST(SphNeighbours, SupportLargerThanTwoPeriodicBoxesThrows) {
  Cloud c = random_cloud(2, 100, true, 0.8, 2.0, 9);
  NeighbourList nl;
  EXPECT_THROW(nl.build(c.p, c.box, KernelType::M4, 0.1), std::runtime_error);
}

/// Segment sizes from a View (a functor: the scan's count).
struct ViewCount {
  Kokkos::View<long long*, mote::MemSpace> c;
  KOKKOS_INLINE_FUNCTION long long operator()(int i) const { return c(i); }
};

/// The exclusive scan of the counts in `counts` (n + 1 offsets); the total.
std::pair<int, std::vector<int>> scan(const std::vector<long long>& counts) {
  const int n = static_cast<int>(counts.size());
  ViewCount count{Kokkos::View<long long*, mote::MemSpace>("counts", n)};
  auto h = Kokkos::create_mirror_view(count.c);
  for (int i = 0; i < n; ++i) h(i) = counts[i];
  Kokkos::deep_copy(count.c, h);
  Kokkos::View<int*, mote::MemSpace> offsets("offsets", n + 1);
  const int total =
      mote::sph::detail::scan_offsets("test::scan", n, offsets, Kokkos::View<long long, mote::MemSpace>("t"), count);
  auto o = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), offsets);
  return {total, std::vector<int>(o.data(), o.data() + n + 1)};
}

}  // namespace

// The lists index their entries with int: a list beyond 2^31 - 1 entries
// (about 10^7 particles with the 3D M6 kernel, which a large GPU holds) is
// refused by its 64-bit total before an entry is written, not wrapped.
TEST(SphNeighbours, ListsBeyondTheIntRangeAreRefused) {
  const auto small = scan({3, 0, 5, 2});
  EXPECT_EQ(small.first, 10);
  EXPECT_EQ(small.second, (std::vector<int>{0, 3, 3, 8, 10}));
  const long long most = std::numeric_limits<int>::max();
  EXPECT_EQ(scan({most - 7, 7}).first, most);
  try {
    scan({1000000000, 1000000000, 1000000000});
    ADD_FAILURE() << "a list of 3e9 entries was accepted";
  } catch (const std::length_error& e) {
    EXPECT_NE(std::string(e.what()).find("3000000000 entries exceeds the 32-bit index range"), std::string::npos)
        << e.what();
  }
}

// A particle whose position or h is not finite (a step gone wrong between non-finite checks) is named at the
// next rebuild as a numerical failure (exit 3), not binned into a cell index it has none of; the old build
// looped forever on an infinite periodic coordinate, or sized its cells from an infinite extent.
TEST(SphNeighbours, NonFiniteParticlesAreNamedAtARebuild) {
  for (const bool periodic : {true, false}) {
    for (const int field : {0, 1, 2}) {  // x = +inf, z = NaN, h = -inf
      Cloud c = random_cloud(3, 200, periodic, 0.05, 2.0, 21);
      auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.x);
      auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.p.h);
      if (field == 0) x(137, 0) = std::numeric_limits<Real>::infinity();
      if (field == 1) x(137, 2) = std::numeric_limits<Real>::quiet_NaN();
      if (field == 2) h(137) = -std::numeric_limits<Real>::infinity();
      h(150) = std::numeric_limits<Real>::quiet_NaN();  // a later one is not the one named
      Kokkos::deep_copy(c.p.x, x);
      Kokkos::deep_copy(c.p.h, h);
      NeighbourList nl;
      try {
        nl.build(c.p, c.box, KernelType::M4, 0.1);
        ADD_FAILURE() << "no error for field " << field;
      } catch (const mote::core::NumericalError& e) {
        EXPECT_NE(std::string(e.what()).find("sph: particle 137 (in memory order) has position ("), std::string::npos)
            << e.what();
      }
    }
  }
}

// Box::wrap brings any finite coordinate into [lo, hi) of a periodic direction (one length at a time near
// the box, as a particle crossing a boundary; by a remainder far from it) and leaves non-finite ones as they
// are; a free direction is not wrapped.
TEST(SphBox, WrapBringsEveryFiniteCoordinateIntoThePeriodicBox) {
  Box box;
  box.lo[0] = -0.5;
  box.hi[0] = 0.25;
  box.periodic[0] = true;
  EXPECT_EQ(box.wrap(0.25 + 0.125, 0), 0.25 + 0.125 - 0.75);
  EXPECT_EQ(box.wrap(-0.5 - 0.125, 0), -0.5 - 0.125 + 0.75);
  for (const Real x : {1e300, -1e300, 7.3e8, -2.1e5, 3.0, -3.01}) {
    const Real w = box.wrap(x, 0);
    EXPECT_TRUE(w >= -0.5 && w < 0.25) << x << " -> " << w;
    EXPECT_NEAR(std::remainder(w - x, 0.75), 0.0, 1e-12 * std::max(1.0, std::fabs(x))) << x;
  }
  EXPECT_EQ(box.wrap(std::numeric_limits<Real>::infinity(), 0), std::numeric_limits<Real>::infinity());
  EXPECT_TRUE(std::isnan(box.wrap(std::numeric_limits<Real>::quiet_NaN(), 0)));
  EXPECT_EQ(box.wrap(1e300, 1), 1e300);
}
