// On 2 ranks (radial slabs): the stellar irradiation's optical depth runs
// through the slabs in turn (RBO24 eq. 45-46), so that every cell's absorbed
// and scattered power is the one-rank figure, computed here on the host from
// the global grid, and the grid's total is the same on every rank.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/core/units.hpp"
#include "mote/radiation/irradiation.hpp"

namespace {

using namespace mote;

constexpr int kBins = 12;

/// rho kappa_ext of global radial cell ig, theta cell j, bin B: a few optical
/// depths along each ray, varying along it, across rays and bins.
double extinction(int ig, int j, int B) {
  return 2e-14 * (1.0 + 0.5 * std::sin(0.7 * ig)) * (1.0 + 0.3 * B) * (1.0 + 0.1 * j);
}

}  // namespace

TEST(MpiIrradiation, SlabsGiveTheOneRankPowerInEveryCell) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  mesh::GridSpec spec;
  spec.nr = 40;
  spec.ntheta = 10;
  spec.r_edges = mesh::log_edges(1.0 * units::cgs::au, 50.0 * units::cgs::au, spec.nr);
  spec.theta_edges = mesh::linear_edges(0.0, 0.4, spec.ntheta);
  const mesh::Grid grid(spec, comm);
  ASSERT_GT(grid.nr, 0);
  const auto constants = radiation::RadiationConstants::in(units::UnitSystem::cgs_units());
  std::vector<double> bins;
  for (int k = 0; k <= kBins; ++k) bins.push_back(1e-5 * std::pow(3e4, double(k) / kBins));
  const radiation::Star star_spec{2.0 * units::cgs::R_sun, 4000.0};
  radiation::StellarIrradiation star(grid, star_spec, bins, {1e-5, 1e-3, 0.3}, constants);
  RealView3 ext("ext", grid.nr_total(), grid.nt_total(), kBins), abs("abs", grid.nr_total(), grid.nt_total(), kBins);
  auto ext_h = Kokkos::create_mirror_view(ext);
  auto abs_h = Kokkos::create_mirror_view(abs);
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j)
      for (int B = 0; B < kBins; ++B) {
        ext_h(i, j, B) = extinction(grid.i_offset + i - grid.i_begin(), j - grid.j_begin(), B);
        abs_h(i, j, B) = 0.6 * ext_h(i, j, B);
      }
  Kokkos::deep_copy(ext, ext_h);
  Kokkos::deep_copy(abs, abs_h);
  RealView2 heating("S", grid.nr_total(), grid.nt_total());
  RealView3 scattering("Ssca", grid.nr_total(), grid.nt_total(), 2);
  star.heat(ext, abs, heating, scattering);
  auto S = Kokkos::create_mirror_view_and_copy(HostSpace(), heating);
  auto Ss = Kokkos::create_mirror_view_and_copy(HostSpace(), scattering);

  // The one-rank figures: the power each global cell takes (eq. 45-46 with the solid angle written out).
  const std::vector<double>& R = grid.r_edges_global;
  const auto& L = star.bin_luminosities();
  double worst = 0.0, total = 0.0;
  for (int j = 0; j < spec.ntheta; ++j) {
    const int jl = grid.j_begin() + j;
    const double inv_cos = 1.0 / std::cos(grid.tc_h(jl));
    const double solid = (std::sin(grid.te_h(jl + 1)) - std::sin(grid.te_h(jl))) / (4.0 * M_PI);
    std::vector<double> tau(kBins, 0.0);  // to the inner edge of cell ig, per bin
    for (int ig = 0; ig < spec.nr; ++ig) {
      const double dr = (R[ig + 1] - R[ig]) * inv_cos;
      double cell = 0.0;
      for (int B = 0; B < kBins; ++B) {
        cell += L[B] * solid * std::exp(-tau[B]) * -std::expm1(-extinction(ig, j, B) * dr);
        tau[B] += extinction(ig, j, B) * dr;
      }
      total += cell;
      const int il = ig - grid.i_offset + grid.i_begin();
      if (il < grid.i_begin() || il >= grid.i_end()) continue;  // another rank's cell
      const double got = grid.V_h(il, jl) * (S(il, jl) + Ss(il, jl, 0) + Ss(il, jl, 1));
      worst = std::fmax(worst, std::fabs(got / cell - 1.0));
    }
  }
  const double worst_all = comm.max(worst);
  radiation::FldFields fields;
  fields.heating = heating;
  fields.scattering_source = scattering;
  const double absorbed = radiation::absorbed_power(grid, fields);
  if (comm.is_root())
    std::printf("irradiation on 2 ranks: worst cell power against one rank %.3e; total %.3e of it\n", worst_all,
                std::fabs(absorbed / total - 1.0));
  EXPECT_LE(worst_all, 1e-12);
  EXPECT_NEAR(absorbed / total, 1.0, 1e-12);
  EXPECT_EQ(comm.max(absorbed), comm.min(absorbed));  // every rank has the grid's total
}
