// Proves the Kokkos Kernels dependency links and works: assemble a CRS matrix
// on the device and compare KokkosSparse::spmv with a dense product on the host.
#include <gtest/gtest.h>

#include <KokkosSparse_CrsMatrix.hpp>
#include <KokkosSparse_spmv.hpp>
#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/core/loops.hpp"

using mote::Real;

namespace {
/// x_i = 1 + 0.5 sin(0.1 i). A free function: nvcc does not allow extended
/// lambdas in a GoogleTest body (a private member function).
void fill_smooth(const mote::RealView1& x) {
  mote::par_for(
      "test::fill_x", 0, static_cast<int>(x.extent(0)),
      KOKKOS_LAMBDA(int i) { x(i) = 1.0 + 0.5 * mote::math::sin(0.1 * i); });
}
}  // namespace

TEST(KokkosKernelsLink, CrsSpmvMatchesDenseProduct) {
  using Matrix = KokkosSparse::CrsMatrix<Real, int, mote::ExecSpace::device_type, void, int>;
  const int n = 200;
  // A 2D-like operator: tridiagonal plus a band at distance 10, non-symmetric.
  std::vector<std::vector<Real>> dense(n, std::vector<Real>(n, 0.0));
  for (int i = 0; i < n; ++i) {
    dense[i][i] = 4.0 + 0.01 * i;
    if (i > 0) dense[i][i - 1] = -1.0;
    if (i + 1 < n) dense[i][i + 1] = -1.5;
    if (i + 10 < n) dense[i][i + 10] = -0.25;
    if (i >= 10) dense[i][i - 10] = -0.5;
  }
  auto row_map_h = Kokkos::View<int*, Kokkos::HostSpace>("row_map", n + 1);
  std::vector<int> cols;
  std::vector<Real> vals;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      if (dense[i][j] != 0.0) {
        cols.push_back(j);
        vals.push_back(dense[i][j]);
      }
    row_map_h(i + 1) = static_cast<int>(cols.size());
  }
  const int nnz = static_cast<int>(cols.size());
  mote::View<int*> row_map("row_map", n + 1);
  mote::View<int*> entries("entries", nnz);
  mote::View<Real*> values("values", nnz);
  Kokkos::deep_copy(row_map, row_map_h);
  Kokkos::deep_copy(entries, mote::UnmanagedHostView<int*>(cols.data(), nnz));
  Kokkos::deep_copy(values, mote::UnmanagedHostView<Real*>(vals.data(), nnz));
  Matrix A("A", n, n, nnz, values, row_map, entries);

  mote::RealView1 x("x", n), y("y", n);
  fill_smooth(x);
  KokkosSparse::spmv("N", 1.0, A, x, 0.0, y);

  auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
  auto yh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), y);
  double max_err = 0.0;
  for (int i = 0; i < n; ++i) {
    double ref = 0.0;
    for (int j = 0; j < n; ++j) ref += dense[i][j] * xh(j);
    max_err = std::max(max_err, std::fabs(yh(i) - ref));
  }
  EXPECT_LT(max_err, 1e-13);
  EXPECT_EQ(A.nnz(), nnz);
  EXPECT_EQ(A.numRows(), n);
}
