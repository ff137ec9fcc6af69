// Snapshot write throughput: one 2D double field of n x n cells written
// collectively with io::H5File + SnapshotWriter (tmp + rename as in a run).
#include <filesystem>
#include <vector>

#include "bench_main.hpp"
#include "mote/io/output_files.hpp"
#include "mote/io/snapshot.hpp"

namespace {

void BM_SnapshotWrite(benchmark::State& state) {
  const auto comm = mote::core::Comm::world();
  const int n = static_cast<int>(state.range(0));
  const int rows = n / comm.size(), row0 = comm.rank() * rows;
  std::vector<double> field(static_cast<size_t>(rows) * n, 1.5), xn(n + 1), yn(n + 1);
  for (int i = 0; i <= n; ++i) xn[i] = yn[i] = i;
  const auto dir = std::filesystem::temp_directory_path() / "mote_bench_io";
  mote::io::create_directory(dir.string(), comm);
  const std::string path = (dir / "snapshot.h5").string();
  for (auto _ : state) {
    {
      mote::io::H5File file(mote::io::temporary_name(path), mote::io::H5File::Mode::Create, comm);
      mote::io::SnapshotWriter w(file);
      w.rectilinear_2d(xn, yn, row0, rows);
      w.cell_field("density", field.data(), {"code density", 1.0});
    }
    mote::io::commit_file(path, comm);
  }
  state.counters["bytes_per_s"] =
      benchmark::Counter(double(n) * n * sizeof(double), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_SnapshotWrite)->Arg(512)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
