// Declarations of input-deck keys (see include/mote/core/deck_schema.hpp).
#include "mote/core/deck_schema.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "mote/core/log.hpp"

namespace mote::core {

const char* type_name(ValueType type) {
  switch (type) {
    case ValueType::Boolean:
      return "boolean";
    case ValueType::Integer:
      return "integer";
    case ValueType::Real:
      return "real";
    case ValueType::String:
      return "string";
    case ValueType::RealArray:
      return "array of reals";
  }
  return "?";
}

std::string value_to_toml(const Value& value) {
  struct Visitor {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(long long i) const { return std::to_string(i); }
    std::string operator()(double d) const {
      // Shortest of %.15g/%.17g that reads back exactly; always with a decimal point or exponent.
      std::string text = logging::format("%.15g", d);
      if (std::strtod(text.c_str(), nullptr) != d) text = logging::format("%.17g", d);
      if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
      return text;
    }
    std::string operator()(const std::string& s) const {  // a TOML basic string, control characters escaped
      std::string out = "\"";
      for (const char c : s) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\')
          out += std::string("\\") + c;
        else if (c == '\n')
          out += "\\n";
        else if (c == '\t')
          out += "\\t";
        else if (c == '\r')
          out += "\\r";
        else if (byte < 0x20 || byte == 0x7f)
          out += logging::format("\\u%04x", byte);
        else
          out += c;
      }
      return out + "\"";
    }
    std::string operator()(const std::vector<double>& v) const {
      std::string out = "[";
      for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + (*this)(v[i]);
      return out + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

KeySpec::KeySpec(std::string table, std::string key, ValueType type)
    : table_(std::move(table)), key_(std::move(key)), type_(type) {}

KeySpec& KeySpec::doc(std::string text) {
  doc_ = std::move(text);
  return *this;
}
KeySpec& KeySpec::unit(std::string text) {
  unit_ = std::move(text);
  return *this;
}

KeySpec& KeySpec::default_value(Value value) {
  // Accept integer literals for real keys so that declarations read naturally.
  if (type_ == ValueType::Real && std::holds_alternative<long long>(value))
    value = static_cast<double>(std::get<long long>(value));
  if (type_ == ValueType::Integer && std::holds_alternative<bool>(value))
    throw std::logic_error(dotted() + ": bool default for an integer key");
  default_ = std::move(value);
  return *this;
}

KeySpec& KeySpec::min(double bound) {
  lower_ = bound;
  lower_strict_ = false;
  return *this;
}
KeySpec& KeySpec::greater_than(double bound) {
  lower_ = bound;
  lower_strict_ = true;
  return *this;
}
KeySpec& KeySpec::max(double bound) {
  upper_ = bound;
  upper_strict_ = false;
  return *this;
}
KeySpec& KeySpec::less_than(double bound) {
  upper_ = bound;
  upper_strict_ = true;
  return *this;
}
KeySpec& KeySpec::one_of(std::vector<std::string> choices) {
  choices_ = std::move(choices);
  return *this;
}
KeySpec& KeySpec::allow_non_finite() {
  non_finite_allowed_ = true;
  return *this;
}
KeySpec& KeySpec::int64() {
  int64_ = true;
  return *this;
}
KeySpec& KeySpec::restart_mutable() {
  restart_mutable_ = true;
  return *this;
}
KeySpec& KeySpec::sets_state_size() {
  state_size_ = true;
  return *this;
}

std::string KeySpec::type_violation(const Value& value) const {
  auto finite = [](double x) { return std::isfinite(x); };
  if (const auto* d = std::get_if<double>(&value); d && !non_finite_allowed_ && !finite(*d)) return "is not finite";
  if (const auto* a = std::get_if<std::vector<double>>(&value);
      a && !non_finite_allowed_ && !std::all_of(a->begin(), a->end(), finite))
    return "holds a value that is not finite";
  if (const auto* i = std::get_if<long long>(&value); i && !int64_) {
    constexpr long long lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
    if (*i < lo || *i > hi) return logging::cat("does not fit the key's C++ type int (", lo, " to ", hi, ")");
  }
  return {};
}

std::string KeySpec::range_text() const {
  std::vector<std::string> parts;
  if (lower_) parts.push_back(logging::cat(lower_strict_ ? "> " : ">= ", logging::format("%g", *lower_)));
  if (upper_) parts.push_back(logging::cat(upper_strict_ ? "< " : "<= ", logging::format("%g", *upper_)));
  if (!choices_.empty()) {
    std::string c = "one of";
    for (size_t i = 0; i < choices_.size(); ++i) c += (i ? ", \"" : " \"") + choices_[i] + "\"";
    parts.push_back(c);
  }
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? " and " : "") + parts[i];
  return out;
}

std::string KeySpec::range_violation(const Value& value) const {
  auto check_number = [&](double x) {
    const bool low_bad = lower_ && (lower_strict_ ? !(x > *lower_) : !(x >= *lower_));
    const bool high_bad = upper_ && (upper_strict_ ? !(x < *upper_) : !(x <= *upper_));
    return low_bad || high_bad;
  };
  bool bad = false;
  if (const auto* d = std::get_if<double>(&value)) bad = check_number(*d);
  if (const auto* i = std::get_if<long long>(&value)) bad = check_number(static_cast<double>(*i));
  if (const auto* a = std::get_if<std::vector<double>>(&value)) bad = std::any_of(a->begin(), a->end(), check_number);
  if (const auto* s = std::get_if<std::string>(&value))
    bad = !choices_.empty() && std::find(choices_.begin(), choices_.end(), *s) == choices_.end();
  return bad ? range_text() : std::string();
}

TableSpec& DeckSchema::table(const std::string& name, const std::string& doc, bool optional) {
  for (auto& t : tables_)
    if (t.name == name) return t;
  tables_.push_back({name, doc, optional});
  return tables_.back();
}

KeySpec& DeckSchema::add(const std::string& dotted, ValueType type) {
  const auto dot = dotted.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == dotted.size() ||
      dotted.find('.', dot + 1) != std::string::npos)
    throw std::logic_error("deck key '" + dotted + "' must be written table.key");
  const std::string table = dotted.substr(0, dot), key = dotted.substr(dot + 1);
  if (!find_table(table)) throw std::logic_error("deck key '" + dotted + "' declared before its table");
  if (find_key(table, key)) throw std::logic_error("deck key '" + dotted + "' declared twice");
  keys_.emplace_back(table, key, type);
  return keys_.back();
}

KeySpec& DeckSchema::boolean(const std::string& dotted) { return add(dotted, ValueType::Boolean); }
KeySpec& DeckSchema::integer(const std::string& dotted) { return add(dotted, ValueType::Integer); }
KeySpec& DeckSchema::real(const std::string& dotted) { return add(dotted, ValueType::Real); }
KeySpec& DeckSchema::string(const std::string& dotted) { return add(dotted, ValueType::String); }
KeySpec& DeckSchema::real_array(const std::string& dotted) { return add(dotted, ValueType::RealArray); }
void DeckSchema::rule(DeckRule rule) { rules_.push_back(std::move(rule)); }

const TableSpec* DeckSchema::find_table(const std::string& name) const {
  for (const auto& t : tables_)
    if (t.name == name) return &t;
  return nullptr;
}

const KeySpec* DeckSchema::find_key(const std::string& table, const std::string& key) const {
  for (const auto& k : keys_)
    if (k.table() == table && k.key() == key) return &k;
  return nullptr;
}

int edit_distance(const std::string& a, const std::string& b) {
  std::vector<int> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

namespace {
std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  int best_d = 0;
  for (const auto& c : candidates) {
    const int d = edit_distance(word, c);
    if (!best || d < best_d) {
      best = c;
      best_d = d;
    }
  }
  const int allowed = std::max(2, static_cast<int>(word.size()) / 3);
  if (best && best_d <= allowed) return best;
  return std::nullopt;
}
}  // namespace

std::optional<std::string> DeckSchema::closest_key(const std::string& dotted) const {
  std::vector<std::string> all;
  for (const auto& k : keys_) all.push_back(k.dotted());
  return closest(dotted, all);
}

std::optional<std::string> DeckSchema::closest_table(const std::string& name) const {
  std::vector<std::string> all;
  for (const auto& t : tables_) all.push_back(t.name);
  return closest(name, all);
}

std::string DeckSchema::help_text() const {
  std::ostringstream os;
  for (const auto& t : tables_) {
    os << "[" << t.name << "]" << (t.optional ? "  (optional: present = enabled)" : "") << "\n    " << t.doc << "\n";
    for (const auto& k : keys_) {
      if (k.table() != t.name) continue;
      os << "  " << k.key() << " (" << type_name(k.type()) << ")";
      os << (k.required() ? "  required" : "  default " + value_to_toml(*k.default_opt()));
      if (!k.unit_text().empty()) os << "  [" << k.unit_text() << "]";
      if (!k.range_text().empty()) os << "  " << k.range_text();
      if (k.is_restart_mutable()) os << "  (may change on restart)";
      if (k.is_state_size()) os << "  (sets the state's size: never changes on restart)";
      os << "\n      " << k.doc_text() << "\n";
    }
  }
  return os.str();
}

std::vector<std::string> DeckSchema::undocumented() const {
  const auto blank = [](const std::string& text) { return text.find_first_not_of(" \t\n") == std::string::npos; };
  std::vector<std::string> out;
  for (const auto& t : tables_)
    if (blank(t.doc)) out.push_back("[" + t.name + "]");
  for (const auto& k : keys_)
    if (blank(k.doc_text())) out.push_back(k.table() + "." + k.key());
  return out;
}

std::string DeckSchema::markdown() const {
  std::ostringstream os;
  for (const auto& t : tables_) {
    os << "### `[" << t.name << "]`" << (t.optional ? " (optional; present = enabled)" : "") << "\n\n"
       << t.doc << "\n\n";
    os << "| key | type | default | unit | allowed | description |\n|---|---|---|---|---|---|\n";
    for (const auto& k : keys_) {
      if (k.table() != t.name) continue;
      os << "| `" << k.key() << "` | " << type_name(k.type()) << " | "
         << (k.required() ? "**required**" : "`" + value_to_toml(*k.default_opt()) + "`") << " | " << k.unit_text()
         << " | " << k.range_text() << " | " << k.doc_text()
         << (k.is_restart_mutable() ? " May change on restart." : "")
         << (k.is_state_size() ? " Sets the state's size: never changes on restart." : "") << " |\n";
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace mote::core
