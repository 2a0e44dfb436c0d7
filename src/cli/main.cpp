// The `erpt` command line: `erpt render`, `erpt info`, `erpt diff` and `erpt compare`.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "erpt/error.h"
#include "erpt/image_io.h"

namespace {
// An interrupted run must not leave a half-written image.
void onSignal(int sig) {
  erpt::removePendingImageFiles();
  _exit(128 + sig);
}
}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  CLI::App app{"erpt: Energy Redistribution Path Tracing renderer for Mitsuba scenes"};
  app.require_subcommand(1);
  erpt::cli::RenderArgs renderArgs;
  erpt::cli::addRenderCommand(app, renderArgs);
  erpt::cli::InfoArgs infoArgs;
  erpt::cli::addInfoCommand(app, infoArgs);
  erpt::cli::DiffArgs diffArgs;
  erpt::cli::addDiffCommand(app, diffArgs);
  erpt::cli::CompareArgs compareArgs;
  erpt::cli::addCompareCommand(app, compareArgs);
  compareArgs.commandLine = "erpt";
  for (int i = 1; i < argc; ++i) {
    // Quoted where a shell would split or expand it, so the report's command can be pasted.
    const std::string arg = argv[i];
    const bool plain = arg.find_first_of(" []*?'\"$;&|<>(){}") == std::string::npos && !arg.empty();
    compareArgs.commandLine += " " + (plain ? arg : "'" + arg + "'");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("render")) return erpt::cli::runRender(renderArgs);
    if (app.got_subcommand("diff")) return erpt::cli::runDiff(diffArgs);
    if (app.got_subcommand("compare")) return erpt::cli::runCompare(compareArgs);
    return erpt::cli::runInfo(infoArgs);
  } catch (const erpt::InputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const erpt::UsageError& e) {
    std::cerr << "erpt: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "erpt: error: " << e.what() << "\n";
    return 1;
  }
}
