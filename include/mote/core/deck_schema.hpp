// Declarations of input-deck keys. Every module declares the keys it owns,
// with type, default, unit, allowed range and a one-line description, and the
// rules that tie several keys together (R_out > R_in, array lengths); the
// Deck (deck.hpp) is validated against the union of these declarations before
// any allocation or output. Reals must be finite unless a key allows inf/nan;
// integers must fit the C++ type they are read into (int unless declared
// 64-bit). The same declarations produce --help and the deck reference in docs.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace mote::core {

enum class ValueType { Boolean, Integer, Real, String, RealArray };

using Value = std::variant<bool, long long, double, std::string, std::vector<double>>;

class Deck;
class DeckCheck;
/// A cross-key rule: reads the validated deck and reports each violation into the DeckCheck.
using DeckRule = std::function<void(const Deck&, DeckCheck&)>;

const char* type_name(ValueType type);
/// TOML text of a value ("1.5", "true", "\"name\"", "[1.0, 2.0]").
std::string value_to_toml(const Value& value);

class KeySpec {
 public:
  KeySpec(std::string table, std::string key, ValueType type);

  KeySpec& doc(std::string text);
  KeySpec& unit(std::string text);
  /// Gives the key a default; a key without one is required.
  KeySpec& default_value(Value value);
  KeySpec& min(double bound);           // value >= bound (every element for arrays)
  KeySpec& greater_than(double bound);  // value > bound
  KeySpec& max(double bound);           // value <= bound
  KeySpec& less_than(double bound);     // value < bound
  KeySpec& one_of(std::vector<std::string> choices);
  /// Accepts inf and nan (reals are otherwise required to be finite).
  KeySpec& allow_non_finite();
  /// The integer is read as a 64-bit long long (otherwise it must fit an int).
  KeySpec& int64();
  /// The key may differ between a checkpoint's deck and the deck of its restart
  /// (stop conditions, output cadence, progress); any other change is refused.
  KeySpec& restart_mutable();
  /// The key sets the size of the stored state (a resolution, a count of particles, species or
  /// bands): a restart can never change it, not even with --force.
  KeySpec& sets_state_size();

  const std::string& table() const { return table_; }
  const std::string& key() const { return key_; }
  std::string dotted() const { return table_ + "." + key_; }
  ValueType type() const { return type_; }
  const std::string& doc_text() const { return doc_; }
  const std::string& unit_text() const { return unit_; }
  const std::optional<Value>& default_opt() const { return default_; }
  bool required() const { return !default_.has_value(); }
  const std::vector<std::string>& choices() const { return choices_; }
  bool is_restart_mutable() const { return restart_mutable_; }
  bool is_state_size() const { return state_size_; }

  /// Empty if the value is allowed; otherwise what was expected ("> 0", "one of ...").
  std::string range_violation(const Value& value) const;
  /// Empty if the value fits the key's C++ type; otherwise why not ("not finite", "outside int").
  std::string type_violation(const Value& value) const;
  /// Human description of the allowed range ("> 0, <= 1"), empty if unrestricted.
  std::string range_text() const;

 private:
  std::string table_, key_;
  ValueType type_;
  std::string doc_, unit_;
  std::optional<Value> default_;
  std::optional<double> lower_, upper_;
  bool lower_strict_ = false, upper_strict_ = false;
  std::vector<std::string> choices_;
  bool non_finite_allowed_ = false;
  bool int64_ = false;
  bool restart_mutable_ = false;
  bool state_size_ = false;
};

struct TableSpec {
  std::string name;
  std::string doc;
  /// Optional tables switch a capability on by being present ([dust], [radiation]);
  /// their required keys are required only then.
  bool optional = false;
};

class DeckSchema {
 public:
  /// Declares a table (once; re-declaring with the same name returns the first).
  TableSpec& table(const std::string& name, const std::string& doc, bool optional = false);

  KeySpec& boolean(const std::string& dotted);
  KeySpec& integer(const std::string& dotted);
  KeySpec& real(const std::string& dotted);
  KeySpec& string(const std::string& dotted);
  KeySpec& real_array(const std::string& dotted);
  /// Adds a cross-key rule, run on every deck after its keys passed their own checks.
  void rule(DeckRule rule);

  const TableSpec* find_table(const std::string& name) const;
  const KeySpec* find_key(const std::string& table, const std::string& key) const;
  const std::vector<TableSpec>& tables() const { return tables_; }
  const std::vector<KeySpec>& keys() const { return keys_; }
  const std::vector<DeckRule>& rules() const { return rules_; }
  /// Declared keys closest to `dotted` by edit distance (for "did you mean").
  std::optional<std::string> closest_key(const std::string& dotted) const;
  std::optional<std::string> closest_table(const std::string& name) const;

  /// Plain-text listing for --help.
  std::string help_text() const;
  /// Markdown reference (docs/deck reference).
  std::string markdown() const;
  /// Tables ("[name]") and keys ("table.key") declared without a description.
  std::vector<std::string> undocumented() const;

 private:
  KeySpec& add(const std::string& dotted, ValueType type);
  std::vector<TableSpec> tables_;
  std::vector<KeySpec> keys_;
  std::vector<DeckRule> rules_;
};

/// Levenshtein edit distance.
int edit_distance(const std::string& a, const std::string& b);

}  // namespace mote::core
