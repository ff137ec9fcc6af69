// Deck table [sph] (see include/mote/sph/sph_settings.hpp).
#include "mote/sph/sph_settings.hpp"

namespace mote::sph {

void declare_settings(core::DeckSchema& s) {
  s.table("sph", "SPH hydrodynamics (PL15 sec. 3).");
  s.string("sph.kernel").default_value(std::string("m4")).one_of({"m4", "m6", "wendland_c4"}).doc("Smoothing kernel.");
  s.real("sph.hfact").default_value(0.0).min(0.0).doc("h / particle spacing; 0 = kernel default (1.2, or 1.0 for M6).");
  s.string("sph.eos")
      .default_value(std::string("adiabatic"))
      .one_of({"adiabatic", "isothermal"})
      .doc("Equation of state.");
  s.real("sph.gamma").default_value(5.0 / 3.0).greater_than(1.0).doc("Adiabatic index.");
  s.real("sph.cs").default_value(1.0).greater_than(0.0).unit("code velocity").doc("Isothermal sound speed.");
  s.real("sph.alpha").default_value(1.0).min(0.0).doc("Linear artificial viscosity (eq. 31-32).");
  s.real("sph.beta").default_value(2.0).min(0.0).doc("Quadratic artificial viscosity.");
  s.real("sph.alpha_u").default_value(1.0).min(0.0).doc("Artificial conductivity (eq. 34-35).");
  s.boolean("sph.cullen_dehnen").default_value(false).doc("Cullen & Dehnen (2010) viscosity switch.");
  s.real("sph.courant").default_value(0.3).greater_than(0.0).max(1.0).doc("Courant number.");
  s.real("sph.damping").default_value(0.0).min(0.0).doc("Velocity damping f of eq. 56 (relaxation); 0 = off.");
}

SphConfig config_from_deck(const core::Deck& d, int dim) {
  SphConfig c;
  c.dim = dim;
  const auto& k = d.string("sph.kernel");
  c.kernel = k == "m6" ? KernelType::M6 : k == "wendland_c4" ? KernelType::WendlandC4 : KernelType::M4;
  c.hfact = d.real("sph.hfact");
  c.eos = d.string("sph.eos") == "isothermal" ? EosType::Isothermal : EosType::Adiabatic;
  c.gamma = d.real("sph.gamma");
  c.cs_iso = d.real("sph.cs");
  c.alpha = d.real("sph.alpha");
  c.alpha_max = std::max(c.alpha_max, c.alpha);
  c.beta = d.real("sph.beta");
  c.alpha_u = d.real("sph.alpha_u");
  c.cullen_dehnen = d.boolean("sph.cullen_dehnen");
  c.c_cour = d.real("sph.courant");
  c.damping = d.real("sph.damping");
  return c;
}

}  // namespace mote::sph
