// Choosing and vetting the checkpoint a run restarts from (issue 22): a
// checkpoint is used only if it opens, every state dataset matches its
// checksum (h5_file.hpp) and holds finite values, and the attributes match
// their checksum; `--restart latest` falls
// back past defective checkpoints to the newest sound one. The deck of the
// restart may differ from the deck stored in the checkpoint only in keys
// declared KeySpec::restart_mutable() (stop conditions, output cadence,
// progress); any other change is refused unless forced.
#pragma once

#include <string>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"

namespace mote::io {

/// What makes checkpoint `path` unusable (unreadable, a state dataset that fails its checksum or
/// holds a non-finite value, attributes that fail theirs); empty if it is sound. Collective: every rank reads the whole
/// state.
std::string checkpoint_defect(const std::string& path, const core::Comm& comm);

/// `path` if it is sound, else a core::InputError naming it and the defect.
std::string sound_checkpoint(const std::string& path, const core::Comm& comm);

/// The newest sound checkpoint in `dir` as rank 0 lists it (collective: every rank vets the same
/// files); each newer defective one is named in a warning. core::InputError if there is none.
std::string latest_sound_checkpoint(const std::string& dir, const core::Comm& comm);

/// The resolved deck (TOML text) stored in `checkpoint`.
std::string deck_stored_in(const std::string& checkpoint, const core::Comm& comm);

/// Refuses a checkpoint of another problem (core::InputError), then compares `deck` with the
/// deck stored in `checkpoint` (parsed with the same schema): a change of a key that sets the
/// state's size (KeySpec::sets_state_size()) is a core::DeckError even with `force`; changes of
/// restart-mutable keys are logged; any other change is a core::DeckError naming each key with
/// both values, or with `force` a warning per change.
void check_restart_deck(const std::string& checkpoint, const core::Deck& deck, const core::DeckSchema& schema,
                        const std::string& problem, bool force, const core::Comm& comm);

/// Vets `checkpoint`, named by deck key `key`, as the source of part of a new run's initial state (not a restart:
/// the new run's clock starts at 0): it must be sound (checkpoint_defect) and belong to `problem` (else a
/// core::InputError), and the deck stored in it (parsed with `deck`'s schema) must give the same value as `deck`
/// to every key in `keys` (a name ending in '.' stands for its whole table), those that give the stored state its
/// meaning (grid, units, size grid); a core::DeckError names each differing key with both values.
void check_initial_state_source(const std::string& checkpoint, const std::string& key, const core::Deck& deck,
                                const std::string& problem, const std::vector<std::string>& keys,
                                const core::Comm& comm);

}  // namespace mote::io
