// Errors and warnings about user input. Every message names where the problem is
// ("file:line") and what it is, on one line, so a user can jump straight to it.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace erpt {

// Control characters as escapes ("\\n", "\\x01"): a value or file name quoted in a message
// may hold a newline (an XML character reference, a binary file's bytes), and a message
// must stay one line.
inline std::string oneLine(const std::string& text) {
  std::string out;
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (u < 0x20 && c != '\t') out += "\\x" + std::string(1, "0123456789abcdef"[u >> 4]) + "0123456789abcdef"[u & 15];
    else out += c;
  }
  return out;
}

struct SourceLocation {
  std::string file;
  // 0 = the file as a whole, where no line exists: a scene file or checkpoint that cannot be
  // read, and inside the mesh and image readers (binary data), whose line-less errors the
  // scene loader reports at the XML line that names the file (src/scene/referenced_file.h).
  int line = 0;
  std::string str() const { return line > 0 ? oneLine(file) + ":" + std::to_string(line) : oneLine(file); }
};

// Bad input: a malformed or missing file, an unknown value, a non-finite number...
class InputError : public std::runtime_error {
 public:
  InputError(const SourceLocation& where, const std::string& cause)
      : std::runtime_error(where.str() + ": error: " + oneLine(cause)), where_(where), cause_(oneLine(cause)) {}
  const SourceLocation& where() const { return where_; }
  const std::string& cause() const { return cause_; }  // the message after "error: "

 private:
  SourceLocation where_;
  std::string cause_;
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
    std::string message = where.str() + ": warning: " + oneLine(what);
    if (std::find(messages.begin(), messages.end(), message) == messages.end()) messages.push_back(std::move(message));
  }
};

}  // namespace erpt
