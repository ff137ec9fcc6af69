// Kokkos Kernels CRS sparse matrix-vector product on the 5-point Laplacian of
// an n x n grid (the stencil of the grid solvers' implicit steps). Reports
// rows/s and the effective memory bandwidth (values + column indices + row
// map + x + y traffic, counting x once per non-zero as an upper bound).
#include <KokkosSparse_CrsMatrix.hpp>
#include <KokkosSparse_spmv.hpp>

#include "bench_main.hpp"
#include "mote/core/kokkos_types.hpp"
#include "mote/core/loops.hpp"

namespace {

using Matrix = KokkosSparse::CrsMatrix<mote::Real, int, mote::ExecSpace::device_type, void, int>;

Matrix laplacian(int n) {
  const int rows = n * n;
  mote::View<int*> row_map("row_map", rows + 1);
  // Row i has 1 + (number of in-grid neighbours) entries.
  mote::par_for(
      "bench::count", 0, rows, KOKKOS_LAMBDA(int r) {
        const int i = r % n, j = r / n;
        row_map(r + 1) = 1 + (i > 0) + (i < n - 1) + (j > 0) + (j < n - 1);
      });
  Kokkos::parallel_scan(
      "bench::scan", Kokkos::RangePolicy<mote::ExecSpace>(0, rows + 1), KOKKOS_LAMBDA(int r, int& sum, bool final) {
        const int c = row_map(r);
        sum += c;
        if (final) row_map(r) = sum;
      });
  int nnz = 0;
  Kokkos::deep_copy(nnz, Kokkos::subview(row_map, rows));
  mote::View<int*> cols("cols", nnz);
  mote::RealView1 vals("vals", nnz);
  mote::par_for(
      "bench::fill", 0, rows, KOKKOS_LAMBDA(int r) {
        const int i = r % n, j = r / n;
        int k = row_map(r);
        auto put = [&](int c, mote::Real v) {
          cols(k) = c;
          vals(k) = v;
          ++k;
        };
        if (j > 0) put(r - n, -1.0);
        if (i > 0) put(r - 1, -1.0);
        put(r, 4.0);
        if (i < n - 1) put(r + 1, -1.0);
        if (j < n - 1) put(r + n, -1.0);
      });
  return Matrix("laplacian", rows, rows, nnz, vals, row_map, cols);
}

void BM_Spmv(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Matrix A = laplacian(n);
  mote::RealView1 x("x", n * n), y("y", n * n);
  Kokkos::deep_copy(x, 1.0);
  for (auto _ : state) {
    KokkosSparse::spmv("N", 1.0, A, x, 0.0, y);
    Kokkos::fence();
  }
  const double bytes =
      A.nnz() * (sizeof(mote::Real) * 2 + sizeof(int)) + (n * n + 1) * sizeof(int) + n * n * sizeof(mote::Real);
  state.counters["rows_per_s"] = benchmark::Counter(double(n) * n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_s"] = benchmark::Counter(bytes, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["nnz"] = A.nnz();
}

}  // namespace

BENCHMARK(BM_Spmv)->Arg(256)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
