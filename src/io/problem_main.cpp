// The main() of every problem executable (see include/mote/io/problem_main.hpp).
#include "mote/io/problem_main.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <regex>
#include <stdexcept>
#include <vector>

#include "mote/core/deck_schema.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/core/runtime.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/restart.hpp"
#include "mote/io/run_loop.hpp"

namespace mote::io {

namespace {

struct CommandLine {
  std::optional<std::string> deck_path;
  std::vector<std::string> overrides;
  std::optional<std::string> restart;
  bool check_only = false;
  bool force = false;                 // accept a restart whose deck changes keys that may not change
  std::vector<std::string> warnings;  // said once the command line is read
};

/// True for an argument that reads as a deck key ("grid.nx") rather than a deck file.
bool looks_like_key(const std::string& arg) {
  static const std::regex key(R"([A-Za-z_][A-Za-z0-9_]*\.[A-Za-z_][A-Za-z0-9_]*)");
  std::error_code ec;
  return std::regex_match(arg, key) && !std::filesystem::exists(arg, ec) &&
         std::filesystem::path(arg).extension() != ".toml";
}

/// A warning if `override` sets a key that one of `earlier` already sets (the last applies, so that
/// a script may follow its common overrides with particular ones); empty otherwise.
std::string repeated_key_warning(const std::vector<std::string>& earlier, const std::string& override) {
  const std::string key = override.substr(0, override.find('='));
  for (const auto& e : earlier)
    if (e.substr(0, e.find('=')) == key)
      return "key '" + key + "' set twice on the command line: '" + override + "' applies, not '" + e + "'";
  return "";
}

CommandLine parse_command_line(int argc, char** argv) {
  CommandLine cl;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--check") {
      cl.check_only = true;
    } else if (arg == "--force") {
      cl.force = true;
    } else if (arg == "--restart") {
      if (i + 1 >= argc || std::string(argv[i + 1]).rfind("-", 0) == 0)
        throw core::DeckError(
            "--restart needs a checkpoint file or 'latest' (a file whose name starts with '-' "
            "as ./NAME)");
      if (cl.restart) throw core::DeckError("--restart given twice ('" + *cl.restart + "' and '" + argv[i + 1] + "')");
      cl.restart = argv[++i];
    } else if (arg.rfind("--kokkos", 0) == 0) {
      continue;  // left for Kokkos
    } else if (arg.rfind("-", 0) == 0) {
      throw core::DeckError("unknown option '" + arg + "' (see --help)");
    } else if (arg.find('=') != std::string::npos) {
      if (std::string w = repeated_key_warning(cl.overrides, arg); !w.empty()) cl.warnings.push_back(std::move(w));
      cl.overrides.push_back(arg);
    } else if (looks_like_key(arg)) {
      throw core::DeckError("'" + arg + "' is not a file; an override needs a value: " + arg + "=VALUE");
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
         " [deck.toml] [table.key=value ...] [--restart FILE|latest [--force]] [--check]\n"
         "       " +
         p.name +
         " --help | --version | --deck-reference\n\n"
         "  --restart FILE    continue from a checkpoint; without a deck, the deck stored in it is used,\n"
         "                    writing beside the checkpoint, without its run.max_steps\n"
         "  --restart latest  continue from the newest sound checkpoint in output.dir (of the directory's own\n"
         "                    run), skipping any that fails its checksum or holds non-finite values\n"
         "  --force           restart even though the deck changes keys that may not change on restart\n"
         "  --check           validate the deck (every rule the run applies but those only the set-up can judge,\n"
         "                    such as cells per MPI rank), print it resolved, and exit\n"
         "  --version         print the version of mote and exit\n"
         "  --kokkos-help     Kokkos's own options\n"
         "exit codes: 0 finished (or stopped at run.max_steps), 1 internal error, 2 invalid input,\n"
         "            3 non-finite value or time-step below run.dt_min, 4 interrupted by SIGINT/SIGTERM\n"
         "            (checkpoint written), 5 file I/O error (docs/quickstart.md)\n\n"
         "deck keys:\n";
}

/// Answers --help, --version and --deck-reference, which need no parallel runtime:
/// before Kokkos starts, so that its banner does not bury mote's help.
std::optional<int> answer_information_request(int argc, char** argv, const ProblemDefinition& problem,
                                              const core::DeckSchema& schema) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << usage(problem) << schema.help_text() << std::flush;
      return core::kExitFinished;
    }
    if (arg == "--version") {
      std::cout << "mote " << MOTE_VERSION_STRING << " (" << problem.name << ")" << std::endl;
      return core::kExitFinished;
    }
    if (arg == "--deck-reference") {
      std::cout << "## Problem `" << problem.name << "`\n\n"
                << problem.summary << "\n\n"
                << schema.markdown() << std::endl;
      const auto missing = schema.undocumented();
      if (missing.empty()) return core::kExitFinished;
      std::cerr << "error: " << problem.name << " declares deck entries without a description:";
      for (const auto& name : missing) std::cerr << " " << name;
      std::cerr << std::endl;
      return core::kExitError;
    }
  }
  return std::nullopt;
}

