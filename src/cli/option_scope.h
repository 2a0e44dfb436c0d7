// The options given on a parsed command line, for the scope check of erpt/render_request.h
// (an option given to an integrator that does not use it is refused with a one-line error
// naming both, rather than silently ignored).
#pragma once

#include <string>
#include <vector>

#include "erpt/render_request.h"

namespace CLI {
class App;
}

namespace erpt::cli {

// The long names ("--spp") of the options given on a parsed command (count > 0).
std::vector<std::string> givenOptions(const CLI::App& cmd);


}  // namespace erpt::cli
