// The `erpt` command line: `erpt render`, `erpt resume`, `erpt info`, `erpt diff` and `erpt compare`.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "option_scope.h"
#include "erpt/error.h"
#include "erpt/image_io.h"
#include "process_group.h"
#include "stop_signals.h"

int main(int argc, char** argv) {
  erpt::cli::installSignalHandlers();  // an interrupted run never leaves a half-written image
  const erpt::cli::ProcessGroup group(argc, argv);  // one process, or a rank of an MPI job

  CLI::App app{"erpt: Energy Redistribution Path Tracing renderer for Mitsuba scenes"};
  app.require_subcommand(1);
  erpt::cli::RenderArgs renderArgs;
  erpt::cli::addRenderCommand(app, renderArgs);
  erpt::cli::InfoArgs infoArgs;
  erpt::cli::addInfoCommand(app, infoArgs);
  erpt::cli::DiffArgs diffArgs;
  erpt::cli::addDiffCommand(app, diffArgs);
  erpt::cli::ResumeArgs resumeArgs;
  erpt::cli::addResumeCommand(app, resumeArgs);
  erpt::cli::CompareArgs compareArgs;
  erpt::cli::addCompareCommand(app, compareArgs);
  compareArgs.commandLine = "erpt";
  for (int i = 1; i < argc; ++i) {
    // Quoted where a shell would split or expand it, so the report's command can be pasted.
    const std::string arg = argv[i];
    const bool plain = arg.find_first_of(" []*?'\"$;&|<>(){}") == std::string::npos && !arg.empty();
    compareArgs.commandLine += " " + (plain ? arg : "'" + arg + "'");
  }
  for (int i = 1; i < argc; ++i)  // what a checkpoint keeps: the render command's own arguments
    if (std::string(argv[i]) == "render") {
      renderArgs.commandArgs.assign(argv + i + 1, argv + argc);
      break;
    }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  renderArgs.given = erpt::cli::givenOptions(*app.get_subcommand("render"));
  compareArgs.render.given = erpt::cli::givenOptions(*app.get_subcommand("compare"));
  // In an MPI job a rank that fails ends the job: the others would wait for it.
  auto fail = [&](int status) { return group.size() > 1 ? group.abortAll(status), status : status; };
  try {
    if (app.got_subcommand("render")) return erpt::cli::runRender(renderArgs);
    if (app.got_subcommand("resume")) return erpt::cli::runResume(resumeArgs);
    if (app.got_subcommand("diff")) return erpt::cli::runDiff(diffArgs);
    if (app.got_subcommand("compare")) return erpt::cli::runCompare(compareArgs);
    return erpt::cli::runInfo(infoArgs);
  } catch (const erpt::InputError& e) {
    std::cerr << e.what() << "\n";
    return fail(1);
  } catch (const erpt::UsageError& e) {
    std::cerr << "erpt: error: " << e.what() << "\n";
    return fail(2);
  } catch (const std::exception& e) {
    std::cerr << "erpt: error: " << e.what() << "\n";
    return fail(1);
  }
}
