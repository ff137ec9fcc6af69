// Dusty particle loops of the one-fluid method (PL15 sec. 3, app. B; HPL18
// sec. 3); see include/mote/sph/one_fluid_dust.hpp.
//   sph::dust_prepare   eps = sum_j eps_j, gas pressure and sound speed (PL15 eq. 14,
//                       HPL18 eq. 31-32), T_sj and tilde T_sj (HPL18 eq. 14-17).
//   sph::dust_forces    momentum (PL15 eq. 25), AV with (1 - eps_a) (eq. 31-32),
//                       conductivity / (1 - eps_a) (eq. 34-35), du/dt (eq. 27 / 45,
//                       HPL18 eq. 55-56) and, for direct second derivatives, the dust
//                       equation PL15 eq. 43 (eps_j, D_j = eps_j tilde T_sj) or HPL18 eq. 51 (S_j).
//   sph::dust_first     two first derivatives: PL15 eq. 26 with (1 - eps) Delta f = -a_hydro
//                       (eq. 29-30), eq. B7 for S_j, and the diffusion part of eq. 27.
// Per-particle gathers over the symmetric neighbour list, no atomics.
#include "mote/core/loops.hpp"
#include "mote/sph/dust_drag.hpp"
#include "mote/sph/eos.hpp"
#include "mote/sph/kernels.hpp"
#include "mote/sph/one_fluid_dust.hpp"

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
  kPackSize = 20
};