/// Prints `error` (on the root rank) and returns its exit code.
int report(const std::exception& error, const core::Comm& comm) {
  if (comm.is_root()) std::cerr << "error: " << error.what() << std::endl;
  return core::exit_code_of(error);
}

/// The exit code of a run that `error` ended. The typed failures (bad input, numerical, I/O) are
/// thrown on every rank together; any other exception (memory exhausted, a bug) may be this rank's
/// alone, which would leave the other ranks waiting for it: on several ranks it ends them all (exit 1).
int stop_after(const std::exception& error, const core::Comm& comm) {
  const bool out_of_memory = dynamic_cast<const std::bad_alloc*>(&error) != nullptr;
  const std::string what = out_of_memory ? "out of memory (" + std::string(error.what()) + ")" : error.what();
  const core::ExitCode code = core::exit_code_of(error);
  if (code != core::kExitError || comm.size() == 1) {
    logging::error(what);
    return code;
  }
  logging::error(what, " on rank ", comm.rank(), ": stopping every rank");
  comm.abort(code);
}

/// The deck of a restart from `checkpoint` without a deck argument: the stored
/// one, writing beside the checkpoint (never into its output.dir resolved from
/// the current directory) and without its stop condition run.max_steps; the
/// command line's overrides come last and win over both.
core::Deck stored_deck(const std::string& checkpoint, const CommandLine& cl, const core::DeckSchema& schema,
                       const core::Comm& comm) {
  std::string text;
  try {
    text = deck_stored_in(checkpoint, comm);
  } catch (const std::exception& e) {
    throw core::DeckError("cannot read the deck stored in checkpoint '" + checkpoint + "': " + e.what());
  }
  const auto dir = std::filesystem::absolute(checkpoint).parent_path().lexically_normal();
  std::vector<std::string> overrides = {"output.dir=" + core::value_to_toml(core::Value(dir.string())),
                                        "run.max_steps=0"};
  overrides.insert(overrides.end(), cl.overrides.begin(), cl.overrides.end());
  return core::Deck::parse(text, "deck of " + checkpoint, schema, overrides);
}

/// Every snapshot and checkpoint stores the resolved deck in one HDF5 attribute (h5_file.hpp): a longer
/// deck is refused before any work (every write of its run failed, exit 5, before 2026-12-07).
void check_deck_fits_the_files(const core::Deck& deck) {
  const std::size_t bytes = deck.to_toml().size();
  if (bytes > kLongestStringAttribute)
    throw core::DeckError(deck.source() + ": the resolved deck takes " + std::to_string(bytes) +
                          " bytes; snapshots and checkpoints store it in one attribute of at most " +
                          std::to_string(kLongestStringAttribute) +
                          ": shorten its longest lists (output.snapshot_times: use output.snapshot_dt; cell edges: "
                          "a spacing)");
}

