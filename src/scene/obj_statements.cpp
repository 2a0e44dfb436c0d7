#include "obj_statements.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <vector>

namespace erpt::obj {

namespace {

// The file's lines as tinyobjloader counts them: ended by "\n", "\r\n" or a lone "\r".
std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> lines;
  std::string line;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c != '\n' && c != '\r') {
      line += c;
      continue;
    }
    if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    lines.push_back(std::move(line));
    line.clear();
  }
  if (!line.empty()) lines.push_back(std::move(line));
  return lines;
}

// A statement's keyword ("v", "vn", "f"...) and the text after it.
struct Statement {
  std::string keyword;
  std::string rest;
};

Statement parseStatement(const std::string& line) {
  Statement s;
  const size_t start = line.find_first_not_of(" \t");
  const size_t end = start == std::string::npos ? start : line.find_first_of(" \t", start);
  // tinyobjloader takes a keyword only when a space or tab follows it: a lone "v" is no vertex.
  if (end == std::string::npos) return s;
  s.keyword = line.substr(start, end - start);
  s.rest = line.substr(end + 1);
  return s;
}

// One corner of a face ("7", "7/2", "7//3", "7/2/3"): its position, uv and normal indices as
// tinyobjloader reads them (atoi; absent ones 0), and the text they were read from.
struct Triple {
  int position = 0, uv = 0, normal = 0;
  bool hasUv = false, hasNormal = false;
  std::string text;
};

// The corners of an 'f' (or 'l', 'p') statement, walked as tinyobjloader's parseTriple walks
// them, quirks included: atoi skips blanks, so "3/ 4" reads uv 4.
std::vector<Triple> parseTriples(const std::string& rest) {
  std::vector<Triple> triples;
  const char* token = rest.c_str();
  auto number = [&token] {
    const int value = std::atoi(token);
    token += std::strcspn(token, "/ \t\r");
    return value;
  };
  token += std::strspn(token, " \t");
  while (*token != '\0' && *token != '\r' && *token != '\n') {
    const char* begin = token;
    Triple t;
    t.position = number();
    if (*token == '/') {
      ++token;
      if (*token == '/') {  // "7//3"
        ++token;
        t.hasNormal = true;
        t.normal = number();
      } else {
        t.hasUv = true;
        t.uv = number();
        if (*token == '/') {
          ++token;
          t.hasNormal = true;
          t.normal = number();
        }
      }
    }
    t.text.assign(begin, token);
    triples.push_back(std::move(t));
    token += std::strspn(token, " \t\r");
  }
  return triples;
}

struct Counts {
  int positions = 0, normals = 0, uvs = 0;
  void count(const std::string& keyword) {
    positions += keyword == "v";
    normals += keyword == "vn";
    uvs += keyword == "vt";
  }
};

// Why `index` (as written, on a line after `before` definitions, of `total` in the file) does
// not resolve; empty when it does (or is absent: 0).
std::string unresolved(int index, int before, int total, const std::string& what, const std::string& plural) {
  auto count = [&](int n) { return std::to_string(n) + " " + (n == 1 ? what : plural); };
  if (index > total)
    return "face refers to " + what + " " + std::to_string(index) + ", but the file has " + count(total);
  if (index < 0 && before + index < 0)
    return "face refers to " + what + " " + std::to_string(index) + ", counting back, but only " + count(before) +
           (before == 1 ? " comes" : " come") + " before it";
  return "";
}

}  // namespace

int lineOfVertex(const std::string& path, size_t index) {
  const std::vector<std::string> lines = readLines(path);
  size_t seen = 0;
  for (size_t n = 0; n < lines.size(); ++n)
    if (parseStatement(lines[n]).keyword == "v" && seen++ == index) return int(n + 1);
  return 0;
}

std::optional<InputError> badFaceReference(const std::string& path) {
  const std::vector<std::string> lines = readLines(path);
  Counts total;
  for (const std::string& line : lines) total.count(parseStatement(line).keyword);
  Counts before;
  for (size_t n = 0; n < lines.size(); ++n) {
    const Statement s = parseStatement(lines[n]);
    before.count(s.keyword);
    if (s.keyword != "f") continue;
    for (const Triple& t : parseTriples(s.rest)) {
      for (const std::string& cause :
           {unresolved(t.position, before.positions, total.positions, "vertex", "vertices"),
            unresolved(t.normal, before.normals, total.normals, "normal", "normals"),
            unresolved(t.uv, before.uvs, total.uvs, "texture coordinate", "texture coordinates")})
        if (!cause.empty()) return InputError({path, int(n + 1)}, cause);
    }
  }
  return std::nullopt;
}

InputError parseFailure(const std::string& path, const std::string& tinyobjError) {
  std::smatch found;
  if (!std::regex_search(tinyobjError, found, std::regex("`(\\w+)' line.*line ([0-9]+)")))
    return InputError({path, 0}, "malformed OBJ file: " + tinyobjError.substr(0, tinyobjError.find('\n')));
  const std::string keyword = found[1];
  const int line = std::atoi(found[2].str().c_str());
  if (keyword == "vw") return InputError({path, line}, "negative joint id in a 'vw' statement");
  // tinyobjloader gives up on an index that reads as 0 (zero, or not a number at all).
  std::string bad;
  const std::vector<std::string> lines = readLines(path);
  if (line >= 1 && size_t(line) <= lines.size())
    for (const Triple& t : parseTriples(parseStatement(lines[size_t(line) - 1]).rest))
      if (t.position == 0 || (t.hasUv && t.uv == 0) || (t.hasNormal && t.normal == 0)) {
        bad = t.text;
        break;
      }
  return InputError({path, line}, "bad index" + (bad.empty() ? "" : " '" + bad + "'") + " in an '" + keyword +
                                      "' statement (OBJ indices are whole numbers other than 0)");
}

}  // namespace erpt::obj
