// Dusty particle loops of the one-fluid method (PL15 sec. 3, app. B; HPL18
// sec. 3); see include/mote/sph/one_fluid_dust.hpp.
//   sph::dust_prepare   eps = sum_j eps_j, gas pressure and sound speed (PL15 eq. 14,
//                       HPL18 eq. 31-32), T_sj (with dust.limit_stopping_time at most h / c_s,
//                       Ballabio et al. 2018) and tilde T_sj (HPL18 eq. 14-17).
//   sph::dust_forces    momentum (PL15 eq. 25), AV with (1 - eps_a) (eq. 31-32),
//                       conductivity / (1 - eps_a) (eq. 34-35), du/dt (eq. 27 / 45,
//                       HPL18 eq. 55-56; with dust.pdv = "gas" the div v_g + drag heating
//                       term as PL15 eq. 43 with D' = P D / rho_g) and, for direct second derivatives, the dust
//                       equation PL15 eq. 43 (eps_j, D_j = eps_j tilde T_sj; optionally with the
//                       pair coefficient limited to 2 D of the donor, so eps_j >= 0) or HPL18
//                       eq. 51 (S_j, stored as S_j / sqrt(rho)).
//   sph::dust_first     two first derivatives: PL15 eq. 26 with (1 - eps) Delta f = -a_hydro
//                       (eq. 29-30), eq. B7 for S_j, and the diffusion part of eq. 27.
// Per-particle gathers over the symmetric neighbour list, no atomics.
#include "mote/core/loops.hpp"
#include "mote/sph/dust_drag.hpp"
#include "mote/sph/eos.hpp"
#include "mote/sph/kernels.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/pair_terms.hpp"

