// [radiation] deck keys (RBO24 sec. 4; VALIDATION D).
#include "mote/radiation/settings.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace mote::radiation {

std::vector<double> log_wavelength_edges(double lo, double hi, int n) {
  std::vector<double> e;
  for (int k = 0; k <= n; ++k) e.push_back(lo * std::pow(hi / lo, double(k) / n));
  return e;
}

namespace {

void declare_grids(core::DeckSchema& s) {
  s.integer("radiation.bands")
      .sets_state_size()
      .default_value(20LL)
      .min(1)
      .doc("Number of FLD wavelength bands (RBO24 sec. 4.1).");
  s.integer("radiation.stellar_bins")
      .default_value(100LL)
      .min(1)
      .doc("Number of wavelength bins for the stellar heating; at least the number of bands.");
  s.real("radiation.lambda_min").default_value(1e-5).greater_than(0.0).unit("cm").doc("Shortest wavelength edge.");
  s.real("radiation.lambda_max").default_value(0.3).greater_than(0.0).unit("cm").doc("Longest wavelength edge.");
  s.real("radiation.T_ext").default_value(10.0).greater_than(0.0).unit("K").doc("Field at the open sides.");
  s.string("radiation.inner").default_value(std::string("open")).one_of({"open", "reflecting"}).doc("R_in side.");
  s.string("radiation.outer").default_value(std::string("open")).one_of({"open", "reflecting"}).doc("R_out side.");
  s.string("radiation.lower")
      .default_value(std::string("reflecting"))
      .one_of({"open", "reflecting"})
      .doc("theta_min side.");
  s.string("radiation.upper").default_value(std::string("open")).one_of({"open", "reflecting"}).doc("theta_max side.");
}

void declare_solver(core::DeckSchema& s) {
  s.real("radiation.tolerance")
      .default_value(1e-4)
      .greater_than(0.0)
      .less_than(1.0)
      .doc("Largest fractional residual of the FLD solve (RBO24 sec. 4.1).");
  s.integer("radiation.max_iterations").default_value(500LL).min(1).doc("BiCGStab iterations per rung.");
  s.integer("radiation.ilu_fill").default_value(0LL).min(-1).doc("ILU(k) level of fill; -1 for no preconditioner.");
  s.integer("radiation.max_fill_level").default_value(2LL).min(0).doc("Highest ILU level the fallback ladder tries.");
  s.integer("radiation.triangular_sweeps")
      .default_value(0LL)
      .min(0)
      .max(1000)
      .doc(
          "0: ILU factors applied by exact level-scheduled triangular solves; m > 0: by m Jacobi sweeps per factor "
          "(2m + 1 kernels instead of one per level: for GPUs; docs/radiation.md).");
}

void declare_star_and_opacity(core::DeckSchema& s) {
  s.real("radiation.star_radius").default_value(1.7).greater_than(0.0).unit("R_sun").doc("Stellar radius.");
  s.real("radiation.star_T_eff").default_value(4500.0).greater_than(0.0).unit("K").doc("Stellar temperature.");
  s.string("radiation.opacity")
      .default_value(std::string("grey"))
      .one_of({"grey", "power-law", "dsharp", "radmc"})
      .doc("Dust opacities: constant, power law with a size cut-off, or a DSHARP/cuDisc or RADMC-3D table.");
  s.string("radiation.opacity_file").default_value(std::string("")).doc("Table file for opacity = dsharp | radmc.");
  s.real("radiation.kappa_abs").default_value(1.0).min(0.0).unit("cm^2/g").doc("Grey absorption opacity.");
  s.real("radiation.kappa_sca").default_value(0.0).min(0.0).unit("cm^2/g").doc("Grey scattering opacity.");
  s.real("radiation.beta").default_value(1.0).min(0.0).doc("Power-law index of Q_abs = (2 pi a / lambda)^beta.");
  s.real("radiation.rho_grain").default_value(1.6).greater_than(0.0).unit("g/cm^3").doc("Grain density (power law).");
  s.real("radiation.kappa_gas").default_value(0.0).min(0.0).unit("cm^2/g").doc("Gas opacity floor (RBO24 sec. 7).");
  s.string("radiation.band_means")
      .default_value(std::string("fixed"))
      .one_of({"fixed", "local"})
      .doc(
          "Opacities of the FLD bands from the stellar bins: fixed, the sum over species of each species' Planck "
          "(absorption) and Rosseland (total) means at radiation.T_binning (exact for the Planck mean; a mixture's "
          "Rosseland mean is not the sum of its species' means, so an approximation); local, per cell at its "
          "temperature for its mixture of species (RBO24 sec. 4.2, as cuDisc), taken at every temperature update.");
  s.real("radiation.T_binning")
      .default_value(100.0)
      .greater_than(0.0)
      .unit("K")
      .doc("Temperature of the band means with band_means = \"fixed\".");
}

/// A length in cm as %g would print it.
std::string cm(double x) {
  std::ostringstream out;
  out << x << " cm";
  return out.str();
}

/// A table file must parse (its reader names the file and line of a fault)
/// and cover the centres of the first and last stellar bins.
void check_opacity_table(const core::Deck& d, core::DeckCheck& check, const std::string& file) {
  OpacityTable table;
  try {
    table = d.string("radiation.opacity") == "dsharp" ? read_dsharp_table(file) : read_radmc_dustkappa(file, 1.0);
  } catch (const OpacityFileError& e) {
    return check.fail("radiation.opacity_file", e.what());
  }
  const auto edges = log_wavelength_edges(d.real("radiation.lambda_min"), d.real("radiation.lambda_max"),
                                          static_cast<int>(d.integer("radiation.stellar_bins")));
  const double first = std::sqrt(edges[0] * edges[1]), last = std::sqrt(edges[edges.size() - 2] * edges.back());
  const double shortest = table.wavelengths_cm.front(), longest = table.wavelengths_cm.back();
  const auto covered = "the table '" + file + "' covers " + cm(shortest) + " - " + cm(longest);
  if (first < shortest * (1 - 1e-12))
    check.fail("radiation.lambda_min", "puts the first stellar bin's centre at " + cm(first) + ", but " + covered);
  if (last > longest * (1 + 1e-12))
    check.fail("radiation.lambda_max", "puts the last stellar bin's centre at " + cm(last) + ", but " + covered);
}

void check_radiation(const core::Deck& d, core::DeckCheck& check) {
  if (!d.has_table("radiation")) return;
  if (d.integer("radiation.bands") > d.integer("radiation.stellar_bins"))
    check.fail("radiation.bands", "must not exceed " + check.quote("radiation.stellar_bins"));
  if (!(d.real("radiation.lambda_max") > d.real("radiation.lambda_min")))
    check.fail("radiation.lambda_max", "must exceed " + check.quote("radiation.lambda_min"));
  const auto& format = d.string("radiation.opacity");
  if (format == "dsharp" || format == "radmc") {
    const auto& file = d.string("radiation.opacity_file");
    if (file.empty())
      check.fail("radiation.opacity_file", "is needed for " + check.quote("radiation.opacity"));
    else if (!std::ifstream(file))
      check.fail("radiation.opacity_file", "names a file that cannot be opened: '" + file + "'");
    else if (d.real("radiation.lambda_max") > d.real("radiation.lambda_min"))
      check_opacity_table(d, check, file);
  }
}

RadiationBoundary side(const core::Deck& d, const std::string& key) {
  return d.string(key) == "open" ? RadiationBoundary::Open : RadiationBoundary::Reflecting;
}

}  // namespace