/// The problem's initial state. Its set-up may find values that the deck's rules cannot judge
/// (rules on the rank count, on derived values): a std::invalid_argument it throws is bad input
/// (exit 2) like a core::DeckError, before any output exists.
std::unique_ptr<Simulation> set_up(const ProblemDefinition& problem, const ProblemContext& context) {
  try {
    return problem.create(context);
  } catch (const std::invalid_argument& e) {
    throw core::DeckError(problem.name + ": the set-up rejects the deck: " + e.what());
  }
}

}  // namespace

core::DeckRule requires_choice(const std::string& problem, const std::string& dotted, const std::string& value) {
  const std::string table = dotted.substr(0, dotted.find('.'));
  return [=](const core::Deck& d, core::DeckCheck& check) {
    if (d.has_table(table) && d.string(dotted) != value) check.fail(dotted, problem + " needs \"" + value + "\"");
  };
}

core::DeckRule requires_table(const std::string& problem, const std::string& table) {
  return [=](const core::Deck& d, core::DeckCheck& check) {
    if (!d.has_table(table)) check.fail_missing_table(table, problem + " needs it");
  };
}

int run_problem(int argc, char** argv, const ProblemDefinition& problem) {
  core::DeckSchema schema;
  RunSettings::declare(schema);
  problem.declare(schema);
  if (const auto answered = answer_information_request(argc, argv, problem, schema)) return *answered;
  const bool kokkos_help = std::find(argv + 1, argv + argc, std::string("--kokkos-help")) != argv + argc;
  core::Runtime runtime(argc, argv);  // prints Kokkos's help for --kokkos-help
  if (kokkos_help) return core::kExitFinished;
  const core::Comm& comm = runtime.comm();

  CommandLine cl;
  std::optional<core::Deck> deck;
  std::optional<std::string> restart;
  try {
    cl = parse_command_line(argc, argv);
    if (comm.is_root())
      for (const auto& w : cl.warnings) logging::warn(w);
    if (cl.deck_path) {
      deck = core::Deck::load(*cl.deck_path, schema, cl.overrides);
    } else if (cl.restart && *cl.restart != "latest") {
      deck = stored_deck(*cl.restart, cl, schema, comm);
    } else {
      throw core::DeckError(cl.restart ? "--restart latest needs the deck, whose output.dir holds the checkpoints "
                                         "(or give a checkpoint file instead of 'latest')"
                                       : "no deck given (see --help)");
    }
    if (cl.force && !cl.restart) throw core::DeckError("--force is only for restarts (--restart)");
    check_deck_fits_the_files(*deck);
    if (cl.restart) {
      restart = *cl.restart == "latest" ? latest_sound_checkpoint(deck->string("output.dir"), comm)
                                        : sound_checkpoint(*cl.restart, comm);
      check_restart_deck(*restart, *deck, schema, problem.name, cl.force, comm);
    }
  } catch (const core::InputError& e) {
    return report(e, comm);
  }

  logging::info("mote ", MOTE_VERSION_STRING, " : problem ", problem.name, " : ", runtime.describe());
  logging::info(deck->to_toml());
  if (cl.check_only) return core::kExitFinished;

  try {
    const RunSettings settings = RunSettings::from_deck(*deck);
    const units::UnitSystem units = units::unit_system_by_name(settings.units);
    core::Timers timers;
    std::unique_ptr<Simulation> sim;
    {
      core::ScopedTimer timer(timers, "setup");
      sim = set_up(problem, ProblemContext{*deck, comm, units, timers, restart.has_value()});
    }
    RunLoop loop(settings, problem.name, *deck, units, comm, timers);
    return loop.run(*sim, restart);
  } catch (const core::InputError& e) {
    return report(e, comm);
  } catch (const core::PeerIOError& e) {
    return core::exit_code_of(e);  // reported by the rank that failed
  } catch (const std::exception& e) {
    return stop_after(e, comm);
  }
}

}  // namespace mote::io
