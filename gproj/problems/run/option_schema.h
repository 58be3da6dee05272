#pragma once
// A problem's options as a typed schema. Every option has an identifier (a keyword argument in
// Python, `--kebab-case` on the command line, a key of the report's "options" object and of the
// service's JSON), a type, a default read off the problem's own Options struct, a range, a unit
// and a one-line doc. CheckOptionValue is the one check of types and ranges for every front end
// (command line, Python, the service), before a run starts; a problem's Options::IsValid guards
// the C++ API, whose callers fill the struct themselves, and adds the rules that join several
// options.

#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/common/input_error.h"

namespace gproj {

enum class OptionType {
  kBool,     // a switch (a flag on the command line)
  kInt,      // an integer
  kNumber,   // a finite real number
  kChoice,   // one of `choices`
  kNumbers,  // a list of `count` finite numbers (0: any length), "a,b,..." on the command line
  kPoints,   // a list of `count` points [x, y, z] (0: any number), "x,y,z,x,y,z,..." on the
             // command line; in Python an (n, 3) array
  kInts,     // a list of `count` integers (0: any length), "a,b,..." on the command line
  // Values of vertices: [[id, value], ...] with 0-based ids and each value within the range;
  // "ID:VALUE,ID:VALUE" on the command line; in Python also a dict {id: value}.
  kVertexValues,
};
// "bool", "int", "number", "choice", "numbers", "points", "ints", "vertex_values"
const char* OptionTypeName(OptionType type);

struct OptionSpec {
  std::string name;  // identifier, e.g. "min_angle"
  OptionType type = OptionType::kNumber;
  std::string doc;               // one line
  std::string unit;              // e.g. "deg", "input units"; empty for pure numbers
  nlohmann::json default_value;  // null: not set unless given
  // Numbers, integers and each value of a list: within [min, max], ends excluded when asked.
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;  // kChoice
  int count = 0;                     // kNumbers, kPoints, kInts
  std::string negation;     // kBool: the identifier of the switch that turns it off ("plain_steps")
  std::string group;        // where the option belongs in help pages, e.g. "solver", "panels"
  std::string placeholder;  // the value's name in help, e.g. "MIN,MAX"
  bool required = false;    // no default: every run must give it

  // The rule of the range ("> 0", "in [0, 59.9]"); empty without one.
  std::string RangeText() const;
};

// Bad option value: names the option (its identifier; front ends spell it their way) and the
// rule broken. `type_mismatch` when the value has the wrong type (Python's TypeError).
class OptionError : public InputError {
 public:
  OptionError(std::string option, std::string rule, bool type_mismatch = false);
  const std::string& option() const { return option_; }
  const std::string& rule() const { return rule_; }
  bool type_mismatch() const { return type_mismatch_; }

 private:
  std::string option_, rule_;
  bool type_mismatch_;
};

// `value` checked against `spec` and normalised (integers as integers, numbers as doubles).
// Throws OptionError.
nlohmann::json CheckOptionValue(const OptionSpec& spec, const nlohmann::json& value);
// Command-line text for `spec` (decimal numbers only, lists separated by commas), checked.
nlohmann::json ParseOptionText(const OptionSpec& spec, const std::string& text);
// `value` as command-line text ("1e-09", "0.01,5").
std::string OptionText(const nlohmann::json& value);
// The spec as the schema's JSON (name, type, doc, unit, default, minimum/maximum, choices, ...).
nlohmann::json OptionSpecJson(const OptionSpec& spec);

// Every option of `specs` checked and the defaults filled in: an object with one key per spec
// that has a value. Unknown names are refused (naming the closest known one).
nlohmann::json CompleteOptions(const std::vector<OptionSpec>& specs, const nlohmann::json& given);

// The options of a problem whose settings are the struct S: specs, each bound to a field of S
// (its default read off S{}), or to a setter with an explicit default.
template <typename S>
class OptionSchema {
 public:
  using Setter = std::function<void(const nlohmann::json&, S*)>;

  // Refines the option just added.
  class Builder {
   public:
    Builder(OptionSpec* spec) : spec_(spec) {}
    Builder& Range(double min, double max) {
      spec_->min = min, spec_->max = max;
      return *this;
    }
    Builder& Positive() {
      spec_->min = 0.0, spec_->min_exclusive = true;
      return *this;
    }
    Builder& NonNegative() {
      spec_->min = 0.0;
      return *this;
    }
    Builder& Below(double max) {
      spec_->max = max, spec_->max_exclusive = true;
      return *this;
    }
    Builder& Choices(std::vector<std::string> choices) {
      spec_->choices = std::move(choices);
      return *this;
    }
    Builder& Unit(std::string unit) {
      spec_->unit = std::move(unit);
      return *this;
    }
    Builder& Group(std::string group) {
      spec_->group = std::move(group);
      return *this;
    }
    Builder& Negation(std::string negation) {
      spec_->negation = std::move(negation);
      return *this;
    }
    Builder& Required() {
      spec_->required = true;
      return *this;
    }
    Builder& Count(int count, std::string placeholder) {
      spec_->count = count, spec_->placeholder = std::move(placeholder);
      return *this;
    }

   private:
    OptionSpec* spec_;
  };

  // An option stored in the field `field` of S (bool, int, double or std::string).
  template <typename T>
  Builder Field(const std::string& name, OptionType type, const std::string& doc,
                std::function<T&(S&)> field) {
    S defaults{};
    return Custom(name, type, doc, nlohmann::json(field(defaults)),
                  [field](const nlohmann::json& value, S* s) { field(*s) = value.get<T>(); });
  }
  // An option without a default (null: not set unless given) stored in `field` of S.
  template <typename T>
  Builder Optional(const std::string& name, OptionType type, const std::string& doc,
                   std::function<T&(S&)> field) {
    return Custom(name, type, doc, nullptr,
                  [field](const nlohmann::json& value, S* s) { field(*s) = value.get<T>(); });
  }
  Builder Custom(const std::string& name, OptionType type, const std::string& doc,
                 nlohmann::json default_value, Setter set) {
    OptionSpec spec;
    spec.name = name, spec.type = type, spec.doc = doc;
    spec.default_value = std::move(default_value);
    specs_.push_back(std::move(spec));
    setters_.push_back(std::move(set));
    return Builder(&specs_.back());
  }

  const std::vector<OptionSpec>& specs() const { return specs_; }

  // S{} with every value of `complete` (CompleteOptions' result) set, in schema order.
  S Apply(const nlohmann::json& complete) const {
    S s{};
    for (size_t i = 0; i < specs_.size(); ++i) {
      const auto it = complete.find(specs_[i].name);
      if (it != complete.end() && !it->is_null()) setters_[i](*it, &s);
    }
    return s;
  }

 private:
  std::vector<OptionSpec> specs_;
  std::vector<Setter> setters_;
};

}  // namespace gproj
