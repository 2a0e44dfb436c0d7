// Which integrators each render option means something for, from the options each integrator
// declares (include/erpt/integrators.h). An option given to an integrator that does not use it
// is refused with a one-line error naming both, rather than silently ignored.
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace erpt::cli {

// The long names ("--spp") of the options given on a parsed command (count > 0).
std::vector<std::string> givenOptions(const CLI::App& cmd);

// The integrators that declare `option` (empty: none does, so every integrator takes it).
std::vector<std::string> integratorsUsing(const std::string& option);

// Throws UsageError for the first given option that none of `integrators` uses.
void checkOptionScope(const std::vector<std::string>& given, const std::vector<std::string>& integrators);

}  // namespace erpt::cli
