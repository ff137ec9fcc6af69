// The main() of every problem executable:
//   <problem> [deck.toml] [table.key=value ...] [--restart FILE|latest [--force]] [--check]
//   <problem> --help | --version | --deck-reference | --kokkos-help
// Order of work: declare the deck (and answer --help, --version and
// --deck-reference before Kokkos starts), parse the command line, validate the
// whole deck with its cross-key rules (nothing allocated or written before it
// is valid), vet the restart's checkpoint and compare its deck (restart.hpp),
// construct the problem, create the output directory, then run the loop. Every failure ends with an exit code of
// core/exit_codes.hpp.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/timers.hpp"
#include "mote/core/units.hpp"
#include "mote/io/simulation.hpp"

namespace mote::io {

/// What a problem's factory receives.
struct ProblemContext {
  const core::Deck& deck;
  const core::Comm& comm;
  const units::UnitSystem& units;
  core::Timers& timers;
  /// True when the run continues from a checkpoint: the state built here is
  /// overwritten by it, so expensive preparation (e.g. a relaxation) may be skipped.
  bool restarting = false;
};

struct ProblemDefinition {
  std::string name;
  std::string summary;
  /// Declares the problem's own deck tables and keys ([run] and [output] are declared for it).
  std::function<void(core::DeckSchema&)> declare;
  /// Builds the initial state. May throw core::DeckError (or std::invalid_argument, from
  /// the modules it builds) for input that only the set-up can judge (e.g. cells per MPI
  /// rank), reported like any deck error (exit 2) before output is created; --check does
  /// not run the set-up, so rules on the deck alone go into declare() (DeckSchema::rule)
  /// so that --check finds them too.
  std::function<std::unique_ptr<Simulation>(const ProblemContext&)> create;
};

/// Deck rules for a problem's declare(): its set-up or reference solution
/// assumes the choice `dotted` = `value` (sph.eos = "adiabatic"), or needs the optional `table`.
core::DeckRule requires_choice(const std::string& problem, const std::string& dotted, const std::string& value);
core::DeckRule requires_table(const std::string& problem, const std::string& table);

/// Runs a problem executable; returns the process exit code (see ExitCode).
int run_problem(int argc, char** argv, const ProblemDefinition& problem);

}  // namespace mote::io
