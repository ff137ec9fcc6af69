// Choosing and vetting a restart's checkpoint (see include/mote/io/restart.hpp).
#include "mote/io/restart.hpp"

#include <exception>
#include <sstream>
#include <vector>

#include "mote/core/log.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/output_files.hpp"

namespace mote::io {

std::string checkpoint_defect(const std::string& path, const core::Comm& comm) {
  try {
    const H5File file(path, H5File::Mode::Read, comm);
    const std::vector<std::string> state = file.datasets("/state");
    if (state.empty()) return "it holds no state datasets";
    for (const auto& name : state)
      if (std::string defect = file.check_state_dataset(name); !defect.empty()) return defect;
    if (std::string defect = file.check_attributes(); !defect.empty()) return defect;
  } catch (const std::exception& e) {
    return std::string("it cannot be read: ") + e.what();
  }
  return {};
}

std::string sound_checkpoint(const std::string& path, const core::Comm& comm) {
  if (const std::string defect = checkpoint_defect(path, comm); !defect.empty())
    throw core::InputError("cannot restart from checkpoint '" + path + "': " + defect);
  return path;
}

namespace {

/// Rank 0's list of the checkpoints in `dir`, on every rank (a listing per rank could differ where a
/// network file system caches directories, and every rank must open the same files).
std::vector<std::string> checkpoints_listed_on_root(const std::string& dir, const core::Comm& comm) {
  std::string joined;
  if (comm.is_root())
    for (const auto& path : numbered_files(dir, "checkpoint", "h5")) joined += path + '\0';
  joined = comm.broadcast(joined);
  std::vector<std::string> paths;
  std::istringstream lines(joined);
  for (std::string path; std::getline(lines, path, '\0');) paths.push_back(path);
  return paths;
}

}  // namespace

std::string latest_sound_checkpoint(const std::string& dir, const core::Comm& comm) {
  const std::vector<std::string> candidates = checkpoints_listed_on_root(dir, comm);
  if (candidates.empty()) throw core::InputError("--restart latest: no checkpoint in '" + dir + "'");
  for (const auto& path : candidates) {
    const std::string defect = checkpoint_defect(path, comm);
    if (defect.empty()) return path;
    logging::warn("--restart latest: skipping checkpoint '", path, "': ", defect);
  }
  throw core::InputError("--restart latest: none of the " + std::to_string(candidates.size()) + " checkpoints in '" +
                         dir + "' is sound (see the warnings above)");
}

std::string deck_stored_in(const std::string& checkpoint, const core::Comm& comm) {
  const H5File file(checkpoint, H5File::Mode::Read, comm);
  return file.read_attribute_string("/", "deck");
}

namespace {

std::string problem_stored_in(const std::string& checkpoint, const core::Comm& comm) {
  const H5File file(checkpoint, H5File::Mode::Read, comm);
  return file.read_attribute_string("/", "problem");
}

/// A core::InputError unless `checkpoint` was written by `problem` (`what` opens the message).
void refuse_other_problem(const std::string& checkpoint, const std::string& problem, const std::string& what,
                          const core::Comm& comm) {
  if (const std::string stored = problem_stored_in(checkpoint, comm); stored != problem)
    throw core::InputError(what + " '" + checkpoint + "' belongs to problem '" + stored + "', not '" + problem + "'");
}

std::string describe(const core::KeyChange& c) {
  return c.key + " = " + c.before + " in the checkpoint, " + c.after + " now";
}

}  // namespace

void check_restart_deck(const std::string& checkpoint, const core::Deck& deck, const core::DeckSchema& schema,
                        const std::string& problem, bool force, const core::Comm& comm) {
  refuse_other_problem(checkpoint, problem, "checkpoint", comm);
  std::vector<core::KeyChange> changes;
  try {
    changes =
        core::Deck::parse(deck_stored_in(checkpoint, comm), "deck stored in " + checkpoint, schema).changes_to(deck);
  } catch (const std::exception& e) {
    if (!force)
      throw core::DeckError("cannot compare the deck with the one stored in checkpoint '" + checkpoint +
                            "' (--force to restart without the comparison): " + e.what());
    logging::warn("--force: restarting without comparing the deck with the checkpoint's: ", e.what());
    return;
  }
  std::string resized;
  for (const auto& c : changes)
    if (c.state_size) resized += "\n  " + describe(c);
  if (!resized.empty())
    throw core::DeckError("the deck changes the size of the state stored in checkpoint '" + checkpoint +
                          "' (a resolution or a count of particles, species or bands), which no restart can change, "
                          "not even with --force:" +
                          resized);
  std::string refused;
  for (const auto& c : changes) {
    if (c.restart_mutable)
      logging::info("restart changes ", describe(c));
    else if (force)
      logging::warn("--force: restart changes ", describe(c));
    else
      refused += "\n  " + describe(c);
  }
  if (!refused.empty())
    throw core::DeckError("the deck differs from the one stored in checkpoint '" + checkpoint +
                          "' in keys that may not change on restart (--force to accept):" + refused);
}

void check_initial_state_source(const std::string& checkpoint, const std::string& key, const core::Deck& deck,
                                const std::string& problem, const std::vector<std::string>& keys,
                                const core::Comm& comm) {
  if (const std::string defect = checkpoint_defect(checkpoint, comm); !defect.empty())
    throw core::InputError(key + ": checkpoint '" + checkpoint + "' cannot be used: " + defect);
  refuse_other_problem(checkpoint, problem, key + ": checkpoint", comm);
  std::vector<core::KeyChange> changes;
  try {
    changes = core::Deck::parse(deck_stored_in(checkpoint, comm), "deck stored in " + checkpoint, deck.schema())
                  .changes_to(deck);
  } catch (const std::exception& e) {
    throw core::DeckError(key + ": cannot compare the deck with the one stored in checkpoint '" + checkpoint +
                          "': " + e.what());
  }
  const auto named = [&keys](const std::string& dotted) {
    for (const auto& k : keys)
      if (k.back() == '.' ? dotted.rfind(k, 0) == 0 : dotted == k) return true;
    return false;
  };
  std::string differing;
  for (const auto& c : changes)
    if (named(c.key)) differing += "\n  " + describe(c);
  if (!differing.empty())
    throw core::DeckError(key + ": the deck differs from the one stored in checkpoint '" + checkpoint +
                          "' in keys that give its state a meaning:" + differing);
}

}  // namespace mote::io
