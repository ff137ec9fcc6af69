// The input deck: a TOML file plus command-line overrides (table.key=value),
// validated completely against a DeckSchema before anything is allocated or
// written: every key on its own (type, range, finiteness), then the schema's
// cross-key rules (DeckSchema::rule) on the resolved values. Every error names
// the file (or the override), the line, the key and what was expected; all
// errors are reported together in one DeckError.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "mote/core/deck_schema.hpp"
#include "mote/core/exit_codes.hpp"

namespace mote::core {

class DeckError : public InputError {
 public:
  using InputError::InputError;
};

/// A key whose resolved value differs between two decks ("(absent)" where its table is off).
struct KeyChange {
  std::string key;
  std::string before, after;  // TOML text of the values
  bool restart_mutable;       // declared KeySpec::restart_mutable()
  bool state_size;            // declared KeySpec::sets_state_size()
};

class Deck {
 public:
  /// Reads and validates `path`, then applies `overrides` ("table.key=value").
  static Deck load(const std::string& path, const DeckSchema& schema, const std::vector<std::string>& overrides = {});
  /// Same from text; `source_name` is used in messages.
  static Deck parse(const std::string& text, const std::string& source_name, const DeckSchema& schema,
                    const std::vector<std::string>& overrides = {});

  bool has_table(const std::string& table) const;
  /// True if the schema declares `dotted` and the deck gives it a value (its table active).
  bool has(const std::string& dotted) const;
  bool boolean(const std::string& dotted) const;
  long long integer(const std::string& dotted) const;
  double real(const std::string& dotted) const;
  const std::string& string(const std::string& dotted) const;
  const std::vector<double>& real_array(const std::string& dotted) const;

  /// Where `dotted` got its value: "deck.toml:12", "command line 'a.b=1'" or "deck.toml (default)".
  const std::string& where(const std::string& dotted) const;

  /// The resolved deck (every active key, defaults filled in) as TOML text.
  std::string to_toml() const;
  /// The keys whose resolved values differ from this deck's in `other` (same schema), in declaration order.
  std::vector<KeyChange> changes_to(const Deck& other) const;
  const std::string& source() const { return source_; }
  /// The schema the deck was validated against.
  const DeckSchema& schema() const { return *schema_; }

 private:
  /// Thrown when a rule reads a key whose value was rejected: that rule is skipped,
  /// the key's own error is already reported.
  struct RejectedKey : std::logic_error {
    using std::logic_error::logic_error;
  };
  /// Thrown when a rule reads a declared key of an optional table the deck does not have: that
  /// rule is skipped where another error (the missing table, from DeckCheck::fail_missing_table)
  /// is reported; a logic error (the rule needs a has_table guard) where none is.
  struct InactiveTable : std::logic_error {
    using std::logic_error::logic_error;
  };
  friend class DeckCheck;
  const Value& value(const std::string& dotted, ValueType type) const;
  /// The rules' errors; `earlier_errors` counts the keys' own.
  std::vector<std::string> check_rules(std::size_t earlier_errors) const;
  std::string source_;
  std::vector<std::string> active_tables_;
  std::map<std::string, Value> values_;
  std::map<std::string, std::string> where_;
  std::vector<std::string> rejected_;
  std::map<std::string, std::string> units_;
  const DeckSchema* schema_ = nullptr;
};

/// What a cross-key rule (DeckSchema::rule) reports into: one error per broken
/// rule, naming the key, where it was set and what was expected.
class DeckCheck {
 public:
  explicit DeckCheck(const Deck& deck) : deck_(deck) {}
  /// Records that `dotted` breaks a rule; `expected` says what would be allowed
  /// ("must exceed grid.R_in = 2 (deck.toml:5)").
  void fail(const std::string& dotted, const std::string& expected);
  /// Records that the deck lacks the optional `table` that a problem needs.
  void fail_missing_table(const std::string& table, const std::string& why);
  /// `other` written as "grid.R_in = 2 (deck.toml:5)", for messages that name a second key.
  std::string quote(const std::string& other) const;
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  const Deck& deck_;
  std::vector<std::string> errors_;
};

}  // namespace mote::core
