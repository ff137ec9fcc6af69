// Physical constants (cgs, CODATA 2018 / IAU 2015 nominal values) and code-unit
// systems. Every conversion between cgs and code units goes through UnitSystem.
#pragma once

#include <string>

namespace mote::units {

namespace cgs {
inline constexpr double G = 6.67430e-8;              // cm^3 g^-1 s^-2
inline constexpr double c = 2.99792458e10;           // cm s^-1
inline constexpr double k_B = 1.380649e-16;          // erg K^-1
inline constexpr double h_planck = 6.62607015e-27;   // erg s
inline constexpr double sigma_SB = 5.670374419e-5;   // erg cm^-2 s^-1 K^-4
inline constexpr double a_rad = 4.0 * sigma_SB / c;  // erg cm^-3 K^-4
inline constexpr double m_H = 1.6735575e-24;         // g: 1.00784 u, H's standard atomic weight (cuDisc's value)
inline constexpr double m_p = 1.67262192369e-24;     // g
inline constexpr double au = 1.495978707e13;         // cm
inline constexpr double pc = 3.0856775814913673e18;  // cm
inline constexpr double year = 3.15576e7;            // s (Julian year)
inline constexpr double M_sun = 1.98840987e33;       // g (GM_sun / G)
inline constexpr double R_sun = 6.957e10;            // cm
inline constexpr double L_sun = 3.828e33;            // erg s^-1
inline constexpr double M_earth = 5.97216787e27;     // g
}  // namespace cgs

/// A system of code units given by its length, mass and time units in cgs.
/// Code value x corresponds to x * unit in cgs.
struct UnitSystem {
  std::string name = "cgs";
  double length = 1.0;  // cm
  double mass = 1.0;    // g
  double time = 1.0;    // s

  double velocity() const { return length / time; }
  double density() const { return mass / (length * length * length); }
  double surface_density() const { return mass / (length * length); }
  double energy() const { return mass * velocity() * velocity(); }
  double specific_energy() const { return velocity() * velocity(); }
  double pressure() const { return density() * specific_energy(); }
  double acceleration() const { return length / (time * time); }
  /// G in code units.
  double gravitational_constant() const { return cgs::G * mass * time * time / (length * length * length); }

  static UnitSystem cgs_units() { return {}; }
  /// Length and mass units given; the time unit is chosen so that G = 1.
  static UnitSystem with_unit_G(std::string name, double length_cm, double mass_g);
};

/// Recognised unit-system names for decks: "cgs", "au_msun" (1 au, 1 M_sun, G = 1),
/// "10au_msun" (10 au, 1 M_sun, G = 1; PL15 settling tests), "dimensionless" (all 1).
UnitSystem unit_system_by_name(const std::string& name);
const char* const* unit_system_names();

}  // namespace mote::units
