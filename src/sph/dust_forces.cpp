// Dusty particle loops of the one-fluid method (PL15 sec. 3, app. B; HPL18
// sec. 3); see include/mote/sph/one_fluid_dust.hpp.
//   sph::dust_prepare   eps = sum_j eps_j, gas pressure and sound speed (PL15 eq. 14,
//                       HPL18 eq. 31-32), T_sj (with dust.limit_stopping_time at most h / c_s,
//                       Ballabio et al. 2018) and tilde T_sj (HPL18 eq. 14-17).
//   sph::dust_pack      the per-particle factors of the pair terms.
//   sph::dust_forces    momentum (PL15 eq. 25), AV with (1 - eps_a) (eq. 31-32),
//                       conductivity / (1 - eps_a) (eq. 34-35), du/dt (eq. 27 / 45,
//                       HPL18 eq. 55-56; with dust.pdv = "gas" the div v_g + drag heating
//                       term as PL15 eq. 43 with D' = P D / rho_g) and, for direct second derivatives, the dust
//                       equation PL15 eq. 43 (eps_j, D_j = eps_j tilde T_sj; optionally with the
//                       pair coefficient limited to 2 D of the donor, so eps_j >= 0) or HPL18
//                       eq. 51 (S_j, stored as S_j / sqrt(rho)).
//   sph::dust_first     two first derivatives: PL15 eq. 26 with (1 - eps) Delta f = -a_hydro
//                       (eq. 29-30), eq. B7 for S_j, and the diffusion part of eq. 27.
//   sph::dust_dq        dS/dt -> dq/dt for the S variable.
// Per-particle gathers over the symmetric neighbour list, no atomics. The
// deck's choices (dust variable, discretisation and pair coefficient, energy
// equation, PdV form, drag law, stopping-time limiter) are template parameters
// of the loops, chosen once per call by run_loops(): no kernel branches on them.
#include <type_traits>

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

/// The dust equation's term inside the force loop: none (two first
/// derivatives, sph::dust_first), PL15 eq. 43 with D_a + D_b, the same with the
/// donor-limited coefficient, or HPL18 eq. 51 (S variable).
enum class DustTerm : int { None, EpsMean, EpsDonor, SqrtRhoEps };
/// The gas energy equation: none (isothermal), u (PL15 eq. 27) or u~ = (1 - eps) u (HPL18 eq. 55).
enum class GasEnergy : int { None, U, UTilde };

/// The run-time choices of the deck, read once per call.
struct Shape {
  bool svar;
  DustTerm term;
  GasEnergy energy;
  bool gas_pdv;
  bool limit_ts;
  DragLaw law;
};

Shape shape_of(const DustSettings& st, const SphConfig& cfg) {
  Shape s{};
  s.svar = st.variable == DustVariable::SqrtRhoEps;
  if (st.discretisation == DustDiscretisation::FirstDerivatives)
    s.term = DustTerm::None;
  else if (s.svar)
    s.term = DustTerm::SqrtRhoEps;
  else
    s.term = st.flux == DustFlux::DonorLimited ? DustTerm::EpsDonor : DustTerm::EpsMean;
  const bool adiabatic = cfg.eos == EosType::Adiabatic;
  s.energy = !adiabatic ? GasEnergy::None : (st.energy == DustEnergy::UTilde ? GasEnergy::UTilde : GasEnergy::U);
  s.gas_pdv = adiabatic && st.pdv == DustPdV::Gas;
  s.limit_ts = st.limit_ts;
  s.law = st.drag;
  return s;
}

/// Calls f(std::integral_constant<..., v>{}) for the run-time value v.
template <class F>
void with_bool(bool v, F&& f) {
  if (v)
    f(std::true_type{});
  else
    f(std::false_type{});
}
template <class F>
void with_energy(GasEnergy e, F&& f) {
  switch (e) {
    case GasEnergy::None:
      f(std::integral_constant<GasEnergy, GasEnergy::None>{});
      return;
    case GasEnergy::U:
      f(std::integral_constant<GasEnergy, GasEnergy::U>{});
      return;
    case GasEnergy::UTilde:
      f(std::integral_constant<GasEnergy, GasEnergy::UTilde>{});
      return;
  }
}
template <class F>
void with_term(DustTerm t, F&& f) {
  switch (t) {
    case DustTerm::None:
      f(std::integral_constant<DustTerm, DustTerm::None>{});
      return;
    case DustTerm::EpsMean:
      f(std::integral_constant<DustTerm, DustTerm::EpsMean>{});
      return;
    case DustTerm::EpsDonor:
      f(std::integral_constant<DustTerm, DustTerm::EpsDonor>{});
      return;
    case DustTerm::SqrtRhoEps:
      f(std::integral_constant<DustTerm, DustTerm::SqrtRhoEps>{});
      return;
  }
}

