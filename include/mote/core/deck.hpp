// The input deck: a TOML file plus command-line overrides (table.key=value),
// validated completely against a DeckSchema before anything is allocated or
// written. Every error names the file (or the override), the line, the key and
// what was expected; all errors are reported together in one DeckError.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "mote/core/deck_schema.hpp"

namespace mote::core {

class DeckError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Deck {
 public:
  /// Reads and validates `path`, then applies `overrides` ("table.key=value").
  static Deck load(const std::string& path, const DeckSchema& schema, const std::vector<std::string>& overrides = {});
  /// Same from text; `source_name` is used in messages.
  static Deck parse(const std::string& text, const std::string& source_name, const DeckSchema& schema,
                    const std::vector<std::string>& overrides = {});

  bool has_table(const std::string& table) const;
  bool boolean(const std::string& dotted) const;
  long long integer(const std::string& dotted) const;
  double real(const std::string& dotted) const;
  const std::string& string(const std::string& dotted) const;
  const std::vector<double>& real_array(const std::string& dotted) const;

  /// The resolved deck (every active key, defaults filled in) as TOML text.
  std::string to_toml() const;
  const std::string& source() const { return source_; }

 private:
  const Value& value(const std::string& dotted, ValueType type) const;
  std::string source_;
  std::vector<std::string> active_tables_;
  std::map<std::string, Value> values_;
  std::map<std::string, std::string> units_;
  const DeckSchema* schema_ = nullptr;
};

}  // namespace mote::core
