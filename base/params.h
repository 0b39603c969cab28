#pragma once
// Typed, validated parameters shared by techniques and scenes. A schema lists
// each parameter's type, default and range; user text ("k=16") is checked
// against it once, at construction, and errors name the key and the range.
#include <cstdint>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "base/suggest.h"

namespace oit {

enum class ParamType { integer, real, boolean, choice, path };

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::integer;
  std::string default_value;         // as the user would type it
  double min = 0.0;                  // inclusive range for integer/real
  double max = 0.0;
  std::vector<std::string> choices;  // for choice
  // path: a file the owner reads. Empty means "no file"; otherwise it must
  // exist and be readable when the ParamSet is built. Paths with whitespace,
  // control characters, ',' or '=' are refused rather than escaped: canonical
  // text separates parameters by spaces and keys from values by '=', and
  // `bench --set key=v1,v2` splits lists at ','; a refused name can be
  // linked or renamed, whereas escaping would leak into every CSV reader.
  std::string description;
  // Integer parameters only: the value may also be "auto", which the owner
  // resolves itself (e.g. k from the view's depth complexity).
  bool accepts_auto = false;

  static ParamSpec integer(std::string name, int64_t default_value, int64_t min, int64_t max, std::string description);
  static ParamSpec real(std::string name, double default_value, double min, double max, std::string description);
  static ParamSpec integer_or_auto(std::string name, std::string default_value, int64_t min, int64_t max,
                                   std::string description);
  static ParamSpec boolean(std::string name, bool default_value, std::string description);
  static ParamSpec choice(std::string name, std::string default_value, std::vector<std::string> choices,
                          std::string description);
  static ParamSpec path(std::string name, std::string default_value, std::string description);
  std::string range_text() const;    // "[1, 64]", "{drop, blend}", "{true, false}", "path ..."
};

// The values of a choice parameter, declared once by its owner: each value
// (an enum, or a number such as a sample count) with the text the user types
// and canonical text shows. The table builds the ParamSpec, so the names are
// not listed a second time, and ParamSet::choice(name, table) turns the
// validated text back into the value, so no owner compares choice strings.
template <typename E>
class Choices {
 public:
  struct Entry {
    E value;
    const char* name;
  };
  Choices(std::initializer_list<Entry> entries) : entries_(entries) {}

  // The schema entry: these names in this order, `default_value`'s as default.
  ParamSpec spec(std::string param, E default_value, std::string description) const {
    return ParamSpec::choice(std::move(param), name(default_value), names(), std::move(description));
  }
  // Every name, in table order (e.g. a quality sweep over all values).
  std::vector<std::string> names() const {
    std::vector<std::string> names;
    for (const Entry& entry : entries_) names.emplace_back(entry.name);
    return names;
  }
  const char* name(E value) const {
    for (const Entry& entry : entries_)
      if (entry.value == value) return entry.name;
    throw std::logic_error("a choice value has no name in its table");
  }
  // The value named `text`, or nullptr.
  const E* find(const std::string& text) const {
    for (const Entry& entry : entries_)
      if (text == entry.name) return &entry.value;
    return nullptr;
  }
  E value(const std::string& text) const {
    if (const E* found = find(text)) return *found;
    throw std::invalid_argument("'" + text + "' is not " + spec("", entries_.begin()->value, "").range_text() +
                                did_you_mean(text, names()));
  }

 private:
  std::vector<Entry> entries_;
};

using ParamSchema = std::vector<ParamSpec>;
using RawParams = std::map<std::string, std::string>;
using ParamValue = std::variant<int64_t, double, bool, std::string>;

// The validated values of every parameter of a schema (defaults filled in).
class ParamSet {
 public:
  ParamSet() = default;
  ParamSet(const ParamSchema& schema, const RawParams& raw, const std::string& owner);

  // Throws std::logic_error when the value is "auto" (check is_auto first).
  int64_t integer(const std::string& name) const;
  // True when an integer_or_auto parameter was given (or defaults to) "auto".
  bool is_auto(const std::string& name) const;
  double real(const std::string& name) const;
  bool boolean(const std::string& name) const;
  // The chosen text; owners read their own choices as values with the
  // overload below.
  const std::string& choice(const std::string& name) const;
  template <typename E>
  E choice(const std::string& name, const Choices<E>& table) const {
    const std::string& text = choice(name);
    if (const E* value = table.find(text)) return *value;
    // The schema entry was not built from this table (Choices::spec).
    throw std::logic_error(owner_ + ": parameter '" + name + "' = '" + text + "' is not in the table it is read with");
  }
  // A path parameter as given ("" when unset); it existed and was readable
  // when this set was built.
  const std::string& path(const std::string& name) const;
  // "k=16 tail=drop" in schema order: the canonical text for CSV and cache keys.
  std::string canonical() const;
  const std::vector<std::pair<std::string, ParamValue>>& values() const { return values_; }

 private:
  const ParamValue& find(const std::string& name) const;
  std::string owner_;
  std::vector<std::pair<std::string, ParamValue>> values_;
};

// Parses "key=value" into raw params; throws naming the malformed text.
void parse_assignment(const std::string& text, RawParams& into);
std::string to_string(const ParamValue& value);

}  // namespace oit
