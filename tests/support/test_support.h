// Helpers shared by tests: temporary directories, writing scene files, running the CLI.
#pragma once

#include <filesystem>
#include <string>

namespace erpt::test {

// A fresh directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& contents) const;

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exitCode;
  std::string output;  // stdout and stderr together
};
// Runs the built `erpt` binary with the given arguments (a shell fragment).
CommandResult runCli(const std::string& args);
// The same with environment assignments before the command (e.g. "LD_DEBUG=files").
CommandResult runCliWithEnvironment(const std::string& environment, const std::string& args);

std::string sharedScenesDir();  // ../shared/scenes beside the project
std::string sourceDir();

}  // namespace erpt::test