namespace mote::sph {

namespace dust_detail {

enum DustSlot : int {
  kX = 0,  // x (3)
  kV = 3,  // v (3)
  kH = 6,
  kHinv = 7,
  kM = 8,
  kPpf = 9,     // P / (Omega rho^2)
  kRpf = 10,    // 1 / (Omega rho)
  kRpfAv = 11,  // (1 - eps) / (Omega rho)  (AV, PL15 eq. 31)
  kAcs = 12,    // alpha c_s
  kCs = 13,
  kU = 14,  // gas u
  kIsGas = 15,
  kP = 16,
  kRho = 17,
  kDtot = 18,  // sum_j eps_j tilde T_sj
  kRpf2 = 19,  // 1 / (Omega rho^2)
  kDgas = 20,  // P sum_j eps_j tilde T_sj / rho_g  (dust.pdv = "gas")
  kPackSize = 21
};

template <int Dim, class K>
void dust_forces_impl(OneFluidDust& dust, Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg,
                      const RealView2& vel, const RealView1& u) {
  const int n = p.n;
  const int ns = dust.nspecies();
  const DustSettings& st = dust.settings();
  const bool svar = st.variable == DustVariable::SqrtRhoEps;
  const bool second = st.discretisation == DustDiscretisation::SecondDerivatives;
  const bool limited = st.flux == DustFlux::DonorLimited;
  const bool energy = cfg.eos == EosType::Adiabatic;
  const bool utilde = energy && st.energy == DustEnergy::UTilde;
  const bool gas_pdv = energy && st.pdv == DustPdV::Gas;
  const Real gamma = cfg.gamma;
  const Real gamma_drag = energy ? cfg.gamma : 1.0;
  const Real cs0 = cfg.cs_iso;
  const int law = static_cast<int>(st.drag);
  const Real rho_grain = st.rho_grain;
  const bool limit_ts = st.limit_ts;

  if (dust.pack.extent(0) != static_cast<std::size_t>(n)) {
    dust.pack = decltype(dust.pack)(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::dust_pack"), n,
                                    static_cast<int>(kPackSize));
  }
  const auto pk = dust.pack;
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
  const auto var = dust.var_pred;
  const auto sv = svar ? dust.s_pairs : var;  // S_j = sqrt(rho) q_j in the pair terms (S variable)
  const auto dvar = dust.dvar;
  const auto ts = dust.ts;
  const auto coef = dust.coef;
  const auto eps_tot = dust.eps_tot;
  const auto eps_ts = dust.eps_ts;
  const auto d_tot = dust.d_tot;
  const auto uloc = dust.uloc;
  const auto gforce = dust.gforce;
  const auto kdrag = dust.kdrag_view();
  const auto gsize = dust.size_view();
  const auto tstop = dust.tstop_view();
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const auto image = nl.image;
  const Real beta = cfg.beta;
  const Real alpha_u = cfg.alpha_u;
  const Real R = K::radius();

  // EOS from the gas density and drag times (PL15 eq. 14; HPL18 eq. 14-17, 31-32).
  par_for(
      "sph::dust_prepare", 0, n, KOKKOS_LAMBDA(int a) {
        const Real rhoa = rho(a);
        Real e = 0.0;
        for (int j = 0; j < ns; ++j) e += svar ? var(a, j) * var(a, j) : var(a, j);
        const Real fg = 1.0 - e;  // gas fraction
        eps_tot(a) = e;
        Real ua = 0.0;
        if (!energy) {
          P(a) = pressure_isothermal(fg * rhoa, cs0);
          cs(a) = cs0;
        } else if (utilde) {
          P(a) = pressure_adiabatic(rhoa, u(a), gamma);  // HPL18 eq. 32
          ua = u(a) / fg;
          cs(a) = sound_speed_adiabatic(fg * rhoa, P(a), gamma);
        } else {
          ua = u(a);
          P(a) = pressure_adiabatic(fg * rhoa, ua, gamma);  // PL15 eq. 14
          cs(a) = sound_speed_adiabatic(fg * rhoa, P(a), gamma);
        }
        uloc(a) = ua;
        Real sum_ts = 0.0;
        for (int j = 0; j < ns; ++j) {
          Real ej = svar ? var(a, j) * var(a, j) : var(a, j);
          ej = ej > 0.0 ? ej : 0.0;
          Real t;
          if (law == static_cast<int>(DragLaw::ConstantK)) {
            t = ts_constant_k(ej, e, rhoa, kdrag(j));
          } else if (law == static_cast<int>(DragLaw::Epstein)) {
            t = ts_epstein(rho_grain, gsize(j), rhoa, cs(a), gamma_drag);
          } else {
            t = tstop(j);
          }
          if (limit_ts && t * cs(a) > h(a)) t = h(a) / cs(a);  // Ballabio et al. (2018)
          ts(a, j) = t;
          sum_ts += ej * t;
        }
        eps_ts(a) = sum_ts;
        Real dsum = 0.0;
        for (int j = 0; j < ns; ++j) {
          Real ej = svar ? var(a, j) * var(a, j) : var(a, j);
          ej = ej > 0.0 ? ej : 0.0;
          const Real tt = (ts(a, j) - sum_ts) / fg;  // HPL18 eq. 15
          coef(a, j) = svar ? tt : ej * tt;
          dsum += ej * tt;
        }
        d_tot(a) = dsum;
      });

  par_for(
      "sph::dust_pack", 0, n, KOKKOS_LAMBDA(int i) {
        if (svar)
          for (int j = 0; j < ns; ++j) sv(i, j) = var(i, j) * math::sqrt(rho(i));
        for (int d = 0; d < Dim; ++d) {
          pk(i, kX + d) = x(i, d);
          pk(i, kV + d) = vel(i, d);
        }
        const Real rpf = 1.0 / (omega(i) * rho(i));
        pk(i, kH) = h(i);
        pk(i, kHinv) = 1.0 / h(i);
        pk(i, kM) = m(i);
        pk(i, kPpf) = P(i) * rpf / rho(i);
        pk(i, kRpf) = rpf;
        pk(i, kRpfAv) = (1.0 - eps_tot(i)) * rpf;
        pk(i, kAcs) = alpha(i) * cs(i);
        pk(i, kCs) = cs(i);
        pk(i, kU) = uloc(i);
        pk(i, kIsGas) = type(i) == ParticleType::kGas ? 1.0 : 0.0;
        pk(i, kP) = P(i);
        pk(i, kRho) = rho(i);
        pk(i, kDtot) = d_tot(i);
        pk(i, kRpf2) = rpf / rho(i);
        pk(i, kDgas) = P(i) * d_tot(i) / ((1.0 - eps_tot(i)) * rho(i));
      });

  par_for(
      "sph::dust_forces", 0, n, KOKKOS_LAMBDA(int a) {
        Real du_d = 0.0, du_w = 0.0, sumc = 0.0;
        HydroSums sum(pk(a, kCs));
        if (second)
          for (int j = 0; j < ns; ++j) dvar(a, j) = 0.0;
        if (pk(a, kIsGas) == 0.0) {
          for (int d = 0; d < Dim; ++d) {
            acc(a, d) = 0.0;
            gforce(a, d) = 0.0;
          }
          dudt(a) = 0.0;
          divv(a) = 0.0;
          vsig(a) = sum.vs;
          return;
        }
        Real xa[3] = {0, 0, 0}, va[3] = {0, 0, 0};
        for (int d = 0; d < Dim; ++d) {
          xa[d] = pk(a, kX + d);
          va[d] = pk(a, kV + d);
        }
        const Real ha = pk(a, kH), ha_inv = 1.0 / ha;
        const Real rpfa = pk(a, kRpf);
        const Real ua = pk(a, kU), Pa = pk(a, kP), rhoa = pk(a, kRho), dta = pk(a, kDtot), dga = pk(a, kDgas);
        // AV with (1 - eps): PL15 eq. 31 / HPL18 eq. 57; (1 - eps_a) du/dt: PL15 eq. 27 first term.
        const HydroSide sa{pk(a, kPpf), pk(a, kRpfAv), pk(a, kAcs), rpfa, ua, pk(a, kCs)};
        const Real norm_a = K::norm() * ipow<Dim + 1>(ha_inv);
        const int jend = offsets(a + 1);
        for (int jj = offsets(a); jj < jend; ++jj) {
          const int b = neigh(jj);
          PairGeometry<Dim, K> g;
          if (!g.separate(box, xa, pk, kX, b, image(jj)) || pk(b, kIsGas) == 0.0) continue;
          const Real hb = pk(b, kH);
          const bool inside = g.r2 < R * R * ha * ha || g.r2 < R * R * hb * hb;
          g.gradients(ha_inv, norm_a, pk(b, kHinv));
          g.approach(va, pk, kV, b);
          const Real ub = pk(b, kU);
          const HydroSide sb{pk(b, kPpf), pk(b, kRpfAv), pk(b, kAcs), pk(b, kRpf), ub, pk(b, kCs)};
          const Real mb = pk(b, kM);
          sum.add(g, inside, sa, sb, mb, beta, alpha_u, energy);
          if (gas_pdv) {
            // (1 - eps_a) du_a/dt += (1/rho) div(D' grad P), D' = P D / rho_g, in the form of PL15 eq. 43.
            du_w += mb / (rhoa * pk(b, kRho)) * (Pa - pk(b, kP)) * 0.5 * (g.fa + g.fb) * g.rinv * (dga + pk(b, kDgas));
          }
          if (second) {
            const Real rhob = pk(b, kRho);
            const Real fbar_r = 0.5 * (g.fa + g.fb) * g.rinv;
            const Real dP = Pa - pk(b, kP);
            if (!svar && limited) {
              // PL15 eq. 43 with D_j,a + D_j,b limited to 2 D_j of the particle the dust leaves
              // (the donor): an empty particle loses no dust, so eps_j stays >= 0.
              const Real c = mb / (rhoa * rhob) * dP * fbar_r;
              Real dsum = 0.0;
              for (int j = 0; j < ns; ++j) {
                const Real ca = coef(a, j), cb = coef(b, j);
                const Real donor = 2.0 * (c * (ca + cb) > 0.0 ? ca : cb);
                const Real d = math::fabs(ca + cb) < math::fabs(donor) ? ca + cb : donor;
                dvar(a, j) -= c * d;
                dsum += d;
              }
              du_d -= 0.5 * c * (ua - ub) * dsum;  // PL15 eq. 45 with the same coefficient
            } else if (!svar) {
              // PL15 eq. 43: d eps_j,a/dt = -sum_b m_b / (rho_a rho_b) (D_j,a + D_j,b)(P_a - P_b) Fbar / r.
              const Real c = mb / (rhoa * rhob) * dP * fbar_r;
              sumc += c;
              for (int j = 0; j < ns; ++j) dvar(a, j) -= c * coef(b, j);
              // (1 - eps_a) du/dt diffusion part (PL15 eq. 45, sign from eq. 41).
              du_d -= 0.5 * c * (ua - ub) * (dta + pk(b, kDtot));
            } else {
              // HPL18 eq. 51 and the diffusion part of eq. 56.
              const Real c = mb / rhob * dP * fbar_r;
              const Real ira = 1.0 / rhoa, irb = 1.0 / rhob;
              Real e = 0.0;
              for (int j = 0; j < ns; ++j) {
                const Real t = c * sv(b, j) * (coef(a, j) * ira + coef(b, j) * irb);
                dvar(a, j) -= 0.5 * t;
                e += sv(a, j) * t;
              }
              du_d -= 0.5 * (ua - ub) * ira * e;
            }
          }
        }
        if (second && !svar && !limited)
          for (int j = 0; j < ns; ++j) dvar(a, j) -= sumc * coef(a, j);
        for (int d = 0; d < Dim; ++d) {
          acc(a, d) = sum.acc[d];
          gforce(a, d) = -sum.acc[d];
        }
        const Real fg = 1.0 - eps_tot(a);
        dudt(a) = energy ? (utilde ? sum.du + du_w : (sum.du + du_d + du_w) / fg) : 0.0;
        divv(a) = sum.dv * rpfa;
        vsig(a) = sum.vs;
      });

  if (!second) {
    // Two first derivatives: PL15 eq. 26 / B7 with (1 - eps) Delta f = -a_hydro (eq. 29-30).
    par_for(
        "sph::dust_first", 0, n, KOKKOS_LAMBDA(int a) {
          for (int j = 0; j < ns; ++j) dvar(a, j) = 0.0;
          if (pk(a, kIsGas) == 0.0) return;
          Real xa[3] = {0, 0, 0}, ga[3] = {0, 0, 0};
          for (int d = 0; d < Dim; ++d) {
            xa[d] = pk(a, kX + d);
            ga[d] = gforce(a, d);
          }
          const Real ha_inv = pk(a, kHinv);
          const Real norm_a = K::norm() * ipow<Dim + 1>(ha_inv);
          const Real rpfa = pk(a, kRpf), rpf2a = pk(a, kRpf2), ua = pk(a, kU), rhoa = pk(a, kRho), dta = pk(a, kDtot);
          Real sum_a = 0.0, du_d = 0.0;
          const int jend = offsets(a + 1);
          for (int jj = offsets(a); jj < jend; ++jj) {
            const int b = neigh(jj);
            PairGeometry<Dim, K> g;
            if (!g.separate(box, xa, pk, kX, b, image(jj)) || pk(b, kIsGas) == 0.0) continue;
            g.gradients(ha_inv, norm_a, pk(b, kHinv));
            Real gra = 0.0, grb = 0.0;
            for (int d = 0; d < Dim; ++d) {
              gra += ga[d] * g.dx[d];
              grb += gforce(b, d) * g.dx[d];
            }
            gra *= g.rinv;
            grb *= g.rinv;
            const Real mb = pk(b, kM);
            const Real ub = pk(b, kU);
            if (!svar) {
              const Real A = rpfa * gra * g.fa, B = pk(b, kRpf) * grb * g.fb;
              sum_a += mb * A;
              for (int j = 0; j < ns; ++j) dvar(a, j) -= mb * B * coef(b, j);
              du_d -= dta * mb * (ua - ub) * A;  // PL15 eq. 27, second term
            } else {
              const Real A = rpf2a * gra * g.fa, B = pk(b, kRpf2) * grb * g.fb;
              Real e = 0.0;
              for (int j = 0; j < ns; ++j) {
                const Real sb = sv(b, j);
                dvar(a, j) -= 0.5 * rhoa * mb * sb * (coef(a, j) * A + coef(b, j) * B);  // eq. B7
                e += sv(a, j) * coef(a, j) * sb;
              }
              du_d -= mb * (ua - ub) * A * e;
            }
          }
          if (!svar)
            for (int j = 0; j < ns; ++j) dvar(a, j) -= sum_a * coef(a, j);
          if (energy && !utilde) dudt(a) += du_d / (1.0 - eps_tot(a));
        });
  }

  if (svar) {
    // The stored variable is q_j = S_j / sqrt(rho) = sqrt(eps_j): dq/dt = (dS/dt)_pairs / sqrt(rho).
    // The last term of HPL18 eq. 51 / PL15 eq. B7, S_a / (2 rho_a Omega_a) sum_b m_b v_ab . grad W_ab
    // = (S / 2) dln(rho)/dt, is the change of S at fixed eps: integrated exactly by storing q.
    par_for(
        "sph::dust_dq", 0, n, KOKKOS_LAMBDA(int a) {
          const Real r = 1.0 / math::sqrt(rho(a));
          for (int j = 0; j < ns; ++j) dvar(a, j) *= r;
        });
  }
}

struct DustForcesDispatch {
  OneFluidDust& dust;
  Particles& p;
  const NeighbourList& nl;
  const Box& box;
  const SphConfig& cfg;
  const RealView2& vel;
  const RealView1& u;
  template <int Dim, class K>
  void operator()() {
    dust_forces_impl<Dim, K>(dust, p, nl, box, cfg, vel, u);
  }
};

}  // namespace dust_detail

void OneFluidDust::mixture_forces(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg,
                                  const RealView2& vel, const RealView1& u) {
  dust_detail::DustForcesDispatch f{*this, p, nl, box, cfg, vel, u};
  dispatch(p.dim, cfg.kernel, f);
}

}  // namespace mote::sph
