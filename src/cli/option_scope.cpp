#include "option_scope.h"

#include <CLI/CLI.hpp>

namespace erpt::cli {

std::vector<std::string> givenOptions(const CLI::App& cmd) {
  std::vector<std::string> given;
  for (const CLI::Option* o : cmd.get_options())
    if (o->count() > 0 && !o->get_lnames().empty()) given.push_back("--" + o->get_lnames().front());
  return given;
}

}  // namespace erpt::cli
