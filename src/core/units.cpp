// Code-unit systems (see include/mote/core/units.hpp).
#include "mote/core/units.hpp"

#include <cmath>
#include <stdexcept>

namespace mote::units {

UnitSystem UnitSystem::with_unit_G(std::string name, double length_cm, double mass_g) {
  UnitSystem u;
  u.name = std::move(name);
  u.length = length_cm;
  u.mass = mass_g;
  // G_code = G_cgs M T^2 / L^3 = 1  =>  T = sqrt(L^3 / (G M))
  u.time = std::sqrt(length_cm * length_cm * length_cm / (cgs::G * mass_g));
  return u;
}

namespace {
const char* const kNames[] = {"cgs", "dimensionless", "au_msun", "10au_msun", nullptr};
}

const char* const* unit_system_names() { return kNames; }

UnitSystem unit_system_by_name(const std::string& name) {
  if (name == "cgs") return UnitSystem::cgs_units();
  if (name == "dimensionless") {
    UnitSystem u;
    u.name = "dimensionless";
    return u;
  }
  if (name == "au_msun") return UnitSystem::with_unit_G(name, cgs::au, cgs::M_sun);
  if (name == "10au_msun") return UnitSystem::with_unit_G(name, 10.0 * cgs::au, cgs::M_sun);
  throw std::invalid_argument("unknown unit system '" + name + "'");
}

}  // namespace mote::units
