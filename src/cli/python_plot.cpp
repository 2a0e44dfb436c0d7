#include "python_plot.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace erpt::cli {

namespace {

// A shell word: single-quoted, with any single quote closed, escaped and reopened.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string interpreter() {
  if (const char* p = std::getenv("ERPT_PYTHON"); p && *p) return p;
  return std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

// build/python when this erpt runs from a build tree (the package sits beside the binary).
std::string packageDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const std::filesystem::path dir = exe.parent_path() / "python";
  return std::filesystem::exists(dir / "erpt" / "plot.py") ? dir.string() : std::string();
}

}  // namespace

std::string plotComparison(const std::string& report, const std::string& image) {
  const std::string python = interpreter(), dir = packageDir();
  const std::string pythonPath = dir.empty() ? std::string() : dir + (std::getenv("PYTHONPATH") ? ":" + std::string(std::getenv("PYTHONPATH")) : "");
  const std::string log = image + ".log";
  const std::string command = (pythonPath.empty() ? std::string() : "PYTHONPATH=" + quoted(pythonPath) + " ") + quoted(python) +
                              " -m erpt.plot " + quoted(report) + " -o " + quoted(image) + " >/dev/null 2>" + quoted(log);
  const int status = std::system(command.c_str());
  std::string why;
  if (status != 0) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty()) last = line;  // a Python traceback ends with the exception
    why = (last.empty() ? "python did not run" : last) +
          "; it needs Python 3 with matplotlib and the erpt package (scripts/setup.sh installs them, "
          "scripts/build.sh builds the package into build/python): " +
          (dir.empty() ? std::string() : "PYTHONPATH=" + dir + " ") + "python3 -m erpt.plot " + report + " -o " + image;
  }
  std::error_code ec;
  std::filesystem::remove(log, ec);
  return why;
}

}  // namespace erpt::cli
