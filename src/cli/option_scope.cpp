#include "option_scope.h"

#include <algorithm>

#include <CLI/CLI.hpp>

#include "erpt/error.h"
#include "erpt/integrators.h"

namespace erpt::cli {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> givenOptions(const CLI::App& cmd) {
  std::vector<std::string> given;
  for (const CLI::Option* o : cmd.get_options())
    if (o->count() > 0 && !o->get_lnames().empty()) given.push_back("--" + o->get_lnames().front());
  return given;
}

std::vector<std::string> integratorsUsing(const std::string& option) {
  std::vector<std::string> users;
  const bool samplePassOption =
      std::find(kSamplePassOptions.begin(), kSamplePassOptions.end(), option) != kSamplePassOptions.end();
  for (const IntegratorModule& m : integratorModules())
    if (samplePassOption ? m.samplePasses : option.rfind("--", 0) == 0 && findOption(m, option.substr(2)))
      users.push_back(m.name);
  return users;
}

void checkOptionScope(const std::vector<std::string>& given, const std::vector<std::string>& integrators) {
  for (const std::string& option : given) {
    const std::vector<std::string> users = integratorsUsing(option);
    if (users.empty()) continue;
    const bool used = std::any_of(integrators.begin(), integrators.end(), [&](const std::string& i) {
      return std::find(users.begin(), users.end(), i) != users.end();
    });
    if (!used)
      throw UsageError(option + " does not apply to " + (integrators.size() == 1 ? "--integrator " : "--integrators ") +
                       joined(integrators) + " (it is an option of " + joined(users) + ")");
  }
}

}  // namespace erpt::cli
