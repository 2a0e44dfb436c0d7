#include "erpt/options.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "erpt/integrators.h"

namespace erpt {

std::string formatOptionNumber(double value) {
  char text[32];
  if (value == std::trunc(value) && std::fabs(value) < 1e15) std::snprintf(text, sizeof text, "%.0f", value);
  else std::snprintf(text, sizeof text, "%g", value);  // float settings: 6 digits show them as written
  return text;
}

std::string OptionSpec::allowed() const {
  if (kind == OptionKind::Choice) {
    std::string words;
    for (const std::string& c : choices) words += (words.empty() ? "" : ", ") + c;
    return "one of " + words;
  }
  return (minOpen ? "(" : "[") + formatOptionNumber(min) + ", " + formatOptionNumber(max) + "]";
}

namespace {
[[noreturn]] void refuse(const OptionSpec& o, const std::string& what, const std::string& text) {
  throw UsageError(o.flag() + " must be " + what + " in " + o.allowed() + ", got '" + text + "'");
}

bool inRange(const OptionSpec& o, double v) { return (o.minOpen ? v > o.min : v >= o.min) && v <= o.max; }
}  // namespace

long long parseOptionInteger(const OptionSpec& o, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno == ERANGE || !inRange(o, double(v))) refuse(o, "an integer", text);
  return v;
}

double parseOptionReal(const OptionSpec& o, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || !inRange(o, v)) refuse(o, "a number", text);
  return v;
}

void checkOptionRange(const OptionSpec& o, const RenderSettings& s) {
  if (!o.number) return;
  const double v = o.number(s);
  if (!(std::isfinite(v) && inRange(o, v))) throw UsageError(o.flag() + " must be in " + o.allowed() + ", got " + formatOptionNumber(v));
}

void applyOptions(const IntegratorModule& integrator, const std::vector<std::pair<std::string, std::string>>& given,
                  RenderSettings& settings) {
  const auto valueOf = [&](const std::string& name) -> const std::string* {
    for (const auto& [n, value] : given)
      if (n == name) return &value;
    return nullptr;
  };
  for (const OptionSpec& o : integrator.options)
    if (const std::string* value = valueOf(o.name)) o.set(settings, *value);
  for (const OptionSpec& o : integrator.options) {
    if (!o.inapplicable || !valueOf(o.name)) continue;
    const std::string why = o.inapplicable(settings);
    if (!why.empty()) throw UsageError(o.flag() + " " + why);
  }
}

}  // namespace erpt
