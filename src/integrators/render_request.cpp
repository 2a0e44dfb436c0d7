// The front ends' request -> RenderSettings (erpt/render_request.h).
#include "erpt/render_request.h"

#include <algorithm>

#include "erpt/error.h"
#include "erpt/integrators.h"

namespace erpt {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

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

RenderSettings settingsFor(const Scene& scene, const RenderRequest& r, std::string* note) {
  if (r.maxDepth == 0) throw UsageError("--max-depth must be -1 (unbounded) or at least 1");
  if (!r.filter.empty() && r.filter != "box" && r.filter != "tent" && r.filter != "gaussian")
    throw UsageError("--filter must be box, tent or gaussian, got '" + r.filter + "'");
  RenderSettings s;
  const bool sceneIntegratorKnown = findIntegrator(scene.integrator.type) != nullptr;
  s.integrator = !r.integrator.empty() ? r.integrator : sceneIntegratorKnown ? scene.integrator.type : defaultIntegrator().name;
  const IntegratorModule& integrator = integratorNamed(s.integrator);
  s.width = r.width;
  s.height = r.height;
  s.spp = r.spp;
  s.maxDepth = r.maxDepth;
  s.seed = r.seed;
  s.threads = r.threads;
  s.timeBudget = r.time;
  const auto given = [&](const std::string& option) { return std::find(r.given.begin(), r.given.end(), option) != r.given.end(); };
  std::vector<std::pair<std::string, std::string>> options;
  for (const auto& [name, value] : r.options)
    if (findOption(integrator, name)) options.emplace_back(name, value);
  if (!integrator.sppOption.empty() && given("--spp")) {
    if (given("--" + integrator.sppOption))
      throw UsageError("for " + integrator.name + " --spp is the " + integrator.sppOption +
                       " (as Mitsuba's sample count): give --spp or --" + integrator.sppOption + ", not both");
    options.emplace_back(integrator.sppOption, std::to_string(r.spp));
    s.spp = 1;  // its render is one pass; time-budgeted passes scale the option by their spp
  }
  applyOptions(integrator, options, s);
  if (!r.filter.empty()) {
    s.filterSet = true;
    s.filter = r.filter == "box" ? FilterKind::Box : r.filter == "tent" ? FilterKind::Tent : FilterKind::Gaussian;
  }
  if (note && r.integrator.empty() && !sceneIntegratorKnown)
    *note = "note: the scene asks for integrator '" + scene.integrator.type + "'; rendering with '" + s.integrator + "'";
  return s;
}

}  // namespace erpt
