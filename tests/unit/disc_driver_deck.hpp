// The deck of the disc driver's unit tests: a closed box of 12 x 24 cells at
// R = 8-12 au, |theta| <= 0.15, three dust species, evolving gas; tests
// change it with overrides.
#pragma once

#include <string>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/disc/disc_simulation.hpp"

namespace mote::test_decks {

inline const char* kDiscDriverDeck = R"(
[grid]
nr = 12
R_in = 8.0
R_out = 12.0
r_spacing = "log"
ntheta = 24
theta_min = -0.15
theta_max = 0.15
[boundaries]
inner = "closed"
outer = "closed"
lower = "closed"
upper = "closed"
[gas]
R_ref = 10.0
T_ref = 88.5
alpha = 1e-2
Sigma0 = 5e-6
inner_boundary = "closed"
outer_boundary = "closed"
[dust]
sizes = [1e-3, 1e-1, 10.0]
[driver]
evolve_gas = true
)";

/// The deck with `tables` (TOML text, e.g. a [coagulation] table) appended and the overrides applied.
inline core::Deck disc_driver_deck(const std::vector<std::string>& overrides = {}, const std::string& tables = "") {
  static const core::DeckSchema schema = [] {
    core::DeckSchema d;
    disc::DiscSimulation::declare(d);
    return d;
  }();
  return core::Deck::parse(std::string(kDiscDriverDeck) + tables, "disc_driver_deck", schema, overrides);
}

}  // namespace mote::test_decks
