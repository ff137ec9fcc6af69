// Input-deck parsing and validation (see include/mote/core/deck.hpp).
#include "mote/core/deck.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace mote::core {

namespace {

struct Located {
  Value value;
  std::string where;  // "deck.toml:12" or "command line 'a.b=1'"
};

std::string where_of(const std::string& file, const toml::source_region& region) {
  return region.begin.line > 0 ? file + ":" + std::to_string(region.begin.line) : file;
}

std::string describe_node(const toml::node& node) {
  if (node.is_boolean()) return "boolean";
  if (node.is_integer()) return "integer " + std::to_string(node.as_integer()->get());
  if (node.is_floating_point()) return "real " + value_to_toml(node.as_floating_point()->get());
  if (node.is_string()) return "string \"" + node.as_string()->get() + "\"";
  if (node.is_array()) return "array";
  if (node.is_table()) return "table";
  return "date/time";
}

/// Converts a TOML node to the declared type, or returns std::nullopt.
std::optional<Value> convert(const toml::node& node, ValueType type) {
  switch (type) {
    case ValueType::Boolean:
      if (node.is_boolean()) return Value(node.as_boolean()->get());
      break;
    case ValueType::Integer:
      if (node.is_integer()) return Value(static_cast<long long>(node.as_integer()->get()));
      break;
    case ValueType::Real:
      if (node.is_floating_point()) return Value(node.as_floating_point()->get());
      if (node.is_integer()) return Value(static_cast<double>(node.as_integer()->get()));
      break;
    case ValueType::String:
      if (node.is_string()) return Value(node.as_string()->get());
      break;
    case ValueType::RealArray:
      if (const auto* arr = node.as_array()) {
        std::vector<double> out;
        for (const auto& el : *arr) {
          if (el.is_floating_point())
            out.push_back(el.as_floating_point()->get());
          else if (el.is_integer())
            out.push_back(static_cast<double>(el.as_integer()->get()));
          else
            return std::nullopt;
        }
        return Value(out);
      }
      break;
  }
  return std::nullopt;
}

std::string expected_text(const KeySpec& spec) {
  std::string e = type_name(spec.type());
  if (!spec.range_text().empty()) e += " " + spec.range_text();
  if (!spec.unit_text().empty()) e += " [" + spec.unit_text() + "]";
  return e;
}

class Validator {
 public:
  Validator(const DeckSchema& schema, std::string file) : schema_(schema), file_(std::move(file)) {}

  void add_file_table(const toml::table& root) {
    for (auto&& [tkey, tnode] : root) {
      const std::string tname(tkey.str());
      const std::string where = where_of(file_, tkey.source());
      const auto* tbl = tnode.as_table();
      if (!tbl) {
        errors_.push_back(where + ": key '" + tname +
                          "' is outside any table; every key belongs to a table such as [run]");
        continue;
      }
      if (!schema_.find_table(tname)) {
        std::string msg = where + ": unknown table [" + tname + "]";
        if (auto s = schema_.closest_table(tname)) msg += " (did you mean [" + *s + "]?)";
        errors_.push_back(msg);
        continue;
      }
      tables_present_.push_back(tname);
      for (auto&& [kkey, knode] : *tbl) add(tname, std::string(kkey.str()), knode, where_of(file_, kkey.source()));
    }
  }

  void add_override(const std::string& text) {
    const std::string where = "command line '" + text + "'";
    const auto eq = text.find('=');
    const auto dot = text.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq) {
      errors_.push_back(where + ": overrides are written table.key=value");
      return;
    }
    const std::string table = text.substr(0, dot), key = text.substr(dot + 1, eq - dot - 1), raw = text.substr(eq + 1);
    if (!schema_.find_table(table)) {
      std::string msg = where + ": unknown table [" + table + "]";
      if (auto s = schema_.closest_table(table)) msg += " (did you mean [" + *s + "]?)";
      errors_.push_back(msg);
      return;
    }
    // Parse the value as TOML; a bare word that is not valid TOML is taken as a string.
    toml::table parsed;
    bool bare_word = false;
    try {
      parsed = toml::parse("v = " + raw);
    } catch (const toml::parse_error&) {
      parsed = toml::table{};
      parsed.insert("v", raw);
      bare_word = true;
    }
    if (std::find(tables_present_.begin(), tables_present_.end(), table) == tables_present_.end())
      tables_present_.push_back(table);
    const KeySpec* spec = schema_.find_key(table, key);
    if (bare_word && spec && spec->type() != ValueType::String) {
      errors_.push_back(where + ": key '" + spec->dotted() + "': '" + raw + "' is not a TOML value (expected " +
                        expected_text(*spec) + "; a number beyond the range of a double, or malformed?)");
      rejected_.push_back(spec->dotted());
      return;
    }
    add(table, key, *parsed.get("v"), where);
  }

