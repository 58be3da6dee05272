#include "gproj/problems/run/option_schema.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace gproj {
namespace {

std::string Compact(double value) {
  char text[32];
  // Integers in full (a seed's 4294967295), other values in %g's short form.
  if (std::abs(value) < 1e10 && std::floor(value) == value)
    std::snprintf(text, sizeof(text), "%.0f", value);
  else
    std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

// The value as a user wrote it, for messages.
std::string Shown(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_float()) return Compact(value.get<double>());
  return value.dump();
}

// Levenshtein distance, for "did you mean".
size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A finite number within the spec's range, or OptionError.
double CheckNumber(const OptionSpec& spec, const nlohmann::json& value, bool integer) {
  const char* expected = integer ? "an integer" : "a number";
  if (!value.is_number() || (integer && value.is_number_float() &&
                             std::floor(value.get<double>()) != value.get<double>()))
    throw OptionError(spec.name, Shown(value) + " is not " + expected, !value.is_number());
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw OptionError(spec.name, Shown(value) + " is not a finite number");
  const bool low = spec.min_exclusive ? !(v > spec.min) : !(v >= spec.min);
  const bool high = spec.max_exclusive ? !(v < spec.max) : !(v <= spec.max);
  if (low || high) throw OptionError(spec.name, Shown(value) + " is not " + spec.RangeText());
  return v;
}

// Decimal text as a number: the whole text, no hexadecimal, finite.
nlohmann::json NumberFromText(const OptionSpec& spec, const std::string& text, bool integer) {
  if (text.empty()) throw OptionError(spec.name, "an empty value is not allowed");
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.find_first_of("xX") != std::string::npos || !std::isfinite(value))
    throw OptionError(spec.name,
                      text + (integer ? " is not an integer" : " is not a finite number"));
  if (integer) {
    if (std::floor(value) != value || text.find_first_of(".eE") != std::string::npos)
      throw OptionError(spec.name, text + " is not an integer");
    return nlohmann::json(static_cast<long long>(value));
  }
  return nlohmann::json(value);
}

// [[id, value], ...] (or {"id": value}) checked: ids 0-based integers, each once, values in range.
nlohmann::json CheckVertexValues(const OptionSpec& spec, const nlohmann::json& value) {
  nlohmann::json pairs = nlohmann::json::array();
  if (value.is_object()) {  // a Python dict: its keys are text; by increasing id
    OptionSpec id_spec;
    id_spec.name = spec.name;
    std::vector<std::pair<long long, nlohmann::json>> items;
    for (const auto& item : value.items())
      items.emplace_back(NumberFromText(id_spec, item.key(), true).get<long long>(), item.value());
    std::sort(items.begin(), items.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [id, v] : items) pairs.push_back({id, v});
  } else if (value.is_array()) {
    pairs = value;
  } else {
    throw OptionError(spec.name, Shown(value) + " is not a list of [vertex, value] pairs", true);
  }
  OptionSpec ids;
  ids.name = spec.name, ids.min = 0.0, ids.max = 2e9;
  nlohmann::json out = nlohmann::json::array();
  std::set<long long> seen;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const nlohmann::json& p = pairs[i];
    if (!p.is_array() || p.size() != 2)
      throw OptionError(spec.name, "entry " + std::to_string(i) + " is not a pair [vertex, value]",
                        !p.is_array());
    const auto id = static_cast<long long>(CheckNumber(ids, p[0], true));
    if (!seen.insert(id).second)
      throw OptionError(spec.name, "vertex " + std::to_string(id) + " is given twice");
    out.push_back({id, CheckNumber(spec, p[1], false)});
  }
  return out;
}

}  // namespace

const char* OptionTypeName(OptionType type) {
  switch (type) {
    case OptionType::kBool:
      return "bool";
    case OptionType::kInt:
      return "int";
    case OptionType::kNumber:
      return "number";
    case OptionType::kChoice:
      return "choice";
    case OptionType::kNumbers:
      return "numbers";
    case OptionType::kPoints:
      return "points";
    case OptionType::kInts:
      return "ints";
    case OptionType::kVertexValues:
      return "vertex_values";
  }
  return "?";
}

std::string OptionSpec::RangeText() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max)
    return std::string("in ") + (min_exclusive ? "(" : "[") + Compact(min) + ", " + Compact(max) +
           (max_exclusive ? ")" : "]");
  if (has_min) return (min_exclusive ? "> " : ">= ") + Compact(min);
  if (has_max) return (max_exclusive ? "< " : "<= ") + Compact(max);
  return "";
}

