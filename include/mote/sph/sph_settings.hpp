// Deck table [sph]: the run-time parameters of SphConfig (PL15 sec. 3:
// kernel, h_fact, equation of state, artificial viscosity alpha/beta (eq.
// 31-32), conductivity alpha_u (eq. 34-35), Courant number, damping (eq. 56)).
#pragma once

#include "mote/core/deck.hpp"
#include "mote/sph/config.hpp"

namespace mote::sph {

void declare_settings(core::DeckSchema& schema);
/// SphConfig from the deck; `dim` is set by the problem.
SphConfig config_from_deck(const core::Deck& deck, int dim);

}  // namespace mote::sph