  void finish() {
    for (const auto& spec : schema_.keys()) {
      const auto* table = schema_.find_table(spec.table());
      const bool active = !table->optional || present(spec.table());
      if (!active || values_.count(spec.dotted()) || rejected(spec.dotted())) continue;
      if (spec.required())
        errors_.push_back(file_ + ": missing required key '" + spec.dotted() + "' (" + expected_text(spec) + ")" +
                          (spec.doc_text().empty() ? "" : ": " + spec.doc_text()));
    }
  }

  bool present(const std::string& table) const {
    return std::find(tables_present_.begin(), tables_present_.end(), table) != tables_present_.end();
  }

  /// True when `dotted` was given but its value was refused (its error is reported).
  bool rejected(const std::string& dotted) const {
    return std::find(rejected_.begin(), rejected_.end(), dotted) != rejected_.end();
  }

  const std::vector<std::string>& errors() const { return errors_; }
  const std::map<std::string, Located>& values() const { return values_; }

 private:
  void add(const std::string& table, const std::string& key, const toml::node& node, const std::string& where) {
    const std::string dotted = table + "." + key;
    const KeySpec* spec = schema_.find_key(table, key);
    if (!spec) {
      std::string msg = where + ": unknown key '" + dotted + "'";
      if (auto s = schema_.closest_key(dotted)) msg += " (did you mean '" + *s + "'?)";
      errors_.push_back(msg);
      return;
    }
    if (const std::string problem = value_problem(*spec, node); !problem.empty()) {
      errors_.push_back(where + ": key '" + dotted + "': " + problem);
      rejected_.push_back(dotted);
      return;
    }
    values_[dotted] = Located{*convert(node, spec->type()), where};
  }

  /// Empty if `node` is a valid value of `spec`; otherwise what is wrong and what was expected.
  static std::string value_problem(const KeySpec& spec, const toml::node& node) {
    const auto value = convert(node, spec.type());
    if (!value) return "expected " + expected_text(spec) + ", got " + describe_node(node);
    if (const auto why = spec.type_violation(*value); !why.empty())
      return "value " + value_to_toml(*value) + " " + why + "; expected " + expected_text(spec);
    if (!spec.range_violation(*value).empty())
      return "value " + value_to_toml(*value) + " is out of range; expected " + expected_text(spec);
    return {};
  }

  const DeckSchema& schema_;
  std::string file_;
  std::vector<std::string> errors_;
  std::vector<std::string> tables_present_;
  std::vector<std::string> rejected_;
  std::map<std::string, Located> values_;
};

std::string error_report(const std::string& source_name, const std::vector<std::string>& errors) {
  std::string msg = "invalid deck " + source_name + " (" + std::to_string(errors.size()) + " error" +
                    (errors.size() > 1 ? "s" : "") + "):";
  for (const auto& e : errors) msg += "\n  " + e;
  return msg;
}

}  // namespace

Deck Deck::parse(const std::string& text, const std::string& source_name, const DeckSchema& schema,
                 const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& err) {
    const auto& r = err.source();
    throw DeckError("invalid deck " + source_name + ":\n  " + source_name + ":" + std::to_string(r.begin.line) + ":" +
                    std::to_string(r.begin.column) + ": TOML syntax error: " + std::string(err.description()));
  }
  Validator v(schema, source_name);
  v.add_file_table(root);
  for (const auto& o : overrides) v.add_override(o);
  v.finish();
  Deck deck;
  deck.source_ = source_name;
  deck.schema_ = &schema;
  for (const auto& t : schema.tables())
    if (!t.optional || v.present(t.name)) deck.active_tables_.push_back(t.name);
  for (const auto& spec : schema.keys()) {
    if (!deck.has_table(spec.table())) continue;
    const auto it = v.values().find(spec.dotted());
    if (it != v.values().end()) {
      deck.values_[spec.dotted()] = it->second.value;
      deck.where_[spec.dotted()] = it->second.where;
    } else if (!v.rejected(spec.dotted()) && spec.default_opt()) {
      deck.values_[spec.dotted()] = *spec.default_opt();
      deck.where_[spec.dotted()] = source_name + " (default)";
    } else {
      deck.rejected_.push_back(spec.dotted());
    }
    deck.units_[spec.dotted()] = spec.unit_text();
  }
  std::vector<std::string> errors = v.errors();
  for (const auto& e : deck.check_rules(errors.size())) errors.push_back(e);
  if (!errors.empty()) throw DeckError(error_report(source_name, errors));
  return deck;
}

