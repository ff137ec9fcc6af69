// Coagulation solver: pair-kernel evaluation and per-cell BS32 integration,
// one Kokkos team per cell (RBO24 sec. 5-6). See coagulation.hpp.
#include "mote/coagulation/coagulation.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "mote/coagulation/bs32.hpp"
#include "mote/coagulation/cell_rates.hpp"
#include "mote/core/loops.hpp"
#include "mote/core/units.hpp"

namespace mote::coagulation {

namespace detail {

using TeamPolicy = Kokkos::TeamPolicy<ExecSpace>;
using Member = TeamPolicy::member_type;
using Scratch = Kokkos::View<Real*, ExecSpace::scratch_memory_space, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;
constexpr int kBs32Arrays = 7;  // y and the six Bs32Work arrays

/// Team scratch of one cell's BS32 integration: the state arrays and the rates' work arrays.
std::size_t integrate_scratch_bytes(int species) {
  return (kBs32Arrays + CellRates::scratch_per_species) * Scratch::shmem_size(species);
}

/// One team per cell: `team_size` threads, or Kokkos's choice (Kokkos::AUTO) for 0.
TeamPolicy cell_teams(int count, int team_size) {
  return team_size > 0 ? TeamPolicy(count, team_size) : TeamPolicy(count, Kokkos::AUTO);
}

template <class Kernel>
bool uses_fragmentation(const Kernel& kernel) {
  if constexpr (std::is_same_v<Kernel, PhysicalKernel>) return kernel.fragmentation;
  return false;
}

/// One reduction for a call's totals (four would each wait for the device):
/// sums of the sub-step counts and failures, the minimum proposed next sub-step
/// (the largest Real where no cell proposes one).
class CallTotals {
 public:
  using reducer = CallTotals;
  using value_type = CallStatistics;
  using result_view_type = Kokkos::View<value_type, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;

  explicit CallTotals(value_type& result) : result_(&result) {}

  KOKKOS_INLINE_FUNCTION void join(value_type& dest, const value_type& src) const {
    dest.substeps += src.substeps;
    dest.rejections += src.rejections;
    dest.failed_cells += src.failed_cells;
    dest.min_next_substep = math::min(dest.min_next_substep, src.min_next_substep);
  }
#if KOKKOS_VERSION < 40000  // Kokkos 3 joins volatile partial results as well
  KOKKOS_INLINE_FUNCTION void join(volatile value_type& dest, const volatile value_type& src) const {
    dest.substeps += src.substeps;
    dest.rejections += src.rejections;
    dest.failed_cells += src.failed_cells;
    dest.min_next_substep = math::min(dest.min_next_substep, src.min_next_substep);
  }
#endif
  KOKKOS_INLINE_FUNCTION void init(value_type& v) const {
    v.substeps = 0;
    v.rejections = 0;
    v.failed_cells = 0;
    v.min_next_substep = Kokkos::reduction_identity<Real>::min();
  }
  KOKKOS_INLINE_FUNCTION value_type& reference() const { return *result_.data(); }
  KOKKOS_INLINE_FUNCTION result_view_type view() const { return result_; }
  KOKKOS_INLINE_FUNCTION bool references_scalar() const { return true; }