template <int Dim, class K>
void dust_forces_impl(OneFluidDust& dust, Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg,
                      const RealView2& vel, const RealView1& u) {
  const int n = p.n;
  const int ns = dust.nspecies();
  const DustSettings& st = dust.settings();
  const bool svar = st.variable == DustVariable::SqrtRhoEps;
  const bool second = st.discretisation == DustDiscretisation::SecondDerivatives;
  const bool energy = cfg.eos == EosType::Adiabatic;
  const bool utilde = energy && st.energy == DustEnergy::UTilde;
  const Real gamma = cfg.gamma;
  const Real gamma_drag = energy ? cfg.gamma : 1.0;
  const Real cs0 = cfg.cs_iso;
  const int law = static_cast<int>(st.drag);
  const Real rho_grain = st.rho_grain;

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
        for (int j = 0; j < ns; ++j) e += svar ? var(a, j) * var(a, j) / rhoa : var(a, j);
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
          Real ej = svar ? var(a, j) * var(a, j) / rhoa : var(a, j);
          ej = ej > 0.0 ? ej : 0.0;
          Real t;
          if (law == static_cast<int>(DragLaw::ConstantK)) {
            t = ts_constant_k(ej, e, rhoa, kdrag(j));
          } else if (law == static_cast<int>(DragLaw::Epstein)) {
            t = ts_epstein(rho_grain, gsize(j), rhoa, cs(a), gamma_drag);
          } else {
            t = tstop(j);
          }
          ts(a, j) = t;
          sum_ts += ej * t;
        }
        eps_ts(a) = sum_ts;
        Real dsum = 0.0;
        for (int j = 0; j < ns; ++j) {
          Real ej = svar ? var(a, j) * var(a, j) / rhoa : var(a, j);
          ej = ej > 0.0 ? ej : 0.0;
          const Real tt = (ts(a, j) - sum_ts) / fg;  // HPL18 eq. 15
          coef(a, j) = svar ? tt : ej * tt;
          dsum += ej * tt;
        }
        d_tot(a) = dsum;
      });

  par_for(
      "sph::dust_pack", 0, n, KOKKOS_LAMBDA(int i) {
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
      });

  par_for(
      "sph::dust_forces", 0, n, KOKKOS_LAMBDA(int a) {
        Real acc_a[3] = {0, 0, 0};
        Real du = 0.0, du_d = 0.0, dv = 0.0, sumc = 0.0;
        const Real csa = pk(a, kCs);
        Real vs = csa;
        if (second)
          for (int j = 0; j < ns; ++j) dvar(a, j) = 0.0;
        if (pk(a, kIsGas) == 0.0) {
          for (int d = 0; d < Dim; ++d) {
            acc(a, d) = 0.0;
            gforce(a, d) = 0.0;
          }
          dudt(a) = 0.0;
          divv(a) = 0.0;
          vsig(a) = vs;
          return;
        }
        Real xa[3] = {0, 0, 0}, va[3] = {0, 0, 0};
        for (int d = 0; d < Dim; ++d) {
          xa[d] = pk(a, kX + d);
          va[d] = pk(a, kV + d);
        }
        const Real ha = pk(a, kH), ha_inv = 1.0 / ha;
        const Real ppfa = pk(a, kPpf), rpfa = pk(a, kRpf), rpfava = pk(a, kRpfAv), acsa = pk(a, kAcs);
        const Real ua = pk(a, kU), Pa = pk(a, kP), rhoa = pk(a, kRho), dta = pk(a, kDtot);
        const Real norm_a = K::norm() * ipow<Dim + 1>(ha_inv);
        const int jend = offsets(a + 1);
        for (int jj = offsets(a); jj < jend; ++jj) {
          const int b = neigh(jj);
          const int img = image(jj);
          Real dx[3] = {0, 0, 0};
          Real r2 = 0.0;
          for (int d = 0; d < Dim; ++d) {
            dx[d] = box.separation(xa[d], pk(b, kX + d), img, d);
            r2 += dx[d] * dx[d];
          }
          if (r2 <= 0.0 || pk(b, kIsGas) == 0.0) continue;
          const Real hb = pk(b, kH), hb_inv = pk(b, kHinv);
          const bool inside = r2 < R * R * ha * ha || r2 < R * R * hb * hb;
          const Real r = math::sqrt(r2);
          const Real rinv = 1.0 / r;
          Real f, dfa, dfb;
          K::shape(r * ha_inv, f, dfa);
          K::shape(r * hb_inv, f, dfb);
          const Real fa = norm_a * dfa;
          const Real fb = K::norm() * ipow<Dim + 1>(hb_inv) * dfb;
          Real vr = 0.0;
          for (int d = 0; d < Dim; ++d) vr += (va[d] - pk(b, kV + d)) * dx[d];
          vr *= rinv;
          const Real vneg = vr < 0.0 ? vr : 0.0;
          // PL15 eq. 31 / HPL18 eq. 57: q_ab,a = -1/2 rho_a (1 - eps_a) v_sig,a v_ab.r_hat.
          const Real qa = -0.5 * rpfava * (acsa - beta * vneg) * vneg;
          const Real qb = -0.5 * pk(b, kRpfAv) * (pk(b, kAcs) - beta * vneg) * vneg;
          const Real mb = pk(b, kM);
          const Real fpair = mb * ((ppfa + qa) * fa + (pk(b, kPpf) + qb) * fb) * rinv;  // PL15 eq. 25
          for (int d = 0; d < Dim; ++d) acc_a[d] -= fpair * dx[d];
          const Real ub = pk(b, kU);
          if (energy) {
            du += mb * (ppfa + qa) * vr * fa;  // (1 - eps_a) du/dt, PL15 eq. 27 first term
            const Real qcond = 0.5 * alpha_u * math::fabs(vr) * (ua - ub);
            du += mb * qcond * (rpfa * fa + pk(b, kRpf) * fb);  // PL15 eq. 34-35
          }
          if (second) {
            const Real rhob = pk(b, kRho);
            const Real fbar_r = 0.5 * (fa + fb) * rinv;
            const Real dP = Pa - pk(b, kP);
            if (!svar) {
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
                const Real t = c * var(b, j) * (coef(a, j) * ira + coef(b, j) * irb);
                dvar(a, j) -= 0.5 * t;
                e += var(a, j) * t;
              }
              du_d -= 0.5 * (ua - ub) * ira * e;
            }
          }
          dv -= mb * vr * fa;
          const Real csb = pk(b, kCs);
          const Real vsab = (csa > csb ? csa : csb) - beta * vneg;
          vs = (inside && vsab > vs) ? vsab : vs;
        }
        if (second && !svar)
          for (int j = 0; j < ns; ++j) dvar(a, j) -= sumc * coef(a, j);
        for (int d = 0; d < Dim; ++d) {
          acc(a, d) = acc_a[d];
          gforce(a, d) = -acc_a[d];
        }
        const Real fg = 1.0 - eps_tot(a);
        dudt(a) = energy ? (utilde ? du : (du + du_d) / fg) : 0.0;
        divv(a) = dv * rpfa;
        vsig(a) = vs;
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
            const int img = image(jj);
            Real dx[3] = {0, 0, 0};
            Real r2 = 0.0;
            for (int d = 0; d < Dim; ++d) {
              dx[d] = box.separation(xa[d], pk(b, kX + d), img, d);
              r2 += dx[d] * dx[d];
            }
            if (r2 <= 0.0 || pk(b, kIsGas) == 0.0) continue;
            const Real r = math::sqrt(r2);
            const Real rinv = 1.0 / r;
            Real f, dfa, dfb;
            K::shape(r * ha_inv, f, dfa);
            const Real hb_inv = pk(b, kHinv);
            K::shape(r * hb_inv, f, dfb);
            const Real fa = norm_a * dfa;
            const Real fb = K::norm() * ipow<Dim + 1>(hb_inv) * dfb;
            Real gra = 0.0, grb = 0.0;
            for (int d = 0; d < Dim; ++d) {
              gra += ga[d] * dx[d];
              grb += gforce(b, d) * dx[d];
            }
            gra *= rinv;
            grb *= rinv;
            const Real mb = pk(b, kM);
            const Real ub = pk(b, kU);
            if (!svar) {
              const Real A = rpfa * gra * fa, B = pk(b, kRpf) * grb * fb;
              sum_a += mb * A;
              for (int j = 0; j < ns; ++j) dvar(a, j) -= mb * B * coef(b, j);
              du_d -= dta * mb * (ua - ub) * A;  // PL15 eq. 27, second term
            } else {
              const Real A = rpf2a * gra * fa, B = pk(b, kRpf2) * grb * fb;
              Real e = 0.0;
              for (int j = 0; j < ns; ++j) {
                const Real sb = var(b, j);
                dvar(a, j) -= 0.5 * rhoa * mb * sb * (coef(a, j) * A + coef(b, j) * B);  // eq. B7
                e += var(a, j) * coef(a, j) * sb;
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
    // S_a / (2 rho_a Omega_a) sum_b m_b v_ab . grad W_ab(h_a) = -S_a div v / 2 (HPL18 eq. 51, PL15 eq. B7).
    par_for(
        "sph::dust_sdivv", 0, n, KOKKOS_LAMBDA(int a) {
          for (int j = 0; j < ns; ++j) dvar(a, j) -= 0.5 * var(a, j) * divv(a);
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

void OneFluidDust::compute_forces(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg,
                                  const RealView2& vel, const RealView1& u) {
  dust_detail::DustForcesDispatch f{*this, p, nl, box, cfg, vel, u};
  dispatch(p.dim, cfg.kernel, f);
}

}  // namespace mote::sph
