// The main() of every problem executable (see include/mote/io/problem_main.hpp).
#include "mote/io/problem_main.hpp"

#include <iostream>
#include <optional>
#include <vector>

#include "mote/core/log.hpp"
#include "mote/core/runtime.hpp"
#include "mote/io/output_files.hpp"
#include "mote/io/run_loop.hpp"

namespace mote::io {

namespace {

struct CommandLine {
  std::optional<std::string> deck_path;
  std::vector<std::string> overrides;
  std::optional<std::string> restart;
  bool help = false, reference = false, check_only = false;
};

CommandLine parse_command_line(int argc, char** argv) {
  CommandLine cl;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      cl.help = true;
    } else if (arg == "--deck-reference") {
      cl.reference = true;
    } else if (arg == "--check") {
      cl.check_only = true;
    } else if (arg == "--restart") {
      if (i + 1 >= argc) throw core::DeckError("--restart needs a checkpoint file or 'latest'");
      cl.restart = argv[++i];
    } else if (arg.rfind("--kokkos", 0) == 0) {
      continue;  // left for Kokkos
    } else if (arg.rfind("-", 0) == 0) {
      throw core::DeckError("unknown option '" + arg + "' (see --help)");
    } else if (arg.find('=') != std::string::npos) {
      cl.overrides.push_back(arg);
    } else if (!cl.deck_path) {
      cl.deck_path = arg;
    } else {
      throw core::DeckError("more than one deck given ('" + *cl.deck_path + "' and '" + arg + "')");
    }
  }
  return cl;
}

std::string usage(const ProblemDefinition& p) {
  return p.name + ": " + p.summary + "\n\nusage: " + p.name +
         " [deck.toml] [table.key=value ...] [--restart FILE|latest] [--check]\n"
         "       " +
         p.name +
         " --help | --deck-reference\n\n"
         "  --restart FILE    continue from a checkpoint; without a deck, the deck stored in it is used\n"
         "  --restart latest  continue from the newest checkpoint in output.dir\n"
         "  --check           validate the deck, print it resolved, and exit\n"
         "exit codes: 0 finished (or stopped at run.max_steps), 1 error, 2 invalid input,\n"
         "            3 non-finite value, 4 interrupted by SIGINT/SIGTERM (checkpoint written)\n\n"
         "deck keys:\n";
}

/// The deck stored in a checkpoint, for restarts without a deck argument.
std::string deck_from_checkpoint(const std::string& path, const core::Comm& comm) {
  H5File file(path, H5File::Mode::Read, comm);
  return file.read_attribute_string("/", "deck");
}

}  // namespace

int run_problem(int argc, char** argv, const ProblemDefinition& problem) {
  core::Runtime runtime(argc, argv);
  const core::Comm& comm = runtime.comm();
  core::DeckSchema schema;
  RunSettings::declare(schema);
  problem.declare(schema);

  CommandLine cl;
  std::optional<core::Deck> deck;
  std::optional<std::string> restart;
  try {
    cl = parse_command_line(argc, argv);
    if (cl.help) {
      logging::info(usage(problem), schema.help_text());
      return kExitFinished;
    }
    if (cl.reference) {
      logging::info("## Problem `", problem.name, "`\n\n", problem.summary, "\n\n", schema.markdown());
      return kExitFinished;
    }
    if (cl.deck_path) {
      deck = core::Deck::load(*cl.deck_path, schema, cl.overrides);
    } else if (cl.restart && *cl.restart != "latest") {
      std::string text;
      try {
        text = deck_from_checkpoint(*cl.restart, comm);
      } catch (const std::exception& e) {
        throw core::DeckError("cannot read the deck stored in checkpoint '" + *cl.restart + "': " + e.what());
      }
      deck = core::Deck::parse(text, "deck of " + *cl.restart, schema, cl.overrides);
    } else {
      throw core::DeckError("no deck given (see --help)");
    }
    if (cl.restart) {
      restart = *cl.restart;
      if (*restart == "latest") {
        const auto found = latest_numbered(deck->string("output.dir"), "checkpoint", "h5");
        if (!found) throw core::DeckError("--restart latest: no checkpoint in '" + deck->string("output.dir") + "'");
        restart = *found;
      }
    }
  } catch (const core::DeckError& e) {
    if (comm.is_root()) std::cerr << "error: " << e.what() << std::endl;
    return kExitBadInput;
  }

  logging::info("mote ", MOTE_VERSION_STRING, " : problem ", problem.name, " : ", runtime.describe());
  logging::info(deck->to_toml());
  if (cl.check_only) return kExitFinished;

  try {
    const RunSettings settings = RunSettings::from_deck(*deck);
    const units::UnitSystem units = units::unit_system_by_name(settings.units);
    core::Timers timers;
    std::unique_ptr<Simulation> sim;
    try {
      core::ScopedTimer timer(timers, "setup");
      sim = problem.create(ProblemContext{*deck, comm, units, timers, restart.has_value()});
    } catch (const core::DeckError& e) {
      if (comm.is_root()) std::cerr << "error: " << e.what() << std::endl;
      return kExitBadInput;
    }
    RunLoop loop(settings, problem.name, *deck, units, comm, timers);
    return loop.run(*sim, restart);
  } catch (const std::exception& e) {
    logging::error(e.what());
    return kExitError;
  }
}

}  // namespace mote::io