 private:
  result_view_type result_;
};

}  // namespace detail

AnyKernel make_kernel(const CoagulationSettings& s, const MassGrid& grid, const GasCells& gas) {
  if (s.kernel == "constant") return ConstantKernel{{}, s.kernel_coefficient};
  if (s.kernel == "additive") return AdditiveKernel{{}, s.kernel_coefficient, grid.mass_view()};
  if (s.kernel == "product") return ProductKernel{{}, s.kernel_coefficient, grid.mass_view()};
  PhysicalKernel k;
  k.mass = grid.mass_view();
  k.size = grid.size_view();
  k.gas = gas;
  k.rho_m = grid.rho_m();
  k.mu_mH = s.mu * units::cgs::m_H;
  k.v_frag = s.v_frag;
  k.vertically_integrated = s.vertically_integrated;
  k.fragmentation = s.fragmentation;
  return k;
}

Coagulation::Coagulation(const MassGrid& grid, const CoagulationSettings& settings, int cells)
    : grid_(grid), settings_(settings), cells_(cells) {
  // A GPU holds a team's scratch in its shared memory: Kokkos 4.6 CUDA offers the block's 48 KiB less
  // 8 KiB it keeps for team reductions, 40,936 bytes, some 465 species; a host has no such limit.
  constexpr bool host_backend = Kokkos::SpaceAccessibility<Kokkos::HostSpace, ExecSpace::memory_space>::accessible;
  const std::size_t scratch = detail::integrate_scratch_bytes(grid_.size());
  const std::size_t scratch_max = detail::TeamPolicy::scratch_size_max(0);
  if (!host_backend && scratch > scratch_max)
    throw std::invalid_argument("coagulation: " + std::to_string(grid_.size()) + " species need " +
                                std::to_string(scratch) + " bytes of team scratch per cell; the " + ExecSpace::name() +
                                " back-end holds " + std::to_string(scratch_max));
  batch_ = std::max(1, std::min(cells_, settings_.cells_per_batch));
  team_size_ = settings_.team_size;
  if (host_backend && team_size_ > ExecSpace().concurrency())
    throw std::invalid_argument("coagulation.team_size = " + std::to_string(team_size_) + " exceeds the " +
                                std::to_string(ExecSpace().concurrency()) + " threads of the host back-end");
  tables_ = build_collision_tables(grid_, settings_.chi_im, settings_.fragment_slope,
                                   product_split_from_name(settings_.product_split));
  k_coag_ = PairCoefficients("coagulation::k_coag", batch_, tables_.pairs);
  k_frag_ = PairCoefficients("coagulation::k_frag", batch_, tables_.pairs);
  next_substep_ = RealView1("coagulation::next_substep", cells_);
  substeps_ = IntView1("coagulation::substeps", cells_);
  rejections_ = IntView1("coagulation::rejections", cells_);
  failed_ = IntView1("coagulation::failed", cells_);
}

template <class Kernel>
void Coagulation::evaluate_pairs(int first, int count, const Kernel& kernel) {
  using SpeciesScratch =
      Kokkos::View<typename Kernel::Species*, ExecSpace::scratch_memory_space, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;
  auto kc = k_coag_;
  auto kf = k_frag_;
  auto pi = tables_.pair_i;
  auto pj = tables_.pair_j;
  const int pairs = tables_.pairs, n = tables_.species;
  const auto policy =
      detail::cell_teams(count, team_size_).set_scratch_size(0, Kokkos::PerTeam(SpeciesScratch::shmem_size(n)));
  Kokkos::parallel_for(
      "coagulation::pair_kernels", policy, KOKKOS_LAMBDA(const detail::Member& team) {
        const int lc = team.league_rank(), c = first + lc;
        const auto cell = kernel.cell(c);
        const SpeciesScratch species(team.team_scratch(0), n);
        Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) { species(k) = kernel.species(cell, k); });
        team.team_barrier();
        Kokkos::parallel_for(Kokkos::TeamThreadRange(team, pairs), [&](int p) {
          const int i = pi(p), j = pj(p);
          const PairRate r = kernel.pair(cell, c, i, j, species(i), species(j));
          const Real half = i == j ? 0.5 : 1.0;
          const Real pf = math::min(math::max(r.p_frag, Real(0)), Real(1));
          kc(lc, p) = half * r.K * (1.0 - pf);
          kf(lc, p) = half * r.K * pf;
        });
      });
  debug_fence("coagulation::pair_kernels");
}

