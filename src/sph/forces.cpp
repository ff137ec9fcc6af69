// Momentum and energy equations with artificial viscosity and conductivity
// (PL15 eq. 25, 27, 31-32, 34-35); see include/mote/sph/forces.hpp.
#include "mote/sph/forces.hpp"

#include "mote/core/loops.hpp"
#include "mote/sph/eos.hpp"
#include "mote/sph/pair_terms.hpp"

namespace mote::sph {

void update_eos(Particles& p, const SphConfig& cfg, const RealView1& u) {
  const auto rho = p.rho;
  const auto P = p.P;
  const auto cs = p.cs;
  const Real gamma = cfg.gamma;
  const Real cs0 = cfg.cs_iso;
  if (cfg.eos == EosType::Isothermal) {
    par_for(
        "sph::eos_isothermal", 0, p.n, KOKKOS_LAMBDA(int a) {
          P(a) = pressure_isothermal(rho(a), cs0);
          cs(a) = cs0;
        });
  } else {
    par_for(
        "sph::eos_adiabatic", 0, p.n, KOKKOS_LAMBDA(int a) {
          P(a) = pressure_adiabatic(rho(a), u(a), gamma);
          cs(a) = sound_speed_adiabatic(rho(a), P(a), gamma);
        });
  }
}

void update_cullen_dehnen(Particles& p, const RealView1& divv_old, const SphConfig& cfg, Real dt) {
  const auto alpha = p.alpha;
  const auto divv = p.divv;
  const auto h = p.h;
  const auto cs = p.cs;
  const Real amax = cfg.alpha_max;
  const Real amin = cfg.alpha_min;
  par_for(
      "sph::cullen_dehnen", 0, p.n, KOKKOS_LAMBDA(int i) {
        const Real aloc = cullen_dehnen_alpha_loc((divv(i) - divv_old(i)) / dt, h(i), cs(i), amin, amax);
        const Real al = alpha(i);
        // where c_s = 0 alpha keeps its value (tau infinite)
        alpha(i) = aloc >= al ? aloc : aloc + (al - aloc) * math::exp(-dt * 0.1 * cs(i) / h(i));
        divv_old(i) = divv(i);
      });
}

// A named namespace: nvcc requires the functions that enclose extended
// (KOKKOS_LAMBDA) lambdas to have external linkage.
namespace detail {

// Layout of the packed per-particle data read for every neighbour b.
enum PackSlot : int {
  kSlotX = 0,         // x (3)
  kSlotV = 3,         // v (3)
  kSlotH = 6,         // h
  kSlotM = 7,         // m
  kSlotPpf = 8,       // P / (Omega rho^2)
  kSlotRpf = 9,       // rho / (Omega rho^2)
  kSlotAcs = 10,      // alpha c_s
  kSlotCs = 11,       // c_s
  kSlotU = 12,        // u
  kSlotGas = 13,      // 1 for gas particles, 0 otherwise
  kSlotHinv = 14,     // 1 / h
  kSlotPackSize = 16  // two cache lines
};

template <int Dim, class K, bool Energy>
void forces_impl(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg, const RealView2& vel,
                 const RealView1& u) {
  const int n = p.n;
  if (p.gather_pack.extent(0) != static_cast<std::size_t>(n)) {
    p.gather_pack = decltype(p.gather_pack)(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::gather_pack"), n,
                                            static_cast<int>(kSlotPackSize));
  }
  const auto pk = p.gather_pack;
  const auto x = p.x;
  const auto m = p.m;
  const auto h = p.h;
  const auto rho = p.rho;
  const auto omega = p.omega;
  const auto P = p.P;
  const auto cs = p.cs;
  const auto alpha = p.alpha;
  const auto type = p.type;
  const auto acc = p.a;
  const auto dudt = p.dudt;
  const auto divv = p.divv;
  const auto vsig = p.vsig;
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const auto image = nl.image;
  const Real beta = cfg.beta;
  const Real alpha_u = cfg.alpha_u;
  const Real R = K::radius();

  par_for(
      "sph::forces_pack", 0, n, KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < Dim; ++d) {
          pk(i, kSlotX + d) = x(i, d);
          pk(i, kSlotV + d) = vel(i, d);
        }
        const Real pf = 1.0 / (omega(i) * rho(i) * rho(i));
        pk(i, kSlotH) = h(i);
        pk(i, kSlotHinv) = 1.0 / h(i);
        pk(i, kSlotM) = m(i);
        pk(i, kSlotPpf) = P(i) * pf;
        pk(i, kSlotRpf) = rho(i) * pf;
        pk(i, kSlotAcs) = alpha(i) * cs(i);
        pk(i, kSlotCs) = cs(i);
        pk(i, kSlotU) = u(i);
        pk(i, kSlotGas) = type(i) == kGas ? 1.0 : 0.0;
      });

