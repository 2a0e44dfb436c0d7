// Which integrators each render option means something for. An option given for an
// integrator that does not use it is refused with a one-line error naming both, rather than
// silently ignored; this table is the one place that says which option applies where.
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace erpt::cli {

// The long names ("--spp") of the options given on a parsed command (count > 0).
std::vector<std::string> givenOptions(const CLI::App& cmd);

// The integrators `option` applies to (empty: every integrator).
const std::vector<std::string>& integratorsUsing(const std::string& option);

// Throws UsageError for the first given option that none of `integrators` uses.
void checkOptionScope(const std::vector<std::string>& given, const std::vector<std::string>& integrators);

}  // namespace erpt::cli
