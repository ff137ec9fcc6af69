// The prologue every SPH problem executable shares: in declare(), the engine's
// deck tables ([sph], and [dust] when the problem has dust) and the rules on
// the equation of state and the dust method it is set up for; in create(), the
// one-rank check (the SPH engine has no particle decomposition yet), the
// engine configuration for the problem's dimension and the dust settings.
#pragma once

#include <string>
#include <vector>

#include "mote/io/problem_main.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/dust_settings.hpp"

namespace mote::sph {

struct SphProblemDeclaration {
  std::string eos;                        ///< "isothermal" or "adiabatic" required; empty: either
  std::vector<std::string> dust_methods;  ///< dust.method values the set-up supports; empty: no [dust] table
  bool dust_required = false;             ///< the [dust] table must be present
};

/// Declares [sph] (and [dust]) with the problem's rules.
void declare_sph_problem(core::DeckSchema& schema, const std::string& problem, const SphProblemDeclaration& what);

struct SphProblemStart {
  SphConfig cfg;
  DustSettings dust;  ///< from [dust] (defaults when the deck has none)
};

/// One MPI rank (else core::DeckError naming the problem), config_from_deck(deck, dim), DustSettings::from_deck.
SphProblemStart start_sph_problem(const io::ProblemContext& ctx, const std::string& problem, int dim);

}  // namespace mote::sph
