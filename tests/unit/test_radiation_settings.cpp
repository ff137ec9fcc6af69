// The [radiation] deck table: values reach the solver settings, and bad input
// (issue 19: band count above the wavelength count, T_ext <= 0, a tolerance
// outside (0, 1), an unknown opacity format, a missing table file, a
// wavelength grid outside the table) is refused with the key or file named.
#include <gtest/gtest.h>

#include <fstream>

#include "mote/core/deck.hpp"
#include "mote/radiation/opacity.hpp"
#include "mote/radiation/settings.hpp"

namespace {

using namespace mote;

/// A Deck refers to its schema: one that outlives every parsed deck.
const core::DeckSchema& schema() {
  static const core::DeckSchema s = [] {
    core::DeckSchema made;
    radiation::declare(made);
    return made;
  }();
  return s;
}

std::string error_of(const std::string& text) {
  try {
    core::Deck::parse(text, "r.toml", schema());
  } catch (const core::DeckError& e) {
    return e.what();
  }
  return "";
}

TEST(RadiationDeck, ValuesReachTheSolverSettings) {
  const auto d = core::Deck::parse(
      "[radiation]\nbands = 5\nstellar_bins = 40\ntolerance = 1e-6\nilu_fill = 1\nT_ext = 20\nupper = \"reflecting\"\n"
      "star_radius = 2\n",
      "r.toml", schema());
  const auto r = radiation::from_deck(d, units::UnitSystem::cgs_units());
  EXPECT_EQ(r.fld.bands(), 5);
  EXPECT_EQ(r.stellar_bin_edges_cm.size(), 41u);
  EXPECT_DOUBLE_EQ(r.fld.band_edges_cm.front(), 1e-5);
  EXPECT_NEAR(r.fld.band_edges_cm.back(), 0.3, 1e-15);
  EXPECT_DOUBLE_EQ(r.fld.solver.tolerance, 1e-6);
  EXPECT_EQ(r.fld.solver.preconditioning.fill_level, 1);
  EXPECT_EQ(r.fld.boundaries.upper, radiation::RadiationBoundary::Reflecting);
  EXPECT_EQ(r.fld.boundaries.lower, radiation::RadiationBoundary::Reflecting);
  EXPECT_EQ(r.fld.boundaries.inner, radiation::RadiationBoundary::Open);
  EXPECT_DOUBLE_EQ(r.fld.boundaries.T_ext, 20.0);
  EXPECT_DOUBLE_EQ(r.star.radius, 2.0 * units::cgs::R_sun);
  const auto table = r.opacities({1e-4, 1e-3});
  EXPECT_EQ(table.wavelengths(), 40);
  EXPECT_DOUBLE_EQ(table.k_abs(1, 3), 1.0);  // grey default
}

TEST(RadiationDeck, BadInputNamesTheKey) {
  EXPECT_NE(error_of("[radiation]\nbands = 50\nstellar_bins = 20\n").find("radiation.bands"), std::string::npos);
  EXPECT_NE(error_of("[radiation]\nbands = 50\nstellar_bins = 20\n").find("must not exceed"), std::string::npos);
  EXPECT_NE(error_of("[radiation]\nT_ext = 0\n").find("radiation.T_ext"), std::string::npos);
  EXPECT_NE(error_of("[radiation]\ntolerance = 1.5\n").find("radiation.tolerance"), std::string::npos);
  EXPECT_NE(error_of("[radiation]\nopacity = \"mie\"\n").find("radiation.opacity"), std::string::npos);
  EXPECT_NE(error_of("[radiation]\nlambda_min = 1\nlambda_max = 0.5\n").find("radiation.lambda_max"),
            std::string::npos);
  const auto missing = error_of("[radiation]\nopacity = \"dsharp\"\nopacity_file = \"/nonexistent/k.dat\"\n");
  EXPECT_NE(missing.find("cannot be opened: '/nonexistent/k.dat'"), std::string::npos) << missing;
  EXPECT_NE(error_of("[radiation]\nopacity = \"radmc\"\n").find("radiation.opacity_file"), std::string::npos);
}

TEST(RadiationDeck, WavelengthsOutsideTheTableAreRefused) {
  const std::string path = ::testing::TempDir() + "narrow.dat";
  std::ofstream(path) << "1 2\n1e-4 1 1 1\n1e-4 100 1 1\n";  // 1 - 100 um only
  const std::string deck = "[radiation]\nopacity = \"dsharp\"\nopacity_file = \"" + path + "\"\n";
  // Refused when the deck is read, before anything is allocated: the stellar
  // bins' default range 0.1 - 3000 um exceeds the table at both ends.
  const auto error = error_of(deck);
  EXPECT_NE(error.find("radiation.lambda_min"), std::string::npos) << error;
  EXPECT_NE(error.find("radiation.lambda_max"), std::string::npos) << error;
  EXPECT_NE(error.find("the table '" + path + "' covers"), std::string::npos) << error;
  // Inside it, accepted.
  EXPECT_EQ(error_of(deck + "lambda_min = 1e-4\nlambda_max = 1e-2\n"), "");
  // The interpolation itself refuses wavelengths outside the table too.
  const auto table = radiation::read_dsharp_table(path);
  try {
    radiation::interpolate(table, {1e-4}, {1e-5});
    FAIL() << "a wavelength outside the table was interpolated";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lies outside the table"), std::string::npos) << e.what();
  }
}

TEST(RadiationDeck, MalformedTableIsRefusedWhenTheDeckIsRead) {
  const std::string path = ::testing::TempDir() + "malformed.dat";
  std::ofstream(path) << "1 2\n1e-4 1 1 1\n1e-4 100 x 1\n";
  const auto error = error_of("[radiation]\nopacity = \"dsharp\"\nopacity_file = \"" + path + "\"\n");
  EXPECT_NE(error.find("radiation.opacity_file"), std::string::npos) << error;
  EXPECT_NE(error.find(path), std::string::npos) << error;
}

}  // namespace
