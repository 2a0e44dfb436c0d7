#include "support/test_support.h"

#include <sys/wait.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <random>

namespace erpt::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() /
          ("erpt-test-" + std::to_string(rd()) + "-" + std::to_string(counter++));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::string TempDir::write(const std::string& name, const std::string& contents) const {
  std::string p = file(name);
  std::filesystem::create_directories(std::filesystem::path(p).parent_path());
  std::ofstream(p, std::ios::binary) << contents;
  return p;
}

CommandResult runCli(const std::string& args) { return runCliWithEnvironment("", args); }

CommandResult runCliWithEnvironment(const std::string& environment, const std::string& args) {
  std::string cmd = environment + " " + std::string(ERPT_CLI_PATH) + " " + args + " 2>&1";
  CommandResult r{0, ""};
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string sourceDir() { return ERPT_SOURCE_DIR; }
std::string sharedScenesDir() { return std::string(ERPT_SOURCE_DIR) + "/../shared/scenes"; }

}  // namespace erpt::test
