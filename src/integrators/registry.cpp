// The only place that maps an integrator's name to its module (include/erpt/integrators.h).
#include "erpt/integrators.h"

#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/direct/direct_integrator.h"
#include "erpt/error.h"
#include "integrators/erpt/erpt_integrator.h"
#include "integrators/mlt/mlt_integrator.h"
#include "integrators/path/path_integrator.h"
#include "integrators/pmc_er/pmc_er_integrator.h"
#include "integrators/mmlt/mmlt_integrator.h"
#include "integrators/pssmlt/pssmlt_integrator.h"

namespace erpt {

const std::vector<IntegratorModule>& integratorModules() {
  static const std::vector<IntegratorModule> modules = {pathModule(), directModule(), erptModule(), pmcErModule(),
                                                        mltModule(), pssmltModule(), mmltModule(),
                                                        bdptModule()};
  return modules;
}

const IntegratorModule* findIntegrator(const std::string& name) {
  for (const IntegratorModule& m : integratorModules())
    if (m.name == name) return &m;
  return nullptr;
}

std::string integratorNames() {
  std::string names;
  for (const IntegratorModule& m : integratorModules()) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

const IntegratorModule& defaultIntegrator() { return integratorModules().front(); }

const OptionSpec* findOption(const IntegratorModule& integrator, const std::string& name) {
  for (const OptionSpec& o : integrator.options)
    if (o.name == name) return &o;
  return nullptr;
}

const IntegratorModule& integratorNamed(const std::string& name) {
  const IntegratorModule* m = findIntegrator(name);
  if (!m) throw UsageError("unknown integrator '" + name + "' (available: " + integratorNames() + ")");
  return *m;
}

}  // namespace erpt
