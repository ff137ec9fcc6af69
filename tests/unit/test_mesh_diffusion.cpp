// The Wu et al. (2012) diffusion stencil (RBO24 sec. 3.2) reproduces the exact
// flux -D grad(u).n A of any linear u on the skewed (R, theta) mesh, for
// uniform D; and conserves (the coefficients of every face sum to zero).
#include <gtest/gtest.h>

#include <cmath>

#include "mote/core/loops.hpp"
#include "mote/mesh/diffusion_stencil.hpp"

using namespace mote;

namespace {
mesh::GridSpec skewed_spec() {
  mesh::GridSpec s;
  s.nr = 24;
  s.ntheta = 20;
  s.r_edges = mesh::log_edges(10.0, 50.0, s.nr);
  s.theta_edges = mesh::power_edges(-M_PI / 6, M_PI / 6, s.ntheta, 1.3);
  return s;
}
}  // namespace

// Kernels live in free functions: nvcc does not allow extended lambdas in a
// GoogleTest body (a private member function).
namespace {
/// u = 3 + b R + c Z on every cell.
RealView2 linear_field(const mesh::Grid& grid, Real b, Real c) {
  RealView2 u("u", grid.nr_total(), grid.nt_total());
  auto Rc = grid.Rc, tan_tc = grid.tan_tc;
  par_for(
      "test::linear", 0, grid.nr_total(), 0, grid.nt_total(),
      KOKKOS_LAMBDA(int i, int j) { u(i, j) = 3.0 + b * Rc(i) + c * Rc(i) * tan_tc(j); });
  return u;
}

/// Largest relative error of the stencil's fluxes of the linear field u against
/// -D0 grad(u).n A, over radial faces (radial = true) or theta faces.
Real worst_flux_error(const mesh::Grid& grid, const mesh::DiffusionCoefficients& coef, const RealView2& u, Real D0,
                      Real b, Real c, bool radial) {
  auto AR = grid.AR, AZ = grid.AZ;
  auto sin_te = grid.sin_te, cos_te = grid.cos_te;
  Real worst = 0;
  const int i0 = grid.i_begin(), i1 = grid.i_end(), j0 = grid.j_begin(), j1 = grid.j_end();
  if (radial) {
    par_reduce(
        "test::radial_error", i0, i1 + 1, j0, j1,
        KOKKOS_LAMBDA(int i, int j, Real& w) {
          const Real exact = -D0 * b * AR(i, j);
          w = math::max(w, math::fabs(coef.radial_flux(u, i, j) - exact) / math::fabs(exact));
        },
        Kokkos::Max<Real>(worst));
  } else {
    par_reduce(
        "test::theta_error", i0, i1, j0, j1 + 1,
        KOKKOS_LAMBDA(int i, int j, Real& w) {
          const Real exact = -D0 * (-b * sin_te(j) + c * cos_te(j)) * AZ(i, j);
          w = math::max(w, math::fabs(coef.theta_flux(u, i, j) - exact) / math::fabs(exact));
        },
        Kokkos::Max<Real>(worst));
  }
  return worst;
}

/// D = 1 + 0.1 R + j: varies along both directions.
RealView2 varying_diffusivity(const mesh::Grid& grid) {
  RealView2 D("D", grid.nr_total(), grid.nt_total());
  auto Rc = grid.Rc;
  par_for(
      "test::D", 0, grid.nr_total(), 0, grid.nt_total(),
      KOKKOS_LAMBDA(int i, int j) { D(i, j) = 1.0 + 0.1 * Rc(i) + j; });
  return D;
}
}  // namespace

TEST(MeshDiffusion, ExactForLinearFields) {
  for (auto geometry : {mesh::Geometry::Planar, mesh::Geometry::Cylindrical}) {
    auto spec = skewed_spec();
    spec.geometry = geometry;
    const mesh::Grid grid(spec, core::Comm::world());
    const Real D0 = 2.5, b = 0.7, c = -1.3;
    RealView2 D("D", grid.nr_total(), grid.nt_total());
    Kokkos::deep_copy(D, D0);
    const auto u = linear_field(grid, b, c);
    const auto coef = mesh::diffusion_coefficients(grid, D);
    EXPECT_LT(worst_flux_error(grid, coef, u, D0, b, c, true), 1e-11);
    EXPECT_LT(worst_flux_error(grid, coef, u, D0, b, c, false), 1e-11);
  }
}

TEST(MeshDiffusion, CoefficientsSumToZero) {
  const mesh::Grid grid(skewed_spec(), core::Comm::world());
  const auto coef = mesh::diffusion_coefficients(grid, varying_diffusivity(grid));
  auto r = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), coef.radial);
  auto t = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), coef.theta);
  double worst_r = 0, worst_t = 0;
  for (int i = 1; i < grid.nr_total(); ++i)
    for (int j = 1; j < grid.nt_total() - 1; ++j)
      worst_r = std::max(worst_r, std::fabs(r(i, j, 0) + r(i, j, 1) + r(i, j, 2) + r(i, j, 3)) / std::fabs(r(i, j, 0)));
  for (int i = 1; i < grid.nr_total() - 1; ++i)
    for (int j = 1; j < grid.nt_total(); ++j)
      worst_t = std::max(worst_t, std::fabs(t(i, j, 0) + t(i, j, 1) + t(i, j, 2) + t(i, j, 3)) / std::fabs(t(i, j, 0)));
  EXPECT_LT(worst_r, 1e-13);
  EXPECT_LT(worst_t, 1e-13);
}
