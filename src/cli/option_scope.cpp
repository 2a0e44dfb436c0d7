#include "option_scope.h"

#include <algorithm>
#include <map>

#include <CLI/CLI.hpp>

#include "erpt/error.h"

namespace erpt::cli {

namespace {

// Options not listed here mean something for every integrator (size, threads, seed, depth,
// filter, defines, spheres, time, output, quiet). `--spp` is listed for every integrator too:
// for mlt it is the mutations per pixel, Mitsuba's convention for its sampler's sample count.
const std::map<std::string, std::vector<std::string>>& scopes() {
  static const std::map<std::string, std::vector<std::string>> table = {
      // Only the path tracer splats samples over the filter; the others use filter importance sampling.
      {"--film", {"path"}},
      // Long renders: checkpoints and partial images need sample passes, which mlt does not have.
      {"--checkpoint", {"path", "direct", "erpt", "pmc-er"}},
      {"--checkpoint-every", {"path", "direct", "erpt", "pmc-er"}},
      {"--write-partial", {"path", "direct", "erpt", "pmc-er"}},
      {"--display", {"path", "direct", "erpt", "pmc-er"}},
      // The chain engine's options, where each integrator lets the user set them (PMC-ER's
      // mixture fixes the mutation kinds, shapes and sizes; MLT fixes its chains' length and
      // deposits expected values; neither needs ERPT's pilot pass).
      {"--mutations-per-pixel", {"erpt", "mlt"}},
      {"--chain-length", {"erpt"}},
      {"--lens-radius", {"erpt", "mlt"}},
      {"--mutation-strategy", {"erpt", "mlt"}},
      {"--lens-shape", {"erpt", "mlt"}},
      {"--caustic-angle", {"erpt", "mlt"}},
      {"--pilot-spp", {"erpt"}},  // PMC-ER's energies come from its pool, MLT's from its bootstrap
      {"--deposit", {"erpt", "pmc-er"}},
      {"--flow", {"erpt"}},
      {"--pm-filter", {"erpt", "pmc-er"}},
      {"--pm-filter-radius", {"erpt", "pmc-er"}},
      {"--max-consecutive", {"erpt", "pmc-er"}},
      {"--max-chains-per-seed", {"erpt"}},
      {"--direct-samples", {"erpt", "pmc-er", "mlt"}},
      {"--pmc-flow", {"pmc-er"}},
      {"--population", {"pmc-er"}},
      {"--mutations-per-member", {"pmc-er"}},
      {"--radii", {"pmc-er"}},
      {"--pmc-adapt", {"pmc-er"}},
      {"--resample-rate", {"pmc-er"}},
      {"--alpha-floor", {"pmc-er"}},
      {"--caustic-prob", {"pmc-er"}},
      {"--pmc-region", {"pmc-er"}},
      {"--pmc-train-iterations", {"pmc-er"}},
      {"--large-step-prob", {"mlt"}},
      {"--bootstrap", {"mlt"}},
      {"--chains", {"mlt"}},
  };
  return table;
}

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

const std::vector<std::string>& integratorsUsing(const std::string& option) {
  static const std::vector<std::string> all;
  const auto it = scopes().find(option);
  return it == scopes().end() ? all : it->second;
}

void checkOptionScope(const std::vector<std::string>& given, const std::vector<std::string>& integrators) {
  for (const std::string& option : given) {
    const std::vector<std::string>& users = integratorsUsing(option);
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
