// Two-fluid dust in SPH with the improved semi-implicit pairwise drag of
// Lorén-Aguilar & Bate (2015, LAB15), an SphModule (dust.method = "two-fluid").
// Dust species j are particles of type kDust + j: pressureless, with the same
// external forces as the gas, and their density summed over the particles of
// their own species (the engine's density loop sums over equal types). The
// engine's kick-drift-kick gives the non-drag update (LAB15 eq. 2-3); this
// module applies the drag after each half kick, over dt / 2 each, pair by
// pair from the same neighbour list (LAB15 sec. 2). With constant
// coefficients the two halves compose to the exact solution over dt (eq.
// 13-14), as one update would; splitting it puts the drag-limited mid-step
// velocity into the drift: applied once after the second kick, the drift of a
// grain at its terminal velocity moves it with v_term + a dt / 2, i.e.
// (1 + dt / 2 t_s) v_term, and the 5-orbit A5 column settled to 0.80 H
// instead of 1.02 H at dt = 2.6 t_s. For each half step dt':
//   for a dust particle i and a gas neighbour k, with eps = rho_i / rho_k,
//   t_s the relaxation time of v_DG from the drag law (below),
//     xi     = (1 - exp(-dt' / t_s)) / (1 + eps)             (eq. 6)
//     Lambda = (dt' + t_s) xi - dt' / (1 + eps)              (eq. 19; 0 in the original scheme, eq. 4-5)
//     S_ik   = xi v~_ik - Lambda a_ik                        (eq. 21)
//   with v~_ik the velocity difference after the half kick and a_ik the
//   difference of the non-drag accelerations of that half kick ((v~ - v) / dt');
//     dust:  v_i += -sum_k^gas (m_k / rho_k) W(r_ik, h_k) (S_ik . r^) T_i^-1 r^
//     gas:   v_k += sum_i^dust (m_i / m_k) (m_k / rho_k) W(r_ik, h_k) (S_ik . r^) T_i^-1 r^
//     T_i  = sum_k^gas (m_k / rho_k) W(r_ik, h_k) r^ r^T
//   so every pair exchanges equal and opposite momentum (exact conservation).
//   Departure from LAB15 eq. 27-28, 30: they normalise with nu / N_i,
//   N_i = sum_k (m_k / rho_k) W(r_ik, h_k), which is T_i^-1 for isotropic
//   neighbours only; on the B2 cubic lattices with h = 1.2 dx a dust particle
//   between lattice planes sees T_xx = 0.76 N_i / 3 and 25 % too little drag
//   along x (a terminal velocity 18 % high, against LAB15's 1 %). With T_i^-1
//   the drag on a uniform relative velocity is exact in any arrangement; the
//   impulse is along T_i^-1 r^, not r^, so angular momentum is conserved only
//   where T_i is isotropic. In 1D the two are the same. Where the gas
//   neighbours lie on a line or a plane (a single one, beyond the edge of
//   the gas) T_i is singular and its pseudo-inverse is used: the drag is
//   exact along the directions they sample and absent across them (LAB15's
//   nu / N_i would multiply a single neighbour's impulse by Dim and reverse
//   and grow v_DG at dt >> t_s).
//   The gas gains the kinetic energy the pairs remove: eq. 29's bookkeeping,
//   with each pair's share taken from the velocity changes the pairs produce
//   (the dust particle's Dv_i and the gas particle's own), which eq. 29
//   approximates by Dv_i = -S_ik, Dv_k = eps S_ik:
//     m_k u_k += sum_i m_i w_ik (S_ik . r^) (v~_ik + Dv_i / 2) . T_i^-1 r^ - m_k |Dv_k|^2 / 2,
//   w_ik = (m_k / rho_k) W(r_ik, h_k): the total energy is then conserved to
//   round-off in any arrangement (the unit tests check 1e-10), and in a uniform
//   mixture the heating is LAB15 eq. 22 exactly. That includes the relative
//   kinetic energy a half kick adds at second order, m_D a_DG^2 dt'^2 / 2 per
//   1 + eps, which the drag removes: at terminal velocity the heating is the
//   physical K v_DG^2 times 1 + dt / (4 t_s), 251 at dt = 1e3 t_s (a
//   splitting error of eq. 20-22, first order in dt; it is heat where
//   the energy is kept exactly).
// Several species: every pair also carries c_jk, the difference between the
// exact update of the local mixture around gas particle k and the mean of its
// pairs' own S_ik (include/mote/sph/mixture_drag.hpp), added to S_ik before the
// projection, so that a species' drift sees the gas dragged by the others.
// Drag laws (the shared dust laws, as in the one-fluid method, with the pair's
// rho = rho_i + rho_k): constant t_s; constant K, t_s = rho_i rho_k / (K rho);
// Epstein, t_s = rho_grain s / (rho v_th). No drag time-step constraint: the
// dust particles' own is the force criterion C_force sqrt(h / |a|).
#pragma once