std::vector<std::string> Deck::check_rules(std::size_t earlier_errors) const {
  DeckCheck check(*this);
  std::string unguarded;
  for (const auto& rule : schema_->rules()) {
    try {
      rule(*this, check);
    } catch (const RejectedKey&) {
      // The rule reads a key whose own error is already reported.
    } catch (const InactiveTable& e) {
      if (unguarded.empty()) unguarded = e.what();
    }
  }
  if (!unguarded.empty() && earlier_errors == 0 && check.errors().empty())
    throw std::logic_error(unguarded + ", and no error reports that table missing (the rule needs a has_table guard)");
  return check.errors();
}

Deck Deck::load(const std::string& path, const DeckSchema& schema, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw DeckError("cannot read deck file '" + path + "': is a directory, not a TOML file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DeckError("cannot read deck file '" + path + "': " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw DeckError("cannot read deck file '" + path + "': read error");
  return parse(text.str(), path, schema, overrides);
}

bool Deck::has_table(const std::string& table) const {
  return std::find(active_tables_.begin(), active_tables_.end(), table) != active_tables_.end();
}

bool Deck::has(const std::string& dotted) const { return values_.count(dotted) > 0; }

const Value& Deck::value(const std::string& dotted, ValueType type) const {
  if (std::find(rejected_.begin(), rejected_.end(), dotted) != rejected_.end())
    throw RejectedKey("deck key '" + dotted + "' has no valid value");
  const auto dot = dotted.find('.');
  const KeySpec* spec = schema_->find_key(dotted.substr(0, dot), dotted.substr(dot + 1));
  const auto it = values_.find(dotted);
  if (it == values_.end() && spec && !has_table(dotted.substr(0, dot)))
    throw InactiveTable("deck key '" + dotted + "' is read but the deck has no table [" + dotted.substr(0, dot) + "]");
  if (it == values_.end())
    throw std::logic_error("deck key '" + dotted + "' is not declared or its table is not active");
  if (!spec || spec->type() != type)
    throw std::logic_error("deck key '" + dotted + "' read as " + type_name(type) + " but declared otherwise");
  return it->second;
}

bool Deck::boolean(const std::string& dotted) const { return std::get<bool>(value(dotted, ValueType::Boolean)); }
long long Deck::integer(const std::string& dotted) const {
  return std::get<long long>(value(dotted, ValueType::Integer));
}
double Deck::real(const std::string& dotted) const { return std::get<double>(value(dotted, ValueType::Real)); }
const std::string& Deck::string(const std::string& dotted) const {
  return std::get<std::string>(value(dotted, ValueType::String));
}
const std::vector<double>& Deck::real_array(const std::string& dotted) const {
  return std::get<std::vector<double>>(value(dotted, ValueType::RealArray));
}

const std::string& Deck::where(const std::string& dotted) const {
  const auto it = where_.find(dotted);
  if (it == where_.end())
    throw std::logic_error("deck key '" + dotted + "' is not declared or its table is not active");
  return it->second;
}

void DeckCheck::fail(const std::string& dotted, const std::string& expected) {
  errors_.push_back(deck_.where(dotted) + ": key '" + dotted + "': " + expected);
}

void DeckCheck::fail_missing_table(const std::string& table, const std::string& why) {
  errors_.push_back(deck_.source() + ": missing table [" + table + "]: " + why);
}

std::string DeckCheck::quote(const std::string& other) const {
  const auto it = deck_.values_.find(other);
  if (it == deck_.values_.end()) throw Deck::RejectedKey("deck key '" + other + "' has no valid value");
  return other + " = " + value_to_toml(it->second) + " (" + deck_.where(other) + ")";
}

std::string Deck::to_toml() const {
  std::ostringstream os;
  os << "# resolved deck (source: " << source_ << ")\n";
  for (const auto& table : active_tables_) {
    os << "\n[" << table << "]\n";
    for (const auto& spec : schema_->keys()) {
      if (spec.table() != table) continue;
      os << spec.key() << " = " << value_to_toml(values_.at(spec.dotted()));
      if (!spec.unit_text().empty()) os << "  # " << spec.unit_text();
      os << "\n";
    }
  }
  return os.str();
}

std::vector<KeyChange> Deck::changes_to(const Deck& other) const {
  const auto text = [](const Deck& d, const std::string& dotted) {
    const auto it = d.values_.find(dotted);
    return it == d.values_.end() ? std::string("(absent)") : value_to_toml(it->second);
  };
  std::vector<KeyChange> changes;
  for (const auto& spec : schema_->keys()) {
    const auto mine = values_.find(spec.dotted()), theirs = other.values_.find(spec.dotted());
    const bool same = mine == values_.end() ? theirs == other.values_.end()
                                            : theirs != other.values_.end() && mine->second == theirs->second;
    if (!same)
      changes.push_back({spec.dotted(), text(*this, spec.dotted()), text(other, spec.dotted()),
                         spec.is_restart_mutable(), spec.is_state_size()});
  }
  return changes;
}

}  // namespace mote::core