template <class Kernel>
CallStatistics Coagulation::integrate_with(const RealView2& density, Real dt, const Kernel& kernel) {
  const int n = tables_.species;
  const size_t bytes = detail::integrate_scratch_bytes(n);
  Bs32Options base;
  base.rel_tol = settings_.rel_tol;
  base.max_steps = settings_.max_substeps;
  const Real abs_factor = settings_.abs_tol;
  auto next = next_substep_;
  auto steps = substeps_;
  auto rejected = rejections_;
  auto failed = failed_;
  for (int first = 0; first < cells_; first += batch_) {
    const int count = std::min(batch_, cells_ - first);
    evaluate_pairs(first, count, kernel);
    const CellRates rates(tables_, k_coag_, k_frag_, detail::uses_fragmentation(kernel));
    const auto policy = detail::cell_teams(count, team_size_).set_scratch_size(0, Kokkos::PerTeam(bytes));
    Kokkos::parallel_for(
        "coagulation::integrate", policy, KOKKOS_LAMBDA(const detail::Member& team) {
          const int lc = team.league_rank(), c = first + lc;
          const auto& scratch = team.team_scratch(0);
          const detail::Scratch y(scratch, n), nd(scratch, n), bucket(scratch, n), theta(scratch, 2 * n);
          const Bs32Work<detail::Scratch> work{detail::Scratch(scratch, n), detail::Scratch(scratch, n),
                                               detail::Scratch(scratch, n), detail::Scratch(scratch, n),
                                               detail::Scratch(scratch, n), detail::Scratch(scratch, n)};
          Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) { y(k) = density(c, k); });
          team.team_barrier();
          Real total = 0;
          Kokkos::parallel_reduce(
              Kokkos::TeamThreadRange(team, n), [&](int k, Real& s) { s += math::fabs(y(k)); }, total);
          Bs32Result r;
          if (total > 0) {
            Bs32Options o = base;
            o.abs_tol = abs_factor * total;
            o.h_init = next(c);
            const auto rhs = [&](const detail::Member& tm, const detail::Scratch& yin, const detail::Scratch& out) {
              rates(tm, lc, yin, out, nd, bucket, theta);
            };
            r = bs32_integrate(team, n, y, dt, o, work, rhs);
            Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) { density(c, k) = y(k); });
          }
          Kokkos::single(Kokkos::PerTeam(team), [&]() {
            next(c) = total > 0 ? r.h_next : 0.0;  // an empty cell proposes nothing
            steps(c) = r.accepted;
            rejected(c) = r.rejected;
            failed(c) = r.ok ? 0 : 1;
          });
        });
    debug_fence("coagulation::integrate");
  }
  CallStatistics stats;
  Kokkos::parallel_reduce(
      "coagulation::call_statistics", Kokkos::RangePolicy<ExecSpace>(0, cells_),
      KOKKOS_LAMBDA(int c, CallStatistics& s) {
        s.substeps += steps(c);
        s.rejections += rejected(c);
        s.failed_cells += failed(c);
        if (next(c) > 0) s.min_next_substep = math::min(s.min_next_substep, next(c));
      },
      detail::CallTotals(stats));
  return stats;
}

template <class Kernel>
void Coagulation::rates_with(const RealView2& density, const Kernel& kernel, const RealView2& dydt) {
  const int n = tables_.species;
  const size_t bytes = (2 + CellRates::scratch_per_species) * detail::Scratch::shmem_size(n);
  for (int first = 0; first < cells_; first += batch_) {
    const int count = std::min(batch_, cells_ - first);
    evaluate_pairs(first, count, kernel);
    const CellRates rates(tables_, k_coag_, k_frag_, detail::uses_fragmentation(kernel));
    const auto policy = detail::cell_teams(count, team_size_).set_scratch_size(0, Kokkos::PerTeam(bytes));
    Kokkos::parallel_for(
        "coagulation::rates", policy, KOKKOS_LAMBDA(const detail::Member& team) {
          const int lc = team.league_rank(), c = first + lc;
          const auto& scratch = team.team_scratch(0);
          const detail::Scratch y(scratch, n), out(scratch, n), nd(scratch, n), bucket(scratch, n),
              theta(scratch, 2 * n);
          Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) { y(k) = density(c, k); });
          team.team_barrier();
          rates(team, lc, y, out, nd, bucket, theta);
          Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) { dydt(c, k) = out(k); });
        });
    debug_fence("coagulation::rates");
  }
}

CallStatistics Coagulation::integrate(const RealView2& density, Real dt, const AnyKernel& kernel) {
  return std::visit([&](const auto& k) { return integrate_with(density, dt, k); }, kernel);
}

void Coagulation::rates(const RealView2& density, const AnyKernel& kernel, const RealView2& dydt) {
  std::visit([&](const auto& k) { rates_with(density, k, dydt); }, kernel);
}

#define MOTE_COAGULATION_INSTANTIATE(K)                                                     \
  template void Coagulation::evaluate_pairs<K>(int, int, const K&);                         \
  template CallStatistics Coagulation::integrate_with<K>(const RealView2&, Real, const K&); \
  template void Coagulation::rates_with<K>(const RealView2&, const K&, const RealView2&);
MOTE_COAGULATION_INSTANTIATE(ConstantKernel)
MOTE_COAGULATION_INSTANTIATE(AdditiveKernel)
MOTE_COAGULATION_INSTANTIATE(ProductKernel)
MOTE_COAGULATION_INSTANTIATE(PhysicalKernel)
#undef MOTE_COAGULATION_INSTANTIATE

}  // namespace mote::coagulation
