// On 2 ranks: a linalg::Distribution whose ghost counts do not match what the
// neighbour sends, or whose send list names a row the rank does not own, is
// refused by a GhostExchange on both ranks together (std::invalid_argument),
// the rank at fault naming the counts; a consistent one fills the ghosts with
// the neighbour's values. (Before, a short send left the receiver's ghost
// tail stale and the solve ran silently on the wrong operator.) An ILU pivot
// that fails on one rank stops the rung on both, each naming where it failed.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/linalg/distribution.hpp"
#include "mote/linalg/solver.hpp"

namespace {

using namespace mote;

IntView1 rows(const std::vector<int>& list) {
  IntView1 v("rows", list.size());
  auto h = Kokkos::create_mirror_view(v);
  for (std::size_t k = 0; k < list.size(); ++k) h(k) = list[k];
  Kokkos::deep_copy(v, h);
  return v;
}

/// Rank 0 owns 4 rows and sends `sent` of them to rank 1, which owns 3 rows and expects `expected` ghosts from
/// the left; rank 1 sends its row 0 to rank 0, which holds it as one right ghost.
linalg::Distribution slabs(const std::vector<int>& sent, int expected) {
  linalg::Distribution d;
  d.comm = core::Comm::world();
  if (d.comm.rank() == 0) {
    d.owned = 4;
    d.right = 1;
    d.from_right = 1;
    d.to_right = rows(sent);
  } else {
    d.owned = 3;
    d.left = 0;
    d.from_left = expected;
    d.to_left = rows({0});
  }
  return d;
}

/// The message of the std::invalid_argument a GhostExchange of d throws ("" when none).
std::string refusal(const linalg::Distribution& d) {
  try {
    linalg::GhostExchange exchange(d);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

/// Two rows per rank of a chain over both ranks, one ghost column each: rank 0's rows are diagonally
/// dominant; rank 1's two rows couple by 1e200 both ways, so its ILU(0) pivot u_11 = 1 - 1e400 overflows.
struct OverflowingChain {
  linalg::Distribution d;
  linalg::CrsPattern pattern;

  OverflowingChain() {
    d.comm = core::Comm::world();
    const int rank = d.comm.rank();
    d.owned = 2;
    (rank == 0 ? d.right : d.left) = 1 - rank;
    (rank == 0 ? d.from_right : d.from_left) = 1;
    (rank == 0 ? d.to_right : d.to_left) = rows({rank == 0 ? 1 : 0});
    const std::vector<std::vector<int>> columns =
        rank == 0 ? std::vector<std::vector<int>>{{0, 1}, {0, 1, 2}} : std::vector<std::vector<int>>{{0, 1, 2}, {0, 1}};
    pattern.n_rows = 2;
    pattern.n_cols = 3;
    pattern.row_map = linalg::RowMap("row_map", 3);
    pattern.entries = linalg::Entries("entries", 5);
    auto map = Kokkos::create_mirror_view(pattern.row_map);
    auto cols = Kokkos::create_mirror_view(pattern.entries);
    int e = 0;
    for (int r = 0; r < 2; ++r) {
      map(r) = e;
      for (int c : columns[r]) cols(e++) = c;
    }
    map(2) = e;
    Kokkos::deep_copy(pattern.row_map, map);
    Kokkos::deep_copy(pattern.entries, cols);
    linalg::finish_pattern("chain", pattern);
  }

  /// Writes the values: 4 on rank 0's diagonal, -1 off it and on the ghost columns; rank 1's block as above.
  void fill(const linalg::CrsMatrix& A) const {
    auto v = Kokkos::create_mirror_view(A.values);
    auto cols = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), pattern.entries);
    auto map = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), pattern.row_map);
    const bool overflowing = d.comm.rank() == 1;
    for (int r = 0; r < 2; ++r)
      for (int e = map(r); e < map(r + 1); ++e) {
        const int c = cols(e);
        v(e) = c == r ? (overflowing ? 1.0 : 4.0) : (overflowing && c < 2 ? 1e200 : -1.0);
      }
    Kokkos::deep_copy(A.values, v);
  }
};

}  // namespace

TEST(MpiLinearSolver, APivotFailingOnOneRankIsNamedOnEach) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  const OverflowingChain chain;
  linalg::SolverSettings settings;
  settings.fallback = false;
  linalg::LinearSolver solver("chain", chain.pattern, settings, chain.d);
  chain.fill(solver.matrix());
  linalg::Vector b("b", 2), x("x", 2);
  Kokkos::deep_copy(b, 1.0);
  const auto report = solver.try_solve(b, x);
  ASSERT_EQ(report.attempts.size(), 1u);
  const std::string& why = report.attempts[0].stop_reason;
  EXPECT_FALSE(report.converged);
  if (comm.rank() == 1) {
    EXPECT_EQ(why, "zero or non-finite pivot in row 1");
  } else {
    EXPECT_EQ(why, "zero or non-finite pivot on another rank");  // was "... in row -1"
  }
}

TEST(MpiDistribution, ConsistentSlabsExchangeTheirGhosts) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  const auto d = slabs({2, 3}, 2);
  linalg::GhostExchange exchange(d);
  linalg::Vector x("x", d.columns());
  auto h = Kokkos::create_mirror_view(x);
  for (int k = 0; k < d.owned; ++k) h(k) = 10 * comm.rank() + k;
  Kokkos::deep_copy(x, h);
  exchange.update(x);
  Kokkos::deep_copy(h, x);
  if (comm.rank() == 0) {
    EXPECT_EQ(h(4), 10.0);  // rank 1's row 0
  } else {
    EXPECT_EQ(h(3), 2.0);  // rank 0's rows 2 and 3, in its send order
    EXPECT_EQ(h(4), 3.0);
  }
}

TEST(MpiDistribution, MismatchedCountsAreRefusedOnEveryRank) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  const std::string why = refusal(slabs({2, 3}, 3));  // rank 1 expects 3 values, rank 0 sends 2
  ASSERT_FALSE(why.empty()) << "rank " << comm.rank() << " accepted it";
  const std::string expected =
      comm.rank() == 1 ? "rank 1 expects 3 ghost values from rank 0, which sends 2" : "rank 1's ghost columns";
  EXPECT_NE(why.find(expected), std::string::npos) << why;
}

TEST(MpiDistribution, SendingARowNotOwnedIsRefusedOnEveryRank) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  const std::string why = refusal(slabs({2, 4}, 2));  // rank 0 owns rows 0 .. 3
  ASSERT_FALSE(why.empty()) << "rank " << comm.rank() << " accepted it";
  EXPECT_NE(why.find(comm.rank() == 0 ? "rank 0 sends row 4" : "rank 0's ghost columns"), std::string::npos) << why;
}
