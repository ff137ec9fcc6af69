// Geometry of the (R, theta) grid (RBO24 eq. 1-3): telescoping sums of
// volumes and areas against the closed forms over the whole domain, the
// divergence theorem on every cell, and the spacing generators.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "mote/core/deck.hpp"
#include "mote/mesh/grid.hpp"

using namespace mote;

namespace {
mesh::GridSpec spec(mesh::Geometry g) {
  mesh::GridSpec s;
  s.nr = 40;
  s.ntheta = 30;
  s.r_edges = mesh::log_edges(3.0, 20.0, s.nr);
  s.theta_edges = mesh::block_edges(0.0, M_PI / 9, M_PI / 4, s.ntheta, 18);
  s.geometry = g;
  return s;
}
}  // namespace

TEST(MeshGrid, VolumesSumToTheDomain) {
  for (auto g : {mesh::Geometry::Cylindrical, mesh::Geometry::Planar}) {
    const mesh::Grid grid(spec(g), core::Comm::world());
    auto V = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.V);
    double sum = 0;
    for (int i = grid.i_begin(); i < grid.i_end(); ++i)
      for (int j = grid.j_begin(); j < grid.j_end(); ++j) sum += V(i, j);
    const double dtan = std::tan(M_PI / 4) - std::tan(0.0);
    const double exact =
        g == mesh::Geometry::Cylindrical ? (std::pow(20.0, 3) - 27.0) / 3.0 * dtan : 0.5 * (400.0 - 9.0) * dtan;
    EXPECT_NEAR(sum / exact, 1.0, 1e-13);
  }
}

TEST(MeshGrid, DivergenceTheoremOnEveryCell) {
  // F = Z Z_hat has div F = 1: the flux through the theta faces must equal V.
  // On a theta face the normal is (-sin, cos), F.n = R sin(theta), and the face
  // integral of R sin(theta) is tan(theta) x A^Z x (2/3 d(R^3)/d(R^2)) ... for the
  // cylindrical case the exact face flux is tan(theta) d(R^3)/3; check it equals
  // A^Z cos(theta) tan(theta) times the area-weighted mean radius.
  const mesh::Grid grid(spec(mesh::Geometry::Cylindrical), core::Comm::world());
  auto V = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.V);
  auto AZ = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.AZ);
  auto Re = grid.Re_h;
  auto te = grid.te_h;
  double worst = 0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      const double r0 = Re(i), r1 = Re(i + 1);
      const double mean_r = (2.0 / 3.0) * (r1 * r1 * r1 - r0 * r0 * r0) / (r1 * r1 - r0 * r0);
      auto flux = [&](int jj) { return AZ(i, jj) * std::cos(te(jj)) * std::tan(te(jj)) * mean_r; };
      worst = std::max(worst, std::fabs((flux(j + 1) - flux(j)) / V(i, j) - 1.0));
    }
  EXPECT_LT(worst, 1e-12);
}

// F = R R_hat has div F = 2 (cylindrical: (1/R) d(R^2)/dR) or 1 (planar). Its flux
// through a theta face, F.n = -R sin(theta) over the cone's area R dR / cos(theta),
// is -tan(theta) d(R^3)/3 (planar: -tan(theta) d(R^2)/2), computed here from the
// edges, so the radial faces' A^R R balance the volume alone: every cell, ghosts
// included.
TEST(MeshGrid, RadialFacesByTheDivergenceOfRHat) {
  for (auto g : {mesh::Geometry::Cylindrical, mesh::Geometry::Planar}) {
    const mesh::Grid grid(spec(g), core::Comm::world());
    auto V = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.V);
    auto AR = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.AR);
    auto Re = grid.Re_h;
    auto te = grid.te_h;
    const bool cyl = g == mesh::Geometry::Cylindrical;
    const double div = cyl ? 2.0 : 1.0;
    double worst = 0;
    for (int i = 0; i < grid.nr_total(); ++i)
      for (int j = 0; j < grid.nt_total(); ++j) {
        const double r0 = Re(i), r1 = Re(i + 1), dtan = std::tan(te(j + 1)) - std::tan(te(j));
        const double theta_out = -dtan * (cyl ? (r1 * r1 * r1 - r0 * r0 * r0) / 3.0 : 0.5 * (r1 * r1 - r0 * r0));
        const double radial_out = AR(i + 1, j) * r1 - AR(i, j) * r0;
        worst = std::max(worst, std::fabs((radial_out + theta_out) / (div * V(i, j)) - 1.0));
      }
    EXPECT_LT(worst, 1e-12) << (cyl ? "cylindrical" : "planar");
  }
}