/// Stopping time T_sj of species j (eps_j, eps, rho, c_s of the particle): the laws of dust_drag.hpp.
struct ConstantKTime {
  RealView1 k;
  KOKKOS_INLINE_FUNCTION Real operator()(int j, Real ej, Real e, Real rho, Real) const {
    return ts_constant_k(ej, e, rho, k(j));
  }
};
struct EpsteinTime {
  RealView1 size;
  Real rho_grain, gamma;
  KOKKOS_INLINE_FUNCTION Real operator()(int j, Real, Real, Real rho, Real cs) const {
    return ts_epstein(rho_grain, size(j), rho, cs, gamma);
  }
};
struct ConstantTime {
  RealView1 ts;
  KOKKOS_INLINE_FUNCTION Real operator()(int j, Real, Real, Real, Real) const { return ts(j); }
};

/// Everything the loops read and write, gathered once per call.
struct LoopData {
  int n, ns, dim;
  KernelType kernel;
  Box box;
  Real gamma, cs0, beta, alpha_u;
  RealView2 x, vel, acc, gforce;
  RealView1 m, h, rho, omega, P, cs, alpha, u, dudt, divv, vsig;
  IntView1 type;
  RealView2 var, sv, dvar, ts, coef;
  RealView1 eps_tot, eps_ts, eps_ts_free, d_tot, uloc;
  decltype(OneFluidDust::pack) pk;
  decltype(NeighbourList::offsets) offsets, neigh;
  decltype(NeighbourList::image) image;
};

/// eps_j from the evolved variable (eps_j, or q_j = sqrt(eps_j)).
template <bool Svar>
KOKKOS_INLINE_FUNCTION Real species_eps(const RealView2& var, int a, int j) {
  if constexpr (Svar)
    return var(a, j) * var(a, j);
  else
    return var(a, j);
}

// EOS from the gas density and drag times (PL15 eq. 14; HPL18 eq. 14-17, 31-32).
template <bool Svar, GasEnergy E, bool LimitTs, class Law>
struct PrepareKernel {
  LoopData d;
  Law law;
  KOKKOS_INLINE_FUNCTION void operator()(int a) const {
    const int ns = d.ns;
    const auto& rho = d.rho;
    const auto& u = d.u;
    const auto& P = d.P;
    const auto& cs = d.cs;
    const auto& h = d.h;
    const auto& var = d.var;
    const auto& ts = d.ts;
    const auto& coef = d.coef;
    const auto& eps_tot = d.eps_tot;
    const auto& eps_ts = d.eps_ts;
    const auto& d_tot = d.d_tot;
    const auto& uloc = d.uloc;
    const Real gamma = d.gamma, cs0 = d.cs0;
    const Real rhoa = rho(a);
    Real e = 0.0;
    for (int j = 0; j < ns; ++j) e += species_eps<Svar>(var, a, j);
    const Real fg = 1.0 - e;  // gas fraction
    eps_tot(a) = e;
    Real ua = 0.0;
    if constexpr (E == GasEnergy::None) {
      P(a) = pressure_isothermal(fg * rhoa, cs0);
      cs(a) = cs0;
    } else if constexpr (E == GasEnergy::UTilde) {
      P(a) = pressure_adiabatic(rhoa, u(a), gamma);  // HPL18 eq. 32
      ua = u(a) / fg;
      cs(a) = sound_speed_adiabatic(fg * rhoa, P(a), gamma);
    } else {
      ua = u(a);
      P(a) = pressure_adiabatic(fg * rhoa, ua, gamma);  // PL15 eq. 14
      cs(a) = sound_speed_adiabatic(fg * rhoa, P(a), gamma);
    }
    uloc(a) = ua;
    Real sum_ts = 0.0, sum_free = 0.0;
    for (int j = 0; j < ns; ++j) {
      Real ej = species_eps<Svar>(var, a, j);
      ej = ej > 0.0 ? ej : 0.0;
      Real t = law(j, ej, e, rhoa, cs(a));
      if constexpr (LimitTs) {
        sum_free += ej * t;
        if (t * cs(a) > h(a)) t = h(a) / cs(a);  // Ballabio et al. (2018)
      }
      ts(a, j) = t;
      sum_ts += ej * t;
    }
    eps_ts(a) = sum_ts;
    if constexpr (LimitTs) d.eps_ts_free(a) = sum_free;
    Real dsum = 0.0;
    for (int j = 0; j < ns; ++j) {
      Real ej = species_eps<Svar>(var, a, j);
      ej = ej > 0.0 ? ej : 0.0;
      const Real tt = (ts(a, j) - sum_ts) / fg;  // HPL18 eq. 15
      coef(a, j) = Svar ? tt : ej * tt;
      dsum += ej * tt;
    }
    d_tot(a) = dsum;
  }
};

