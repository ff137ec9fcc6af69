// The main() of every problem executable:
//   <problem> [deck.toml] [table.key=value ...] [--restart FILE|latest] [--check]
//   <problem> --help | --deck-reference
// Order of work: parse the command line, declare and validate the whole deck
// (nothing allocated or written before it is valid), construct the problem,
// create the output directory, then run the loop.
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
  /// Builds the initial state. May throw core::DeckError for inconsistent input
  /// (reported like any deck error, before output is created).
  std::function<std::unique_ptr<Simulation>(const ProblemContext&)> create;
};

/// Runs a problem executable; returns the process exit code (see ExitCode).
int run_problem(int argc, char** argv, const ProblemDefinition& problem);

}  // namespace mote::io
