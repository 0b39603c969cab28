#include "base/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "base/suggest.h"

namespace oit {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

ParamValue parse_value(const ParamSpec& spec, const std::string& text, const std::string& owner) {
  auto fail = [&](const std::string& why) -> std::invalid_argument {
    return std::invalid_argument(owner + ": parameter '" + spec.name + "' = '" + text + "' " + why +
                                 "; allowed: " + spec.range_text());
  };
  switch (spec.type) {
    case ParamType::integer: {
      if (spec.accepts_auto && text == "auto") return std::string("auto");
      int64_t value = 0;
      auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (end != text.data() + text.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
        throw fail("is not an integer");
      if (ec == std::errc::result_out_of_range) throw fail("is out of range");
      if (value < spec.min || value > spec.max) throw fail("is out of range");
      return value;
    }
    case ParamType::real: {
      size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(text, &used);
      } catch (const std::out_of_range&) {
        throw fail("is out of range");  // 1e400: a number, too large for a double
      } catch (const std::exception&) {
        throw fail("is not a number");
      }
      if (used != text.size() || !std::isfinite(value)) throw fail("is not a finite number");
      if (value < spec.min || value > spec.max) throw fail("is out of range");
      return value;
    }
    case ParamType::boolean:
      if (text == "true" || text == "1" || text == "on") return true;
      if (text == "false" || text == "0" || text == "off") return false;
      throw fail("is not a boolean");
    case ParamType::choice:
      for (const auto& choice : spec.choices)
        if (choice == text) return text;
      throw fail("is not a valid choice" + did_you_mean(text, spec.choices));
    case ParamType::path: {
      if (text.empty()) return text;
      for (char c : text)
        if (static_cast<unsigned char>(c) <= ' ' || c == ',' || c == '=' || c == 0x7f)
          throw fail("contains whitespace, a control character, ',' or '=' (they separate parameters and list "
                     "values in canonical text and --set); rename the file or link it under a plain name");
      std::error_code ec;
      const auto status = std::filesystem::status(text, ec);
      if (!std::filesystem::exists(status)) {
        const std::filesystem::path given(text);
        throw fail(given.is_relative() ? "does not exist (relative to " +
                                             std::filesystem::current_path(ec).string() + ")"
                                       : "does not exist");
      }
      if (std::filesystem::is_directory(status)) throw fail("is a directory, not a file");
      // A FIFO would block its reader forever, a device feed it endlessly.
      if (!std::filesystem::is_regular_file(status))
        throw fail("is not a regular file (a FIFO, device or socket); give a file");
      if (!std::ifstream(text, std::ios::binary)) throw fail("cannot be opened for reading");
      return text;
    }
  }
  throw fail("has an unknown type");
}

}  // namespace

ParamSpec ParamSpec::integer(std::string name, int64_t default_value, int64_t min, int64_t max,
                             std::string description) {
  return {std::move(name), ParamType::integer, std::to_string(default_value), double(min), double(max), {},
          std::move(description)};
}
ParamSpec ParamSpec::integer_or_auto(std::string name, std::string default_value, int64_t min, int64_t max,
                                     std::string description) {
  ParamSpec spec{std::move(name), ParamType::integer, std::move(default_value), double(min), double(max), {},
                 std::move(description)};
  spec.accepts_auto = true;
  return spec;
}
ParamSpec ParamSpec::real(std::string name, double default_value, double min, double max, std::string description) {
  return {std::move(name), ParamType::real, format_number(default_value), min, max, {}, std::move(description)};
}
ParamSpec ParamSpec::boolean(std::string name, bool default_value, std::string description) {
  return {std::move(name), ParamType::boolean, default_value ? "true" : "false", 0, 1, {}, std::move(description)};
}
ParamSpec ParamSpec::choice(std::string name, std::string default_value, std::vector<std::string> choices,
                            std::string description) {
  return {std::move(name), ParamType::choice, std::move(default_value), 0, 0, std::move(choices),
          std::move(description)};
}

ParamSpec ParamSpec::path(std::string name, std::string default_value, std::string description) {
  return {std::move(name), ParamType::path, std::move(default_value), 0, 0, {}, std::move(description)};
}

std::string ParamSpec::range_text() const {
  switch (type) {
    case ParamType::integer:
      return "integer in [" + std::to_string(int64_t(min)) + ", " + std::to_string(int64_t(max)) + "]" +
             (accepts_auto ? " or auto" : "");
    case ParamType::real: return "number in [" + format_number(min) + ", " + format_number(max) + "]";
    case ParamType::boolean: return "true or false";
    case ParamType::choice: {
      std::string text = "one of {";
      for (size_t i = 0; i < choices.size(); ++i) text += (i ? ", " : "") + choices[i];
      return text + "}";
    }
    case ParamType::path: return "path of a readable file without spaces, ',' or '=' (empty: none)";
  }
  return "";
}

ParamSet::ParamSet(const ParamSchema& schema, const RawParams& raw, const std::string& owner) : owner_(owner) {
  std::vector<std::string> names;
  for (const auto& spec : schema) names.push_back(spec.name);
  for (const auto& [key, text] : raw) {
    if (std::find(names.begin(), names.end(), key) != names.end()) continue;
    std::string list;
    for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
    throw std::invalid_argument(owner + " has no parameter '" + key + "'" + did_you_mean(key, names) +
                                " (its parameters: " + (list.empty() ? "none" : list) + ")");
  }
  for (const auto& spec : schema) {
    auto it = raw.find(spec.name);
    values_.emplace_back(spec.name, parse_value(spec, it != raw.end() ? it->second : spec.default_value, owner));
  }
}

const ParamValue& ParamSet::find(const std::string& name) const {
  for (const auto& [key, value] : values_)
    if (key == name) return value;
  throw std::logic_error(owner_ + ": parameter '" + name + "' is not in the schema");
}

int64_t ParamSet::integer(const std::string& name) const {
  const ParamValue& value = find(name);
  if (!std::holds_alternative<int64_t>(value))
    throw std::logic_error(owner_ + ": parameter '" + name + "' is '" + to_string(value) + "', not an integer");
  return std::get<int64_t>(value);
}
bool ParamSet::is_auto(const std::string& name) const {
  const ParamValue& value = find(name);
  return std::holds_alternative<std::string>(value) && std::get<std::string>(value) == "auto";
}
double ParamSet::real(const std::string& name) const { return std::get<double>(find(name)); }
bool ParamSet::boolean(const std::string& name) const { return std::get<bool>(find(name)); }
const std::string& ParamSet::choice(const std::string& name) const { return std::get<std::string>(find(name)); }
const std::string& ParamSet::path(const std::string& name) const { return std::get<std::string>(find(name)); }

std::string to_string(const ParamValue& value) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>) return v;
        else if constexpr (std::is_same_v<T, double>) return format_number(v);
        else return std::to_string(v);
      },
      value);
}

std::string ParamSet::canonical() const {
  std::string text;
  for (const auto& [key, value] : values_) text += (text.empty() ? "" : " ") + key + "=" + to_string(value);
  return text;
}

void parse_assignment(const std::string& text, RawParams& into) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw std::invalid_argument("'" + text + "' is not of the form key=value");
  }
  into[text.substr(0, eq)] = text.substr(eq + 1);
}

}  // namespace oit
