// Standalone coagulation cells (see include/mote/coagulation/standalone_cells.hpp).
#include "mote/coagulation/standalone_cells.hpp"

#include <cmath>
#include <stdexcept>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"

namespace mote::coagulation {

StandaloneCells::StandaloneCells(const MassGrid& grid, const CoagulationSettings& settings, int cells, AnyKernel kernel,
                                 const std::vector<double>& initial, double call_interval, io::FieldUnit density_unit)
    : grid_(grid),
      solver_(grid_, settings, cells),
      kernel_(std::move(kernel)),
      cells_(cells),
      call_interval_(call_interval),
      density_unit_(std::move(density_unit)) {
  if (const auto w = grid_.resolution_warning(); !w.empty()) logging::warn(w);
  const int n = grid_.size();
  if (static_cast<int>(initial.size()) != n)
    throw std::logic_error("StandaloneCells: initial distribution size differs from the grid");
  density_ = RealView2("coagulation::density", cells_, n);
  auto h = Kokkos::create_mirror_view(density_);
  for (int c = 0; c < cells_; ++c)
    for (int k = 0; k < n; ++k) h(c, k) = initial[k];
  Kokkos::deep_copy(density_, h);
  total0_ = total_density();
}

double StandaloneCells::max_dt() { return call_interval_ > 0 ? call_interval_ : 1e300; }

void StandaloneCells::advance(double, double dt) {
  const auto st = solver_.integrate(density_, dt, kernel_);
  substeps_ += st.substeps;
  rejections_ += st.rejections;
  if (st.failed_cells > 0)
    throw core::NumericalError(
        logging::cat("coagulation failed in ", st.failed_cells, " cells (max_substeps reached)"));
  elapsed_ += dt;
}

void StandaloneCells::write_distribution(io::SnapshotWriter& out, const io::FieldUnit& mass_unit,
                                         const io::FieldUnit& size_unit) const {
  const hsize_t n = grid_.size(), nc = cells_;
  out.array("mass", io::Block::whole({n}), grid_.masses().data(), mass_unit);
  out.array("mass_edges", io::Block::whole({n + 1}), grid_.edges().data(), mass_unit);
  out.array("grain_size", io::Block::whole({n}), grid_.sizes().data(), size_unit);
  out.array("density", io::Block::whole({nc, n}), host_density().data(), density_unit_);
}

void StandaloneCells::save_state(io::H5File& file) const {
  const hsize_t n = grid_.size(), nc = cells_;
  file.write("/state/density", io::Block::whole({nc, n}), host_density().data());
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver_.next_substep());
  file.write("/state/next_substep", io::Block::whole({nc}), h.data());
  file.write_attribute("/state", "elapsed", elapsed_);
  file.write_attribute("/state", "initial_total", total0_);
  file.write_attribute("/state", "substeps", static_cast<std::int64_t>(substeps_));
  file.write_attribute("/state", "rejections", static_cast<std::int64_t>(rejections_));
}

void StandaloneCells::load_state(const io::H5File& file) {
  const int n = grid_.size();
  std::vector<double> rho(size_t(cells_) * n), next(cells_);
  file.read("/state/density", io::Block::whole({hsize_t(cells_), hsize_t(n)}), rho.data());
  file.read("/state/next_substep", io::Block::whole({hsize_t(cells_)}), next.data());
  elapsed_ = file.read_attribute_real("/state", "elapsed");
  total0_ = file.read_attribute_real("/state", "initial_total");
  // The history's running totals (absent from checkpoints before 2026-12-07: counted from 0).
  const auto count = [&](const char* name) {
    return file.has_attribute("/state", name) ? file.read_attribute_int("/state", name) : 0;
  };
  substeps_ = count("substeps");
  rejections_ = count("rejections");
  auto h = Kokkos::create_mirror_view(density_);
  for (int c = 0; c < cells_; ++c)
    for (int k = 0; k < n; ++k) h(c, k) = rho[size_t(c) * n + k];
  Kokkos::deep_copy(density_, h);
  auto hn = Kokkos::create_mirror_view(solver_.next_substep());
  for (int c = 0; c < cells_; ++c) hn(c) = next[c];
  Kokkos::deep_copy(solver_.next_substep(), hn);
}

std::vector<io::Diagnostic> StandaloneCells::diagnostics() const {
  const double m = total_density();
  return {{"total_density", m},
          {"mass_error", (m - total0_) / total0_},
          {"substeps", double(substeps_)},
          {"rejections", double(rejections_)}};
}

std::optional<io::NonFinite> StandaloneCells::find_non_finite() const {
  const auto rho = host_density();
  for (size_t i = 0; i < rho.size(); ++i)
    if (!std::isfinite(rho[i]))
      return io::NonFinite{"density", logging::cat("cell ", i / grid_.size(), ", species ", i % grid_.size())};
  return std::nullopt;
}

std::vector<double> StandaloneCells::host_density() const {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), density_);
  const int n = grid_.size();
  std::vector<double> out(size_t(cells_) * n);
  for (int c = 0; c < cells_; ++c)
    for (int k = 0; k < n; ++k) out[size_t(c) * n + k] = h(c, k);
  return out;
}

double StandaloneCells::total_density() const {
  auto rho = density_;
  double m = 0;
  par_reduce(
      "coagulation::total_density", 0, cells_, 0, grid_.size(),
      KOKKOS_LAMBDA(int c, int k, double& s) { s += rho(c, k); }, m);
  return m / cells_;
}

std::string StandaloneCells::summary() const {
  return logging::format("mass error = %.3e, substeps = %lld, rejections = %lld", (total_density() - total0_) / total0_,
                         substeps_, rejections_);
}

}  // namespace mote::coagulation