template <bool Svar, GasEnergy E, bool LimitTs, class Law>
void prepare(const LoopData& d, const Law& law) {
  par_for("sph::dust_prepare", 0, d.n, PrepareKernel<Svar, E, LimitTs, Law>{d, law});
}

template <int Dim, bool Svar>
struct PackKernel {
  LoopData d;
  KOKKOS_INLINE_FUNCTION void operator()(int i) const {
    const int ns = d.ns;
    const auto& pk = d.pk;
    const auto& x = d.x;
    const auto& vel = d.vel;
    const auto& var = d.var;
    const auto& sv = d.sv;
    const auto& h = d.h;
    const auto& m = d.m;
    const auto& rho = d.rho;
    const auto& omega = d.omega;
    const auto& P = d.P;
    const auto& cs = d.cs;
    const auto& alpha = d.alpha;
    const auto& uloc = d.uloc;
    const auto& eps_tot = d.eps_tot;
    const auto& d_tot = d.d_tot;
    const auto& type = d.type;
    if constexpr (Svar)
      for (int j = 0; j < ns; ++j) sv(i, j) = var(i, j) * math::sqrt(rho(i));
    for (int dd = 0; dd < Dim; ++dd) {
      pk(i, kX + dd) = x(i, dd);
      pk(i, kV + dd) = vel(i, dd);
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
  }
};

template <int Dim, bool Svar>
void pack(const LoopData& d) {
  par_for("sph::dust_pack", 0, d.n, PackKernel<Dim, Svar>{d});
}

/// Pair (a, b) contribution of the dust equation with direct second
/// derivatives (the DustTerm T != None) to dvar(a, .) and the diffusion part
/// du_d of (1 - eps_a) du_a/dt; sumc collects PL15 eq. 43's own-particle factor.
template <DustTerm T>
struct SecondDerivativeTerm {
  RealView2 dvar, coef, sv;
  int ns;
  KOKKOS_INLINE_FUNCTION void add(int a, int b, Real mb, Real rhoa, Real rhob, Real dP, Real fbar_r, Real ua, Real ub,
                                  Real dta, Real dtb, Real& sumc, Real& du_d) const {
    if constexpr (T == DustTerm::EpsDonor) {
      // PL15 eq. 43 with D_j,a + D_j,b limited to 2 D_j of the particle the dust leaves
      // (the donor): an empty particle loses no dust, so eps_j stays >= 0.
      const Real c = mb / (rhoa * rhob) * dP * fbar_r;
      Real dsum = 0.0;
      for (int j = 0; j < ns; ++j) {
        const Real ca = coef(a, j), cb = coef(b, j);
        const Real donor = 2.0 * (c * (ca + cb) > 0.0 ? ca : cb);
        const Real dd = math::fabs(ca + cb) < math::fabs(donor) ? ca + cb : donor;
        dvar(a, j) -= c * dd;
        dsum += dd;
      }
      du_d -= 0.5 * c * (ua - ub) * dsum;  // PL15 eq. 45 with the same coefficient
    } else if constexpr (T == DustTerm::EpsMean) {
      // PL15 eq. 43: d eps_j,a/dt = -sum_b m_b / (rho_a rho_b) (D_j,a + D_j,b)(P_a - P_b) Fbar / r.
      const Real c = mb / (rhoa * rhob) * dP * fbar_r;
      sumc += c;
      for (int j = 0; j < ns; ++j) dvar(a, j) -= c * coef(b, j);
      // (1 - eps_a) du/dt diffusion part (PL15 eq. 45, sign from eq. 41).
      du_d -= 0.5 * c * (ua - ub) * (dta + dtb);
    } else if constexpr (T == DustTerm::SqrtRhoEps) {
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
};

template <int Dim, class K, DustTerm T, GasEnergy E, bool GasPdV>
struct ForceKernel {
  LoopData d;
  SecondDerivativeTerm<T> dust_term;
  KOKKOS_INLINE_FUNCTION void operator()(int a) const {
    constexpr bool energy = E != GasEnergy::None;
    constexpr bool second = T != DustTerm::None;
    static_assert(energy || !GasPdV, "dust.pdv = \"gas\" needs an energy equation");
    const int ns = d.ns;
    const auto& pk = d.pk;
    const auto& acc = d.acc;
    const auto& gforce = d.gforce;
    const auto& dvar = d.dvar;
    const auto& coef = d.coef;
    const auto& dudt = d.dudt;
    const auto& divv = d.divv;
    const auto& vsig = d.vsig;
    const auto& eps_tot = d.eps_tot;
    const auto& offsets = d.offsets;
    const auto& neigh = d.neigh;
    const auto& image = d.image;
    const Box& box = d.box;
    const Real beta = d.beta, alpha_u = d.alpha_u;
    const Real R = K::radius();
    Real du_d = 0.0, du_w = 0.0, sumc = 0.0;
    HydroSums sum(pk(a, kCs));
    if constexpr (second)
      for (int j = 0; j < ns; ++j) dvar(a, j) = 0.0;
    if (pk(a, kIsGas) == 0.0) {
      for (int dd = 0; dd < Dim; ++dd) {
        acc(a, dd) = 0.0;
        gforce(a, dd) = 0.0;
      }
      dudt(a) = 0.0;
      divv(a) = 0.0;
      vsig(a) = sum.vs;
      return;
    }
    Real xa[3] = {0, 0, 0}, va[3] = {0, 0, 0};
    for (int dd = 0; dd < Dim; ++dd) {
      xa[dd] = pk(a, kX + dd);
      va[dd] = pk(a, kV + dd);
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
      sum.add<energy>(g, inside, sa, sb, mb, beta, alpha_u);
      if constexpr (GasPdV) {
        // (1 - eps_a) du_a/dt += (1/rho) div(D' grad P), D' = P D / rho_g, in the form of PL15 eq. 43.
        du_w += mb / (rhoa * pk(b, kRho)) * (Pa - pk(b, kP)) * 0.5 * (g.fa + g.fb) * g.rinv * (dga + pk(b, kDgas));
      }
      if constexpr (second) {
        const Real fbar_r = 0.5 * (g.fa + g.fb) * g.rinv;
        dust_term.add(a, b, mb, rhoa, pk(b, kRho), Pa - pk(b, kP), fbar_r, ua, ub, dta, pk(b, kDtot), sumc, du_d);
      }
    }
    if constexpr (T == DustTerm::EpsMean)
      for (int j = 0; j < ns; ++j) dvar(a, j) -= sumc * coef(a, j);
    for (int dd = 0; dd < Dim; ++dd) {
      acc(a, dd) = sum.acc[dd];
      gforce(a, dd) = -sum.acc[dd];
    }
    const Real fg = 1.0 - eps_tot(a);
    if constexpr (E == GasEnergy::None)
      dudt(a) = 0.0;
    else if constexpr (E == GasEnergy::UTilde)
      dudt(a) = sum.du + du_w;
    else
      dudt(a) = (sum.du + du_d + du_w) / fg;
    divv(a) = sum.dv * rpfa;
    vsig(a) = sum.vs;
  }
};

template <int Dim, class K, DustTerm T, GasEnergy E, bool GasPdV>
void force_loop(const LoopData& d) {
  par_for("sph::dust_forces", 0, d.n, ForceKernel<Dim, K, T, E, GasPdV>{d, {d.dvar, d.coef, d.sv, d.ns}});
}

// Two first derivatives: PL15 eq. 26 / B7 with (1 - eps) Delta f = -a_hydro (eq. 29-30);
// AddsHeat: the u equation (not u~) takes the diffusion part of PL15 eq. 27.
template <int Dim, class K, bool Svar, bool AddsHeat>
struct FirstDerivativeKernel {
  LoopData d;
  KOKKOS_INLINE_FUNCTION void operator()(int a) const {
    const int ns = d.ns;
    const auto& pk = d.pk;
    const auto& gforce = d.gforce;
    const auto& dvar = d.dvar;
    const auto& coef = d.coef;
    const auto& sv = d.sv;
    const auto& dudt = d.dudt;
    const auto& eps_tot = d.eps_tot;
    const auto& offsets = d.offsets;
    const auto& neigh = d.neigh;
    const auto& image = d.image;
    const Box& box = d.box;
    for (int j = 0; j < ns; ++j) dvar(a, j) = 0.0;
    if (pk(a, kIsGas) == 0.0) return;
    Real xa[3] = {0, 0, 0}, ga[3] = {0, 0, 0};
    for (int dd = 0; dd < Dim; ++dd) {
      xa[dd] = pk(a, kX + dd);
      ga[dd] = gforce(a, dd);
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
      for (int dd = 0; dd < Dim; ++dd) {
        gra += ga[dd] * g.dx[dd];
        grb += gforce(b, dd) * g.dx[dd];
      }
      gra *= g.rinv;
      grb *= g.rinv;
      const Real mb = pk(b, kM);
      const Real ub = pk(b, kU);
      if constexpr (!Svar) {
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
    if constexpr (!Svar)
      for (int j = 0; j < ns; ++j) dvar(a, j) -= sum_a * coef(a, j);
    if constexpr (AddsHeat) dudt(a) += du_d / (1.0 - eps_tot(a));
  }
};

template <int Dim, class K, bool Svar, bool AddsHeat>
void first_derivatives(const LoopData& d) {
  par_for("sph::dust_first", 0, d.n, FirstDerivativeKernel<Dim, K, Svar, AddsHeat>{d});
}

// The stored variable is q_j = S_j / sqrt(rho) = sqrt(eps_j): dq/dt = (dS/dt)_pairs / sqrt(rho).
// The last term of HPL18 eq. 51 / PL15 eq. B7, S_a / (2 rho_a Omega_a) sum_b m_b v_ab . grad W_ab
// = (S / 2) dln(rho)/dt, is the change of S at fixed eps: integrated exactly by storing q.
void sqrt_rho_rate(const LoopData& d) {
  const int ns = d.ns;
  const auto rho = d.rho;
  const auto dvar = d.dvar;
  par_for(
      "sph::dust_dq", 0, d.n, KOKKOS_LAMBDA(int a) {
        const Real r = 1.0 / math::sqrt(rho(a));
        for (int j = 0; j < ns; ++j) dvar(a, j) *= r;
      });
}

template <DustTerm T, GasEnergy E, bool GasPdV>
struct ForceLoop {
  const LoopData& d;
  template <int Dim, class K>
  void operator()() {
    force_loop<Dim, K, T, E, GasPdV>(d);
  }
};

template <bool Svar, bool AddsHeat>
struct FirstDerivatives {
  const LoopData& d;
  template <int Dim, class K>
  void operator()() {
    first_derivatives<Dim, K, Svar, AddsHeat>(d);
  }
};

template <bool Svar>
struct Pack {
  const LoopData& d;
  template <int Dim, class K>
  void operator()() {
    pack<Dim, Svar>(d);
  }
};

template <bool Svar, GasEnergy E, bool LimitTs>
void prepare_with_law(const LoopData& d, const Shape& s, const OneFluidDust& dust, Real rho_grain) {
  switch (s.law) {
    case DragLaw::ConstantK:
      prepare<Svar, E, LimitTs>(d, ConstantKTime{dust.kdrag_view()});
      return;
    case DragLaw::Epstein:
      prepare<Svar, E, LimitTs>(d, EpsteinTime{dust.size_view(), rho_grain, E == GasEnergy::None ? 1.0 : d.gamma});
      return;
    case DragLaw::ConstantStoppingTime:
      prepare<Svar, E, LimitTs>(d, ConstantTime{dust.tstop_view()});
      return;
  }
}

/// Runs the loops in the shape s.
void run_loops(const LoopData& d, const Shape& s, const OneFluidDust& dust) {
  using E = GasEnergy;
  using T = DustTerm;
  with_bool(s.svar, [&](auto svar) {
    constexpr bool Svar = decltype(svar)::value;
    with_energy(s.energy, [&](auto energy) {
      constexpr E En = decltype(energy)::value;
      with_bool(s.limit_ts, [&](auto limit) {
        prepare_with_law<Svar, En, decltype(limit)::value>(d, s, dust, dust.settings().rho_grain);
      });
    });
    dispatch(d.dim, d.kernel, Pack<Svar>{d});
  });
  with_term(s.term, [&](auto term) {
    with_energy(s.energy, [&](auto energy) {
      with_bool(s.gas_pdv, [&](auto pdv) {
        constexpr E En = decltype(energy)::value;
        constexpr bool Pdv = decltype(pdv)::value;
        if constexpr (En != E::None || !Pdv) dispatch(d.dim, d.kernel, ForceLoop<decltype(term)::value, En, Pdv>{d});
      });
    });
  });
  if (s.term == T::None) {
    with_bool(s.svar, [&](auto svar) {
      with_bool(s.energy == E::U, [&](auto heat) {
        dispatch(d.dim, d.kernel, FirstDerivatives<decltype(svar)::value, decltype(heat)::value>{d});
      });
    });
  }
  if (s.svar) sqrt_rho_rate(d);
}

LoopData loop_data(OneFluidDust& dust, Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg,
                   const RealView2& vel, const RealView1& u) {
  const int n = p.n;
  if (dust.pack.extent(0) != static_cast<std::size_t>(n)) {
    dust.pack = decltype(dust.pack)(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::dust_pack"), n,
                                    static_cast<int>(kPackSize));
  }
  const bool svar = dust.settings().variable == DustVariable::SqrtRhoEps;
  LoopData d{};
  d.n = n;
  d.ns = dust.nspecies();
  d.dim = p.dim;
  d.kernel = cfg.kernel;
  d.box = box;
  d.gamma = cfg.gamma;
  d.cs0 = cfg.cs_iso;
  d.beta = cfg.beta;
  d.alpha_u = cfg.alpha_u;
  d.x = p.x;
  d.vel = vel;
  d.acc = p.a;
  d.gforce = dust.gforce;
  d.m = p.m;
  d.h = p.h;
  d.rho = p.rho;
  d.omega = p.omega;
  d.P = p.P;
  d.cs = p.cs;
  d.alpha = p.alpha;
  d.u = u;
  d.dudt = p.dudt;
  d.divv = p.divv;
  d.vsig = p.vsig;
  d.type = p.type;
  d.var = dust.var_pred;
  d.sv = svar ? dust.s_pairs : dust.var_pred;  // S_j = sqrt(rho) q_j in the pair terms (S variable)
  d.dvar = dust.dvar;
  d.ts = dust.ts;
  d.coef = dust.coef;
  d.eps_tot = dust.eps_tot;
  d.eps_ts = dust.eps_ts;
  d.eps_ts_free = dust.eps_ts_free;
  d.d_tot = dust.d_tot;
  d.uloc = dust.uloc;
  d.pk = dust.pack;
  d.offsets = nl.offsets;
  d.neigh = nl.neigh;
  d.image = nl.image;
  return d;
}

}  // namespace dust_detail

void OneFluidDust::mixture_forces(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg,
                                  const RealView2& vel, const RealView1& u) {
  const dust_detail::LoopData d = dust_detail::loop_data(*this, p, nl, box, cfg, vel, u);
  dust_detail::run_loops(d, dust_detail::shape_of(s_, cfg), *this);
}

}  // namespace mote::sph
