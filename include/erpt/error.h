// Errors and warnings about user input. Every message names where the problem is
// ("file:line") and what it is, on one line, so a user can jump straight to it.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace erpt {

struct SourceLocation {
  std::string file;
  int line = 0;  // 0 = the file as a whole
  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

// Bad input: a malformed or missing file, an unknown value, a non-finite number...
class InputError : public std::runtime_error {
 public:
  InputError(const SourceLocation& where, const std::string& cause)
      : std::runtime_error(where.str() + ": error: " + cause), where_(where) {}
  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

// Bad options on the command line (no file to point at).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Non-fatal problems found while loading; printed by the CLI and by `erpt info`.
struct Warnings {
  std::vector<std::string> messages;
  // Each message once: a shapegroup member is read again for every instance that copies it.
  void add(const SourceLocation& where, const std::string& what) {
    std::string message = where.str() + ": warning: " + what;
    if (std::find(messages.begin(), messages.end(), message) == messages.end()) messages.push_back(std::move(message));
  }
};

}  // namespace erpt