#include <string>
#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/dust_settings.hpp"
#include "mote/sph/sph_module.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::sph {

class TwoFluidDust : public SphModule {
 public:
  /// The system must hold particles of every dust type kDust + j, j < settings.nspecies.
  TwoFluidDust(const DustSettings& settings, const SphSystem& sys);

  std::string name() const override { return "two-fluid dust"; }
  std::string exclusive_group() const override { return "dust method"; }
  void begin_step(SphSystem& sys, Real dt) override;
  void after_first_kick(SphSystem& sys, Real half_dt) override;
  void after_kick(SphSystem& sys, Real half_dt) override;
  Real timestep(SphSystem& sys) override;
  std::string timestep_name() const override { return "two-fluid dust particles' force criterion"; }
  void reorder(ParticleReorder& r) override;
  void add_diagnostics(const SphSystem& sys, Diagnostics& dg) const override;
  std::vector<io::Diagnostic> history(const SphSystem& sys) const override;
  /// ndustlarge = N (the dust species are the particle types Phantom's idust + j).
  void write_phantom_dump(const SphSystem& sys, io::PhantomDump& dump) const override;
  void save_state(const SphSystem& sys, io::H5File& f) const override;
  void load_state(SphSystem& sys, const io::H5File& f) override;

  const DustSettings& settings() const { return s_; }
  /// Kinetic energy the drag has turned into gas heat since the start (sum of eq. 29 times m; read from the device).
  Real drag_heating() const;
  /// Applies the drag of a (sub-)step dt to the current velocities (and u,
  /// adiabatic gas), with a_DG from the change since v_start; public for tests
  /// that hold the particles fixed.
  void apply_drag(SphSystem& sys, Real dt);

  /// Per-particle scratch, public only because nvcc's extended lambdas may not
  /// live in private member functions.
  RealView2 v_start, dv;                               ///< velocity at the start of the step; drag change (n x dim)
  RealView2 tinv;                                      ///< T_i^-1 of the dust (n x 9, row-major 3 x 3), see above
  RealView1 du;                                        ///< drag heating of the gas
  RealView2 drag_pack;                                 ///< per-particle factors of the pair terms (n x 6)
  RealView1 kdrag, size, tstop;                        ///< per species
  RealView1 species_decay;                             ///< 1 - exp(-dt / t_s) per species (constant t_s)
  Kokkos::View<Real, MemSpace> heat_step, heat_total;  ///< drag heating of the last update and since the start
  /// The dust-gas pairs of the neighbour list, numbered again after each of its
  /// builds: dust particle i's gas neighbours, in its list's order, hold the
  /// slots pair_start(i) ..; gas particle k's slots, in the order of its own
  /// list, are gas_pairs(gas_start(k) ..). Each drag update evaluates a pair
  /// once, from the dust, into pair_terms (slots x 6: w, S.r^, v~.e, e), and
  /// the gas sums read it back in the same order as before: the same bits as
  /// evaluating every pair from both sides, at half the pair evaluations.
  View<int*> pair_start, gas_start, gas_pairs, pair_dust;
  View<int*> gas_sorted, gas_fill;  ///< work of the numbering
  View<unsigned char*> pair_code;   ///< image code of each slot's gas particle in the dust particle's list
  RealView2 pair_terms;
  /// Several species: the correction c_jk of each gas particle k and species j
  /// (n x 3N, include/mote/sph/mixture_drag.hpp), and the count of gas
  /// particles whose mixture could not be solved (their c is zero; in the history).
  RealView2 mixture_corr;
  /// Several species: each pair's w, rate, xi, Lambda and r^.e at its position
  /// in the gas order (slots x 5), slot_in_gas(slot) that position and
  /// gas_dust(position) its dust particle; renumbered with the pairs.
  RealView2 mixture_terms;
  View<int*> slot_in_gas, gas_dust;
  Kokkos::View<int, MemSpace> mixture_unsolved;
  int pair_map_builds = -1;  ///< NeighbourList::builds() the numbering belongs to

 private:
  DustSettings s_;
};

/// Registers the two-fluid dust on sys (after set_particles(), before initialise()).
TwoFluidDust& add_two_fluid_dust(SphSystem& sys, const DustSettings& settings);

}  // namespace mote::sph