  par_for(
      "sph::forces", 0, n, KOKKOS_LAMBDA(int a) {
        HydroSums sum(pk(a, kSlotCs));
        if (pk(a, kSlotGas) == 0.0) {
          for (int d = 0; d < Dim; ++d) acc(a, d) = 0.0;
          dudt(a) = 0.0;
          divv(a) = 0.0;
          vsig(a) = sum.vs;
          return;
        }
        Real xa[3] = {0, 0, 0}, va[3] = {0, 0, 0};
        for (int d = 0; d < Dim; ++d) {
          xa[d] = pk(a, kSlotX + d);
          va[d] = pk(a, kSlotV + d);
        }
        const Real ha = pk(a, kSlotH), ha_inv = 1.0 / ha;
        const Real rpfa = pk(a, kSlotRpf);
        const HydroSide sa{pk(a, kSlotPpf), rpfa, pk(a, kSlotAcs), rpfa, pk(a, kSlotU), pk(a, kSlotCs)};
        const Real norm_a = K::norm() * ipow<Dim + 1>(ha_inv);
        const int jend = offsets(a + 1);
        for (int j = offsets(a); j < jend; ++j) {
          const int b = neigh(j);
          PairGeometry<Dim, K> g;
          if (!g.separate(box, xa, pk, kSlotX, b, image(j)) || pk(b, kSlotGas) == 0.0) continue;
          // Branch-free from here: pairs in the list skin beyond both supports
          // get F = 0 from the kernels and are excluded from v_sig by a select.
          const Real hb = pk(b, kSlotH);
          const bool inside = g.r2 < R * R * ha * ha || g.r2 < R * R * hb * hb;
          g.gradients(ha_inv, norm_a, pk(b, kSlotHinv));
          g.approach(va, pk, kSlotV, b);
          const Real rpfb = pk(b, kSlotRpf);
          const HydroSide sb{pk(b, kSlotPpf), rpfb, pk(b, kSlotAcs), rpfb, pk(b, kSlotU), pk(b, kSlotCs)};
          sum.add<Energy>(g, inside, sa, sb, pk(b, kSlotM), beta, alpha_u);
        }
        for (int d = 0; d < Dim; ++d) acc(a, d) = sum.acc[d];
        dudt(a) = Energy ? sum.du : 0.0;
        divv(a) = sum.dv * rpfa;  // -(1 / (Omega_a rho_a)) sum m_b v_ab . grad W(h_a)
        vsig(a) = sum.vs;
      });
}

template <int Dim, class K>
long long pairs_impl(const Particles& p, const NeighbourList& nl, const Box& box) {
  const auto x = p.x;
  const auto h = p.h;
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const auto image = nl.image;
  const Real R = K::radius();
  long long total = 0;
  par_reduce(
      "sph::count_pairs", 0, p.n,
      KOKKOS_LAMBDA(int a, long long& c) {
        for (int j = offsets(a); j < offsets(a + 1); ++j) {
          const int b = neigh(j);
          Real r2 = 0.0;
          for (int d = 0; d < Dim; ++d) {
            const Real dx = box.separation(x(a, d), x(b, d), image(j), d);
            r2 += dx * dx;
          }
          const Real hm = h(a) > h(b) ? h(a) : h(b);
          if (r2 < R * R * hm * hm) ++c;
        }
      },
      total);
  return total;
}

struct ForcesDispatch {
  Particles& p;
  const NeighbourList& nl;
  const Box& box;
  const SphConfig& cfg;
  const RealView2& vel;
  const RealView1& u;
  template <int Dim, class K>
  void operator()() {
    if (cfg.eos == EosType::Adiabatic)
      forces_impl<Dim, K, true>(p, nl, box, cfg, vel, u);
    else
      forces_impl<Dim, K, false>(p, nl, box, cfg, vel, u);
  }
};

struct PairsDispatch {
  const Particles& p;
  const NeighbourList& nl;
  const Box& box;
  long long result = 0;
  template <int Dim, class K>
  void operator()() {
    result = pairs_impl<Dim, K>(p, nl, box);
  }
};

}  // namespace detail

void compute_forces(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg, const RealView2& vel,
                    const RealView1& u) {
  detail::ForcesDispatch f{p, nl, box, cfg, vel, u};
  dispatch(p.dim, cfg.kernel, f);
}

long long count_interacting_pairs(const Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg) {
  detail::PairsDispatch f{p, nl, box};
  dispatch(p.dim, cfg.kernel, f);
  return f.result;
}

}  // namespace mote::sph
