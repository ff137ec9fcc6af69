// [coagulation] deck keys (RBO24 sec. 5; VALIDATION E).
#include "mote/coagulation/settings.hpp"

namespace mote::coagulation {

namespace {

void check_size_range(const core::Deck& d, core::DeckCheck& check) {
  if (d.has_table("coagulation") && !(d.real("coagulation.a_max") > d.real("coagulation.a_min")))
    check.fail("coagulation.a_max", "must exceed " + check.quote("coagulation.a_min"));
}

}  // namespace

void declare(core::DeckSchema& s) {
  s.table("coagulation", "Grain growth and fragmentation (RBO24 sec. 5), integrated independently in every cell.",
          true);
  s.string("coagulation.kernel")
      .default_value(std::string("physical"))
      .one_of({"constant", "additive", "product", "physical"})
      .doc("Collision kernel: K0, K0 (m_i + m_j), K0 m_i m_j (analytic tests) or sigma_ij dv_ij (RBO24 eq. 56).");
  s.real("coagulation.kernel_coefficient")
      .default_value(1.0)
      .greater_than(0.0)
      .unit("code units of K")
      .doc("K0 of the constant, additive and product kernels.");
  s.boolean("coagulation.vertically_integrated")
      .default_value(false)
      .doc("Physical kernel divided by sqrt(2 pi (h_i^2 + h_j^2)) for surface densities (RBO24 sec. 5.1).");
  s.boolean("coagulation.fragmentation")
      .default_value(true)
      .doc("Fragmentation with the Maxwellian probability of RBO24 eq. 62 (physical kernel only).");
  s.real("coagulation.v_frag")
      .default_value(100.0)
      .greater_than(0.0)
      .unit("cm/s")
      .doc("Fragmentation velocity v_frag (RBO24 eq. 62).");
  s.real("coagulation.fragment_slope")
      .default_value(11.0 / 6.0)
      .greater_than(0.0)
      .doc("eta of the fragment distribution n(m) ~ m^-eta (RBO24 eq. 66).");
  s.real("coagulation.chi_im")
      .default_value(1.0)
      .greater_than(0.0)
      .doc("Mass excavated from the target in units of the impactor mass (RBO24 eq. 68).");
  s.string("coagulation.product_split")
      .default_value(std::string("quadratic"))
      .one_of({"quadratic", "two-bin"})
      .doc(
          "Sharing of products and remnants between the centres around them: the number-conserving split with a "
          "limited second-moment correction (default; VALIDATION E1/E2 at 7 bins per mass decade, "
          "docs/coagulation.md) or the two-bin mass fractions of RBO24 eq. 63-65 (as cuDisc).");
  s.real("coagulation.rel_tol")
      .default_value(1e-2)
      .greater_than(0.0)
      .less_than(1.0)
      .doc("Relative tolerance of the Bogacki-Shampine 3(2) sub-steps.");
  s.real("coagulation.abs_tol")
      .default_value(1e-10)
      .greater_than(0.0)
      .less_than(1.0)
      .doc(
          "Absolute tolerance, in units of the cell's total dust density (below 1: at 1 the error control "
          "would accept any change of the cell's dust).");
  s.integer("coagulation.max_substeps")
      .default_value(1000000LL)
      .min(1)
      .doc("Largest number of sub-steps per cell and call before the call fails.");
  s.integer("coagulation.cells_per_batch")
      .default_value(1024LL)
      .min(1)
      .doc("Cells whose pair kernels are held in memory at once (memory: 16 N(N+1)/2 bytes per cell).");
  s.integer("coagulation.team_size")
      .default_value(0LL)
      .min(0)
      .max(256)
      .doc(
          "Threads of the team that integrates one cell (at most 256, the largest measured on a GPU); 0 chooses per "
          "back-end (docs/coagulation.md).");
  s.real("coagulation.a_min")
      .default_value(5e-5)
      .greater_than(0.0)
      .unit("cm")
      .doc("Grain size of the smallest species.");
  s.real("coagulation.a_max").default_value(0.1).greater_than(0.0).unit("cm").doc("Grain size of the largest species.");
  s.integer("coagulation.species")
      .sets_state_size()
      .default_value(200LL)
      .min(2)
      .doc("Number of species (logarithmic in mass; >= 7 per mass decade recommended).");
  s.real("coagulation.rho_m").default_value(1.6).greater_than(0.0).unit("g/cm^3").doc("Intrinsic grain density.");
  s.real("coagulation.mu")
      .default_value(2.4)
      .greater_than(0.0)
      .doc(
          "Mean molecular weight of the gas (k_B T = mu m_H c_s^2, mean free path); on the disc grid gas.mu "
          "applies and this key, if given, must equal it.");
  s.rule(check_size_range);
}

CoagulationSettings settings_from_deck(const core::Deck& d) {
  CoagulationSettings s;
  if (!d.has_table("coagulation")) return s;
  s.kernel = d.string("coagulation.kernel");
  s.kernel_coefficient = d.real("coagulation.kernel_coefficient");
  s.vertically_integrated = d.boolean("coagulation.vertically_integrated");
  s.fragmentation = d.boolean("coagulation.fragmentation");
  s.v_frag = d.real("coagulation.v_frag");
  s.fragment_slope = d.real("coagulation.fragment_slope");
  s.chi_im = d.real("coagulation.chi_im");
  s.product_split = d.string("coagulation.product_split");
  s.rel_tol = d.real("coagulation.rel_tol");
  s.abs_tol = d.real("coagulation.abs_tol");
  s.max_substeps = static_cast<int>(d.integer("coagulation.max_substeps"));
  s.cells_per_batch = static_cast<int>(d.integer("coagulation.cells_per_batch"));
  s.team_size = static_cast<int>(d.integer("coagulation.team_size"));
  s.a_min = d.real("coagulation.a_min");
  s.a_max = d.real("coagulation.a_max");
  s.species = static_cast<int>(d.integer("coagulation.species"));
  s.rho_m = d.real("coagulation.rho_m");
  s.mu = d.real("coagulation.mu");
  return s;
}

}  // namespace mote::coagulation