// Ghost theta edges continue the last cell's width: within two widths of the
// pole they would pass it, where tan(theta) changes sign and a ghost cell's
// volume with it; such a grid is refused (0 to 1.45 rad in 10 cells: ghost
// edges at 1.595 and 1.74), one whose ghosts stay short of it is not.
TEST(MeshGrid, ThetaGhostsBeyondThePoleAreRefused) {
  auto with_theta = [](double lo, double hi) {
    mesh::GridSpec s;
    s.nr = 4;
    s.ntheta = 10;
    s.r_edges = mesh::log_edges(1.0, 2.0, s.nr);
    s.theta_edges = mesh::linear_edges(lo, hi, s.ntheta);
    return s;
  };
  for (const auto& [lo, hi] : {std::pair{0.0, 1.45}, std::pair{-1.45, 0.0}, std::pair{-1.2, 1.44}}) {
    try {
      mesh::Grid grid(with_theta(lo, hi), core::Comm::world());
      ADD_FAILURE() << lo << " to " << hi << " rad was accepted";
    } catch (const core::DeckError& e) {
      EXPECT_NE(std::string(e.what()).find("pole"), std::string::npos) << e.what();
    }
  }
  const mesh::Grid grid(with_theta(0.0, 1.3), core::Comm::world());  // ghosts at 1.43, 1.56
  auto V = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.V);
  auto AZ = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.AZ);
  for (int i = 0; i < grid.nr_total(); ++i)
    for (int j = 0; j < grid.nt_total(); ++j) {
      EXPECT_GT(V(i, j), 0.0) << i << ", " << j;
      EXPECT_GT(AZ(i, j + 1), 0.0) << i << ", " << j + 1;
    }
}

// A hand-built spec whose edge lists do not match its cell counts is refused
// before any edge is read.
TEST(MeshGrid, SpecEdgeCountsAreChecked) {
  auto s = spec(mesh::Geometry::Cylindrical);
  s.nr = 41;
  EXPECT_THROW(mesh::Grid(s, core::Comm::world()), std::invalid_argument);
  s = spec(mesh::Geometry::Cylindrical);
  s.theta_edges.pop_back();
  EXPECT_THROW(mesh::Grid(s, core::Comm::world()), std::invalid_argument);
}

TEST(MeshGrid, GhostCellsAndSpacing) {
  const auto s = spec(mesh::Geometry::Cylindrical);
  const mesh::Grid grid(s, core::Comm::world());
  EXPECT_EQ(grid.nr_total(), s.nr + 4);
  EXPECT_DOUBLE_EQ(grid.Re_h(grid.i_begin()), 3.0);
  EXPECT_DOUBLE_EQ(grid.Re_h(grid.i_end()), 20.0);
  // Log spacing continues into the ghosts at both ends, linear theta spacing
  // with the width of the first and last cells.
  const double ratio = std::pow(20.0 / 3.0, 1.0 / s.nr);
  for (int k = 1; k <= grid.ng; ++k) {
    EXPECT_NEAR(grid.Re_h(grid.i_begin() - k + 1) / grid.Re_h(grid.i_begin() - k), ratio, 1e-12);
    EXPECT_NEAR(grid.Re_h(grid.i_end() + k) / grid.Re_h(grid.i_end() + k - 1), ratio, 1e-12);
    EXPECT_NEAR(grid.te_h(grid.j_begin() - k), -k * (M_PI / 9) / 18, 1e-14);
    EXPECT_NEAR(grid.te_h(grid.j_end() + k) - M_PI / 4, k * (M_PI / 4 - M_PI / 9) / 12, 1e-14);
  }
  // Two blocks: 18 cells below pi/9, 0.533 the width of the 12 above (RBO24: about half).
  const auto b = mesh::block_edges(0.0, M_PI / 9, M_PI / 4, 30, 18);
  EXPECT_NEAR((b[1] - b[0]) / (b[29] - b[28]), (M_PI / 9 / 18) / ((M_PI / 4 - M_PI / 9) / 12), 1e-12);
  // Two logarithmic blocks: 40 cells in (0.1, 0.15), 200 in (0.15, 400) (RBO24 sec. 4.3).
  const auto l = mesh::log_block_edges(0.1, 0.15, 400.0, 240, 40);
  ASSERT_EQ(l.size(), 241u);
  EXPECT_DOUBLE_EQ(l[40], 0.15);
  EXPECT_NEAR(l[1] / l[0], std::pow(1.5, 1.0 / 40), 1e-13);
  EXPECT_NEAR(l[240] / l[239], std::pow(400.0 / 0.15, 1.0 / 200), 1e-13);
  const auto p = mesh::power_edges(0.0, 1.0, 4, 2.0);
  EXPECT_DOUBLE_EQ(p[1], 1.0 / 16.0);
}

TEST(MeshGrid, LogBlocksFromTheDeckAndTheirErrors) {
  core::DeckSchema schema;
  mesh::GridSpec::declare(schema);
  const std::string base =
      "[grid]\nnr = 240\nR_in = 0.1\nR_out = 400.0\nntheta = 8\ntheta_max = 0.7\nr_spacing = \"log_blocks\"\n";
  const auto g =
      mesh::GridSpec::from_deck(core::Deck::parse(base + "R_split = 0.15\nr_block_cells = 40\n", "grid.toml", schema));
  EXPECT_EQ(g.r_edges, mesh::log_block_edges(0.1, 0.15, 400.0, 240, 40));
  const auto refused = [&](const std::string& rest, const std::string& key) {
    try {
      core::Deck::parse(base + rest, "grid.toml", schema);
    } catch (const core::DeckError& e) {
      return std::string(e.what()).find("key '" + key + "'") != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused("R_split = 500.0\nr_block_cells = 40\n", "grid.R_split"));
  EXPECT_TRUE(refused("R_split = 0.15\nr_block_cells = 240\n", "grid.r_block_cells"));
  EXPECT_TRUE(refused("R_split = 0.15\n", "grid.r_block_cells"));
}
