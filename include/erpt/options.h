// An integrator's options, each declared once: its long name, help, range or choices, and the
// settings field it sets. The default is that field's value in a default-constructed
// RenderSettings, so it lives in one place (the settings struct). Front ends (the CLI, the
// Python module) build their options, help and error messages from these declarations, and
// render() checks programmatic settings against the same ranges.
#pragma once

#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "erpt/error.h"
#include "erpt/render.h"

namespace erpt {

enum class OptionKind { Integer, Real, Choice, Flag, List };

struct OptionSpec {
  OptionSpec(std::string name_, std::string help_, OptionKind kind_)
      : name(std::move(name_)), help(std::move(help_)), kind(kind_) {}

  std::string name;  // long name without dashes: "chain-length"
  std::string help;  // one line, without the default (front ends append it)
  OptionKind kind = OptionKind::Integer;
  // Integer and Real: the values allowed, [min, max] (min excluded when minOpen).
  double min = 0, max = 0;
  bool minOpen = false;
  std::vector<std::string> choices;  // Choice: the words it takes, in help order
  // Parses `value` (text as on a command line; "true" for a flag) into the settings; throws
  // UsageError naming the option when the text is not a value it takes.
  std::function<void(RenderSettings&, const std::string& value)> set;
  // The option's value in `settings` as text it would parse (the default: get(RenderSettings{})).
  std::function<std::string(const RenderSettings&)> get;
  // Integer and Real: the value as a number, for the range check of programmatic settings.
  std::function<double(const RenderSettings&)> number;
  // Optional: why giving the option has no effect with these settings (the other options
  // already applied), e.g. "applies to --pmc-adapt region only"; empty when it has one. Front
  // ends refuse a given option that has none rather than ignore it.
  std::function<std::string(const RenderSettings&)> inapplicable;

  std::string flag() const { return "--" + name; }
  std::string defaultText() const { return get ? get(RenderSettings{}) : std::string(); }
  // "[1, 16777216]", "(0, 10000]", "one of paper, mixed, lens, caustic".
  std::string allowed() const;
};

// Throws UsageError "--name must be in [min, max]" when the settings' value is out of range
// (Integer and Real options; the others are checked when set).
void checkOptionRange(const OptionSpec& option, const RenderSettings& settings);

// Makers. `field` is a generic lambda returning the settings field by reference, e.g.
// [](auto& s) -> auto& { return s.erpt.chainLength; }, so that one accessor serves set and get.
std::string formatOptionNumber(double value);
long long parseOptionInteger(const OptionSpec& option, const std::string& text);
double parseOptionReal(const OptionSpec& option, const std::string& text);

template <class Field>
OptionSpec integerOption(std::string name, std::string help, double min, double max, Field field) {
  OptionSpec o(std::move(name), std::move(help), OptionKind::Integer);
  o.min = min, o.max = max;
  o.number = [field](const RenderSettings& s) { return double(field(s)); };
  o.get = [field](const RenderSettings& s) { return std::to_string(field(s)); };
  o.set = [field, o](RenderSettings& s, const std::string& text) {
    field(s) = static_cast<std::remove_reference_t<decltype(field(s))>>(parseOptionInteger(o, text));
  };
  return o;
}

template <class Field>
OptionSpec realOption(std::string name, std::string help, double min, double max, Field field, bool minOpen = false) {
  OptionSpec o(std::move(name), std::move(help), OptionKind::Real);
  o.min = min, o.max = max, o.minOpen = minOpen;
  o.number = [field](const RenderSettings& s) { return double(field(s)); };
  o.get = [field](const RenderSettings& s) { return formatOptionNumber(double(field(s))); };
  o.set = [field, o](RenderSettings& s, const std::string& text) {
    field(s) = static_cast<std::remove_reference_t<decltype(field(s))>>(parseOptionReal(o, text));
  };
  return o;
}

// `values` pairs each word with the enum value it sets.
template <class Enum, class Field>
OptionSpec choiceOption(std::string name, std::string help, std::vector<std::pair<std::string, Enum>> values,
                        Field field) {
  OptionSpec o(std::move(name), std::move(help), OptionKind::Choice);
  for (const auto& v : values) o.choices.push_back(v.first);
  o.get = [field, values](const RenderSettings& s) {
    for (const auto& [word, value] : values)
      if (field(s) == value) return word;
    return std::string();
  };
  o.set = [field, values, flag = o.flag(), allowed = o.allowed()](RenderSettings& s, const std::string& text) {
    for (const auto& [word, value] : values)
      if (word == text) {
        field(s) = value;
        return;
      }
    throw UsageError(flag + " must be " + allowed + ", got '" + text + "'");
  };
  return o;
}

// `option` with OptionSpec::inapplicable set to `why`.
inline OptionSpec onlyWhen(OptionSpec option, std::function<std::string(const RenderSettings&)> why) {
  option.inapplicable = std::move(why);
  return option;
}

}  // namespace erpt
