// Deck table [dust] of the one-fluid SPH dust method (PL15, HPL18); see
// include/mote/sph/dust_settings.hpp.
#include "mote/sph/dust_settings.hpp"

#include <stdexcept>
#include <string>

#include "mote/core/deck.hpp"
#include "mote/core/deck_schema.hpp"
#include "mote/core/log.hpp"
#include "mote/dust/size_distribution.hpp"
#include "mote/sph/mixture_drag.hpp"

namespace mote::sph {

namespace {

/// One-fluid dust: the initial fractions leave a gas fraction 1 - sum_j eps_j above kMinGasFraction
/// (one value is each species'), or the pressure and the stopping times, which divide by it (PL15
/// eq. 9, 26), are lost to round-off: ten species of 0.1 sum to 1 - 1.1e-16.
constexpr double kMinGasFraction = 1e-9;

void check_total_fraction(const core::Deck& d, core::DeckCheck& check) {
  const auto& eps = d.real_array("dust.eps");
  if (d.string("dust.method") == "two-fluid" || d.string("dust.sizes_from") != "list" || eps.empty()) return;
  const long long n = d.integer("dust.species");
  if (eps.size() != 1 && static_cast<long long>(eps.size()) != n) return;  // reported by the list's check
  double total = 0.0;
  for (long long j = 0; j < n; ++j) total += eps[eps.size() == 1 ? 0 : static_cast<std::size_t>(j)];
  if (!(1.0 - total > kMinGasFraction))
    check.fail("dust.eps", logging::cat("sums to ", logging::format("%.17g", total), " over the ", n, " species (",
                                        check.quote("dust.species"), "); one-fluid dust needs a gas fraction 1 - ",
                                        "sum eps_j above ", kMinGasFraction));
}

/// Per-species lists hold one value (all species) or dust.species values, as
/// DustSettings::validate() requires; checked here against the deck, with file and line.
void check_species_lists(const core::Deck& d, core::DeckCheck& check) {
  if (!d.has_table("dust")) return;
  const long long n = d.integer("dust.species");
  auto check_list = [&](const std::string& key, bool needed) {
    const size_t size = d.real_array(key).size();
    if (needed && !(size == 1 || static_cast<long long>(size) == n))
      check.fail(key, n == 1
                          ? logging::cat("needs 1 entry (", check.quote("dust.species"), "), got ", size)
                          : logging::cat("needs 1 or ", n, " entries (", check.quote("dust.species"), "), got ", size));
  };
  if (d.string("dust.method") == "two-fluid" && n > kMaxCoupledSpecies)
    check.fail("dust.species",
               logging::cat("two-fluid dust couples at most ", kMaxCoupledSpecies, " species, got ", n));
  const std::string& drag = d.string("dust.drag");
  const bool lists = d.string("dust.sizes_from") == "list";
  check_list("dust.K", drag == "constant_K");
  check_list("dust.stopping_time", drag == "constant_ts");
  check_list("dust.sizes", lists && drag == "epstein");
  check_list("dust.eps", lists && !d.real_array("dust.eps").empty());
  if (!lists && !(d.real("dust.s_max") > d.real("dust.s_min")))
    check.fail("dust.s_max", "must exceed " + check.quote("dust.s_min"));
  check_total_fraction(d, check);
}

/// PdV work from div v_g with drag heating needs an energy equation.
void check_pdv(const core::Deck& d, core::DeckCheck& check) {
  if (d.has_table("dust") && d.has_table("sph") && d.string("dust.pdv") == "gas" && d.string("sph.eos") != "adiabatic")
    check.fail("dust.pdv",
               "\"gas\" needs " + check.quote("sph.eos") + " to be \"adiabatic\" (no PdV work when isothermal)");
}

}  // namespace

core::DeckRule requires_dust_method(const std::string& problem, const std::vector<std::string>& methods) {
  return [=](const core::Deck& d, core::DeckCheck& check) {
    if (!d.has_table("dust")) return;
    const std::string& m = d.string("dust.method");
    std::string names;
    for (const auto& name : methods) {
      if (name == m) return;
      names += (names.empty() ? "\"" : ", \"") + name + "\"";
    }
    check.fail("dust.method", problem + " is set up for " + names + ", not \"" + m + "\"");
  };
}

void DustSettings::declare(core::DeckSchema& s) {
  s.table("dust",
          "SPH dust: one-fluid in the terminal-velocity approximation (PL15; N species: MULTIGRAIN, HPL18) or "
          "two-fluid dust particles with semi-implicit pairwise drag (LAB15).",
          /*optional=*/true);
  s.string("dust.method")
      .default_value(std::string("diffusion"))
      .one_of({"diffusion", "multigrain", "two-fluid"})
      .doc(
          "diffusion (PL15) and multigrain (HPL18) are the same one-fluid scheme (N = species); two-fluid: "
          "dust particles, one particle type per species, with the drag of LAB15.");
  s.string("dust.drag_scheme")
      .default_value(std::string("improved"))
      .one_of({"improved", "original"})
      .doc("two-fluid drag update: LAB15 eq. 17-19 (improved) or eq. 4-6 (original, for comparison).");
  s.integer("dust.species")
      .sets_state_size()
      .default_value(1LL)
      .min(1)
      .doc("Number of dust species N (one View extent).");
  s.string("dust.variable")
      .default_value(std::string("epsilon"))
      .one_of({"epsilon", "sqrt_rho_eps"})
      .doc("Evolved variable: eps_j, or S_j = sqrt(rho eps_j) (PL15 app. B, HPL18 eq. 51).");
  s.string("dust.discretisation")
      .default_value(std::string("second_derivatives"))
      .one_of({"second_derivatives", "first_derivatives"})
      .doc("Direct second derivatives (PL15 eq. 43) or two first derivatives (PL15 eq. 26, 29-30).");
  s.string("dust.flux")
      .default_value(std::string("arithmetic"))
      .one_of({"arithmetic", "donor_limited"})
      .doc("PL15 eq. 43 (eps, second derivatives): D_a + D_b, or limited to 2 D of the donor (eps >= 0).");
  s.string("dust.energy")
      .default_value(std::string("u"))
      .one_of({"u", "u_tilde"})
      .doc("Evolve u (PL15 eq. 27/45, HPL18 eq. 56) or u~ = (1 - eps) u (HPL18 eq. 55).");
  s.string("dust.pdv")
      .default_value(std::string("barycentric"))
      .one_of({"barycentric", "gas"})
      .doc("PdV work with div v (PL15 eq. 13) or div v_g + drag heating (energy-conserving form).");
  s.string("dust.drag")
      .default_value(std::string("constant_K"))
      .one_of({"constant_K", "epstein", "constant_ts"})
      .doc("Drag law: constant K_j (HPL18 eq. 16), linear Epstein (PL15 eq. 20), constant t_s.");
  s.real_array("dust.K")
      .default_value(std::vector<double>{1000.0})
      .greater_than(0.0)
      .doc(
          "Drag coefficients K_j (one value: all species). HPL18 eq. 14: N equal bins of one grain population "
          "reproduce its single-species run with K_j = K / N, not K.");
  s.real_array("dust.stopping_time")
      .default_value(std::vector<double>{0.1})
      .greater_than(0.0)
      .unit("code time")
      .doc("t_s per species for drag = constant_ts.");
  s.string("dust.sizes_from")
      .default_value(std::string("list"))
      .one_of({"list", "power_law"})
      .doc("Grain sizes and fractions from lists or the power law of HPL18 eq. 63 on a log grid.");
  s.real_array("dust.sizes")
      .default_value(std::vector<double>{1.0})
      .greater_than(0.0)
      .unit("code length")
      .doc("Grain sizes s_j (epstein, sizes_from = list).");
  s.real_array("dust.eps")
      .default_value(std::vector<double>{0.01})
      .min(0.0)
      .doc(
          "Initial dust fractions eps_j (sizes_from = list; one value: each species); one-fluid: 1 - sum_j eps_j "
          "> 1e-9.");
  s.real("dust.s_min").default_value(5.99e-6).greater_than(0.0).unit("code length").doc("Power law: lower cell edge.");
  s.real("dust.s_max").default_value(0.167).greater_than(0.0).unit("code length").doc("Power law: upper cell edge.");
  s.real("dust.p").default_value(3.5).doc("Power law: index p of d eps = eps0 s^(3-p) ds (HPL18 eq. 63).");
  s.real("dust.eps_total").default_value(1.0 / 101.0).min(0.0).less_than(1.0).doc("Power law: total eps.");
  s.real("dust.rho_grain").default_value(1.0).greater_than(0.0).unit("code density").doc("Intrinsic grain density.");
  s.string("dust.timestep")
      .default_value(std::string("combined"))
      .one_of({"combined", "separate"})
      .doc("HPL18 eq. 44 (combined) or PL15 eq. 16 (separate diffusion limit).");
  s.real("dust.C0").default_value(0.3).greater_than(0.0).max(1.0).doc("Safety factor C0 of the dust time-step.");
  s.boolean("dust.floor_negative").default_value(true).doc("Set eps_j < 0 to zero and report the mass (PL15 4.4.2).");
  s.boolean("dust.project_mass")
      .default_value(true)
      .doc(
          "S variable: rescale each species after every step to its dust mass at the step's start "
          "(projection; the surplus is reported). The eps variable conserves dust mass without it.");
  s.boolean("dust.limit_stopping_time")
      .default_value(false)
      .doc(
          "Use min(t_sj, h / c_s) for t_sj (the flux limiter of Ballabio et al. 2018): caps the drift where "
          "the stopping length exceeds the resolution and the terminal-velocity approximation fails (the "
          "low-density gas above a disc column). The capped value also sets the dust time-step and the written "
          "velocities; the PL15 eq. 18 warning counts with the uncapped one.");
  s.boolean("dust.write_velocities")
      .default_value(false)
      .doc(
          "Snapshots also hold dust_velocity: v_dj = v_g + Dv_j of every species (HPL18 eq. 24-25), "
          "3N components per particle, v_dj along axis d in column 3 j + d.");
  s.rule(check_species_lists);
  s.rule(check_pdv);
}

DustSettings DustSettings::from_deck(const core::Deck& d) {
  DustSettings s;
  s.method = d.string("dust.method") == "two-fluid" ? DustMethod::TwoFluid : DustMethod::OneFluid;
  s.drag_scheme = d.string("dust.drag_scheme") == "original" ? TwoFluidDrag::Original : TwoFluidDrag::Improved;
  s.nspecies = static_cast<int>(d.integer("dust.species"));
  s.variable = d.string("dust.variable") == "epsilon" ? DustVariable::Epsilon : DustVariable::SqrtRhoEps;
  s.discretisation = d.string("dust.discretisation") == "second_derivatives" ? DustDiscretisation::SecondDerivatives
                                                                             : DustDiscretisation::FirstDerivatives;
  s.flux = d.string("dust.flux") == "donor_limited" ? DustFlux::DonorLimited : DustFlux::Arithmetic;
  s.energy = d.string("dust.energy") == "u" ? DustEnergy::U : DustEnergy::UTilde;
  s.pdv = d.string("dust.pdv") == "gas" ? DustPdV::Gas : DustPdV::Barycentric;
  const std::string drag = d.string("dust.drag");
  s.drag = drag == "constant_K" ? DragLaw::ConstantK
                                : (drag == "epstein" ? DragLaw::Epstein : DragLaw::ConstantStoppingTime);
  s.k_drag = d.real_array("dust.K");
  s.stopping_time = d.real_array("dust.stopping_time");
  s.rho_grain = d.real("dust.rho_grain");
  if (d.string("dust.sizes_from") == "power_law") {
    const dust::SizeBins b = dust::power_law_bins(s.nspecies, d.real("dust.s_min"), d.real("dust.s_max"),
                                                  d.real("dust.p"), d.real("dust.eps_total"));
    s.sizes = b.size;
    s.eps = b.fraction;
  } else {
    s.sizes = d.real_array("dust.sizes");
    s.eps = d.real_array("dust.eps");
  }
  s.timestep = d.string("dust.timestep") == "combined" ? DustTimestep::Combined : DustTimestep::Separate;
  s.c_dust = d.real("dust.C0");
  s.floor_negative = d.boolean("dust.floor_negative");
  s.project_mass = d.boolean("dust.project_mass");
  s.limit_ts = d.boolean("dust.limit_stopping_time");
  s.write_velocities = d.boolean("dust.write_velocities");
  return s;
}

SpeciesDrag DustSettings::species_drag(const std::string& label) const {
  SpeciesDrag out{RealView1(label + "_K", nspecies), RealView1(label + "_size", nspecies),
                  RealView1(label + "_tstop", nspecies)};
  auto hk = Kokkos::create_mirror_view(out.k_drag);
  auto hs = Kokkos::create_mirror_view(out.size);
  auto ht = Kokkos::create_mirror_view(out.stopping_time);
  for (int j = 0; j < nspecies; ++j) {
    hk(j) = drag == DragLaw::ConstantK ? species_value(k_drag, j) : 1.0;
    hs(j) = drag == DragLaw::Epstein ? species_value(sizes, j) : 0.0;
    ht(j) = drag == DragLaw::ConstantStoppingTime ? species_value(stopping_time, j) : 0.0;
  }
  Kokkos::deep_copy(out.k_drag, hk);
  Kokkos::deep_copy(out.size, hs);
  Kokkos::deep_copy(out.stopping_time, ht);
  return out;
}

Real DustSettings::species_value(const std::vector<Real>& list, int j) const {
  if (list.empty()) return 0.0;
  return list.size() == 1 ? list[0] : list[j];
}

std::vector<Real> DustSettings::grain_sizes() const {
  std::vector<Real> s(nspecies, 0.0);
  if (drag == DragLaw::Epstein)
    for (int j = 0; j < nspecies; ++j) s[j] = species_value(sizes, j);
  return s;
}

std::vector<Real> DustSettings::grain_densities() const {
  return std::vector<Real>(nspecies, drag == DragLaw::Epstein ? rho_grain : 0.0);
}

void DustSettings::validate() const {
  if (nspecies < 1) throw std::invalid_argument("dust: species must be >= 1");
  if (method == DustMethod::TwoFluid && nspecies > kMaxCoupledSpecies)
    throw std::invalid_argument("dust: two-fluid dust couples at most " + std::to_string(kMaxCoupledSpecies) +
                                " species (dust.species = " + std::to_string(nspecies) + ")");
  auto check = [&](const std::vector<Real>& l, const char* name, bool needed) {
    if (!needed) return;
    if (!(l.size() == 1 || static_cast<int>(l.size()) == nspecies))
      throw std::invalid_argument(std::string("dust.") + name +
                                  (nspecies == 1 ? std::string(" needs 1 entry (dust.species = 1)")
                                                 : " needs 1 or " + std::to_string(nspecies) + " entries"));
  };
  check(k_drag, "K", drag == DragLaw::ConstantK);
  check(sizes, "sizes", drag == DragLaw::Epstein);
  check(stopping_time, "stopping_time", drag == DragLaw::ConstantStoppingTime);
  if (!eps.empty()) check(eps, "eps", true);
}

}  // namespace mote::sph