void declare(core::DeckSchema& schema) {
  schema.table("radiation", "Temperature solver: stellar heating and multi-band FLD (RBO24 sec. 4).", true);
  declare_grids(schema);
  declare_solver(schema);
  declare_star_and_opacity(schema);
  schema.rule(check_radiation);
}

RadiationDeck from_deck(const core::Deck& d, const units::UnitSystem& units) {
  RadiationDeck r;
  const double lo = d.real("radiation.lambda_min"), hi = d.real("radiation.lambda_max");
  r.fld.band_edges_cm = log_wavelength_edges(lo, hi, static_cast<int>(d.integer("radiation.bands")));
  r.stellar_bin_edges_cm = log_wavelength_edges(lo, hi, static_cast<int>(d.integer("radiation.stellar_bins")));
  r.fld.boundaries = {side(d, "radiation.inner"), side(d, "radiation.outer"), side(d, "radiation.lower"),
                      side(d, "radiation.upper"), d.real("radiation.T_ext")};
  r.fld.solver.tolerance = d.real("radiation.tolerance");
  r.fld.solver.max_iterations = static_cast<int>(d.integer("radiation.max_iterations"));
  r.fld.solver.preconditioning = {static_cast<int>(d.integer("radiation.ilu_fill"))};
  r.fld.solver.max_fill_level = static_cast<int>(d.integer("radiation.max_fill_level"));
  r.fld.solver.triangular_sweeps = static_cast<int>(d.integer("radiation.triangular_sweeps"));
  r.star = {d.real("radiation.star_radius") * units::cgs::R_sun / units.length, d.real("radiation.star_T_eff")};
  r.opacity = d.string("radiation.opacity");
  r.opacity_file = d.string("radiation.opacity_file");
  r.kappa_abs = d.real("radiation.kappa_abs");
  r.kappa_sca = d.real("radiation.kappa_sca");
  r.beta = d.real("radiation.beta");
  r.rho_grain = d.real("radiation.rho_grain");
  r.kappa_gas = d.real("radiation.kappa_gas");
  r.T_binning = d.real("radiation.T_binning");
  r.band_means_at_cell_T = d.string("radiation.band_means") == "local";
  return r;
}

OpacityTable RadiationDeck::opacities(const std::vector<double>& sizes_cm) const {
  std::vector<double> centres;
  for (std::size_t k = 0; k + 1 < stellar_bin_edges_cm.size(); ++k)
    centres.push_back(std::sqrt(stellar_bin_edges_cm[k] * stellar_bin_edges_cm[k + 1]));
  if (opacity == "grey") return grey_opacity(sizes_cm, centres, kappa_abs, kappa_sca);
  if (opacity == "power-law") return power_law_opacity(sizes_cm, centres, rho_grain, beta);
  const OpacityTable table =
      opacity == "dsharp" ? read_dsharp_table(opacity_file) : read_radmc_dustkappa(opacity_file, sizes_cm.front());
  return interpolate(table, sizes_cm, centres);
}

}  // namespace mote::radiation