OptionError::OptionError(std::string option, std::string rule, bool type_mismatch)
    : InputError(option + ": " + rule),
      option_(std::move(option)),
      rule_(std::move(rule)),
      type_mismatch_(type_mismatch) {}

nlohmann::json CheckOptionValue(const OptionSpec& spec, const nlohmann::json& value) {
  switch (spec.type) {
    case OptionType::kBool:
      if (!value.is_boolean())
        throw OptionError(spec.name, Shown(value) + " is not true or false", true);
      return value;
    case OptionType::kInt:
      return nlohmann::json(static_cast<long long>(CheckNumber(spec, value, true)));
    case OptionType::kNumber:
      return nlohmann::json(CheckNumber(spec, value, false));
    case OptionType::kChoice: {
      std::string list;
      for (const std::string& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
      if (!value.is_string())
        throw OptionError(spec.name, Shown(value) + " is not a text; one of " + list, true);
      const std::string text = value.get<std::string>();
      if (std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end())
        throw OptionError(spec.name, "'" + text + "' is not one of " + list);
      return value;
    }
    case OptionType::kInts:
    case OptionType::kNumbers: {
      const bool integers = spec.type == OptionType::kInts;
      if (!value.is_array())
        throw OptionError(spec.name,
                          Shown(value) + " is not a list of " + (integers ? "integers" : "numbers"),
                          true);
      if (spec.count > 0 && static_cast<int>(value.size()) != spec.count)
        throw OptionError(spec.name, "expects " + std::to_string(spec.count) + " numbers (" +
                                         spec.placeholder + "), not " +
                                         std::to_string(value.size()));
      nlohmann::json out = nlohmann::json::array();
      for (const nlohmann::json& v : value) {
        const double number = CheckNumber(spec, v, integers);
        out.push_back(integers ? nlohmann::json(static_cast<long long>(number))
                               : nlohmann::json(number));
      }
      return out;
    }
    case OptionType::kPoints: {
      const std::string expected =
          spec.count > 0 ? std::to_string(spec.count) + " points" : "points";
      if (!value.is_array())
        throw OptionError(spec.name, Shown(value) + " is not a list of " + expected + " (x, y, z)",
                          true);
      if (spec.count > 0 && static_cast<int>(value.size()) != spec.count)
        throw OptionError(spec.name, "expects " + expected + " (" + spec.placeholder + "), not " +
                                         std::to_string(value.size()));
      nlohmann::json out = nlohmann::json::array();
      for (size_t i = 0; i < value.size(); ++i) {
        const nlohmann::json& p = value[i];
        if (!p.is_array() || p.size() != 3)
          throw OptionError(spec.name,
                            "point " + std::to_string(i) + " is not three numbers x, y, z" +
                                (p.is_array() ? " (it has " + std::to_string(p.size()) + ")" : ""),
                            !p.is_array());
        nlohmann::json point = nlohmann::json::array();
        for (const nlohmann::json& v : p) point.push_back(CheckNumber(spec, v, false));
        out.push_back(point);
      }
      return out;
    }
    case OptionType::kVertexValues:
      return CheckVertexValues(spec, value);
  }
  return value;
}

nlohmann::json ParseOptionText(const OptionSpec& spec, const std::string& text) {
  switch (spec.type) {
    case OptionType::kBool:
      if (text == "true" || text == "1") return true;
      if (text == "false" || text == "0") return false;
      throw OptionError(spec.name, text + " is not true or false");
    case OptionType::kInt:
    case OptionType::kNumber:
      return CheckOptionValue(spec, NumberFromText(spec, text, spec.type == OptionType::kInt));
    case OptionType::kChoice:
      if (text.empty()) throw OptionError(spec.name, "an empty value is not allowed");
      return CheckOptionValue(spec, text);
    case OptionType::kInts:
    case OptionType::kNumbers: {
      if (text.empty()) throw OptionError(spec.name, "an empty value is not allowed");
      nlohmann::json values = nlohmann::json::array();
      size_t start = 0;
      while (true) {
        const size_t comma = text.find(',', start);
        values.push_back(NumberFromText(spec, text.substr(start, comma - start),
                                        spec.type == OptionType::kInts));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      return CheckOptionValue(spec, values);
    }
    case OptionType::kPoints: {
      OptionSpec list;
      list.name = spec.name, list.type = OptionType::kNumbers;
      const nlohmann::json numbers = ParseOptionText(list, text);
      if (numbers.size() % 3 != 0 ||
          (spec.count > 0 && static_cast<int>(numbers.size()) != 3 * spec.count))
        throw OptionError(spec.name, "expects " +
                                         (spec.count > 0 ? std::to_string(3 * spec.count)
                                                         : std::string("3 per point")) +
                                         " comma-separated numbers (" + spec.placeholder +
                                         "), not " + std::to_string(numbers.size()));
      nlohmann::json points = nlohmann::json::array();
      for (size_t i = 0; i < numbers.size(); i += 3)
        points.push_back({numbers[i], numbers[i + 1], numbers[i + 2]});
      return CheckOptionValue(spec, points);
    }
    case OptionType::kVertexValues: {
      if (text.empty()) throw OptionError(spec.name, "an empty value is not allowed");
      nlohmann::json pairs = nlohmann::json::array();
      size_t start = 0;
      while (true) {
        const size_t comma = text.find(',', start);
        const std::string word = text.substr(start, comma - start);
        const size_t colon = word.find(':');
        if (colon == std::string::npos)
          throw OptionError(spec.name, "'" + word + "' is not VERTEX:VALUE (e.g. 12:0.5)");
        OptionSpec id;
        id.name = spec.name;
        pairs.push_back({NumberFromText(id, word.substr(0, colon), true),
                         NumberFromText(spec, word.substr(colon + 1), false)});
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      return CheckOptionValue(spec, pairs);
    }
  }
  return nullptr;
}

std::string OptionText(const nlohmann::json& value) {
  // Vertex values: "ID:VALUE,...".
  if (value.is_array() && !value.empty() && value[0].is_array() && value[0].size() == 2 &&
      value[0][0].is_number_integer()) {
    std::string out;
    for (const nlohmann::json& p : value)
      out += (out.empty() ? "" : ",") + Shown(p[0]) + ":" + Shown(p[1]);
    return out;
  }
  if (value.is_array()) {
    std::string out;
    for (const nlohmann::json& v : value) out += (out.empty() ? "" : ",") + OptionText(v);
    return out;
  }
  return Shown(value);
}

nlohmann::json OptionSpecJson(const OptionSpec& spec) {
  nlohmann::json j = {{"name", spec.name},
                      {"type", OptionTypeName(spec.type)},
                      {"doc", spec.doc},
                      {"default", spec.default_value}};
  if (!spec.unit.empty()) j["unit"] = spec.unit;
  if (!spec.group.empty()) j["group"] = spec.group;
  if (std::isfinite(spec.min)) {
    j["minimum"] = spec.min;
    j["minimum_exclusive"] = spec.min_exclusive;
  }
  if (std::isfinite(spec.max)) {
    j["maximum"] = spec.max;
    j["maximum_exclusive"] = spec.max_exclusive;
  }
  if (!spec.choices.empty()) j["choices"] = spec.choices;
  if (spec.type == OptionType::kNumbers || spec.type == OptionType::kPoints ||
      spec.type == OptionType::kInts)
    j["count"] = spec.count;
  if (!spec.negation.empty()) j["negation"] = spec.negation;
  if (spec.required) j["required"] = true;
  return j;
}

nlohmann::json CompleteOptions(const std::vector<OptionSpec>& specs, const nlohmann::json& given) {
  if (!given.is_null() && !given.is_object())
    throw InputError("options must be an object of named values");
  nlohmann::json out = nlohmann::json::object();
  if (given.is_object())
    for (const auto& item : given.items()) {
      const std::string name = item.key();
      const auto spec = std::find_if(specs.begin(), specs.end(),
                                     [&](const OptionSpec& s) { return s.name == name; });
      if (spec != specs.end()) continue;
      std::string closest;
      size_t best = 4;  // suggest only near misses
      for (const OptionSpec& s : specs)
        if (const size_t d = EditDistance(name, s.name); d < best) best = d, closest = s.name;
      throw OptionError(
          name,
          "there is no such option" + (closest.empty() ? "" : " (did you mean " + closest + "?)"),
          true);
    }
  for (const OptionSpec& spec : specs) {
    const nlohmann::json* value = &spec.default_value;
    if (given.is_object() && given.contains(spec.name) && !given[spec.name].is_null())
      value = &given[spec.name];
    if (value->is_null() && spec.required)
      throw OptionError(spec.name, "this option is required", true);
    if (!value->is_null()) out[spec.name] = CheckOptionValue(spec, *value);
  }
  return out;
}

}  // namespace gproj
