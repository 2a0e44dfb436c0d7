#pragma once

#include <map>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace erpt::cli {

struct RenderArgs {
  std::string scene, output, integrator, filter;
  int spp = 0, width = 0, height = 0, threads = 0, maxDepth = -2;
  unsigned long long seed = 0;
  std::vector<std::string> defines;
  bool quiet = false;
};

struct InfoArgs {
  std::string scene;
  std::vector<std::string> defines;
};

void addRenderCommand(CLI::App& app, RenderArgs& args);
void addInfoCommand(CLI::App& app, InfoArgs& args);
int runRender(const RenderArgs& args);
int runInfo(const InfoArgs& args);

// "-D name=value" strings to a map; throws UsageError on a malformed one.
std::map<std::string, std::string> parseDefines(const std::vector<std::string>& defines);

}  // namespace erpt::cli
