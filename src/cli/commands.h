#pragma once

#include <map>
#include <string>

#include "io/checkpoint.h"
#include "erpt/render.h"
#include "erpt/scene.h"
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
  bool quiet = false, tessellateSpheres = false;
  // The integrators' own options (options.h), by long name without dashes, as given.
  std::map<std::string, std::string> integratorOptions;
  double time = 0;
  // Long renders (docs/long-renders.md).
  std::string checkpoint;        // --checkpoint FILE
  double checkpointEvery = 300;  // --checkpoint-every SECONDS
  double writePartial = 0;       // --write-partial SECONDS (0: off)
  std::string display;           // --display HOST:PORT (the tev viewer)
  std::vector<std::string> commandArgs;  // the render command's own arguments (kept in checkpoints)
  std::vector<std::string> given;        // long names of the options given (option_scope.h)
  const Checkpoint* resumeFrom = nullptr;  // `erpt resume`
};

struct ResumeArgs {
  std::string checkpoint;
  int threads = -1;  // -1: as the checkpointed render
  bool quiet = false;
};

struct InfoArgs {
  std::string scene;
  std::vector<std::string> defines;
  bool tessellateSpheres = false;
};

struct DiffArgs {
  std::string image, reference, heatmap;
};

struct CompareArgs {
  RenderArgs render;  // scene, render and ERPT options (not --integrator, -o or --time)
  std::string reference, outDir = "compare-out", integrators = "path,erpt";
  double time = 0;
  bool json = false;        // print the JSON report instead of the Markdown table
  std::string commandLine;  // recorded in the report
};

void addDiffCommand(CLI::App& app, DiffArgs& args);
int runDiff(const DiffArgs& args);
void addRenderCommand(CLI::App& app, RenderArgs& args);
// The render options shared by `render` and `compare`: those every integrator takes, then each
// integrator's declared options (once each, with the integrators that take them in the help).
void addRenderOptions(CLI::App* cmd, RenderArgs& args);
Scene loadSceneFor(const RenderArgs& args);
RenderSettings settingsFromArgs(const RenderArgs& args, const Scene& scene);
void addCompareCommand(CLI::App& app, CompareArgs& args);
int runCompare(const CompareArgs& args);
void addInfoCommand(CLI::App& app, InfoArgs& args);
int runRender(const RenderArgs& args);
void addResumeCommand(CLI::App& app, ResumeArgs& args);
int runResume(const ResumeArgs& args);
int runInfo(const InfoArgs& args);

// "-D name=value" strings to a map; throws UsageError on a malformed one.
std::map<std::string, std::string> parseDefines(const std::vector<std::string>& defines);

}  // namespace erpt::cli
