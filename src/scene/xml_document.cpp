#include "xml_document.h"

#include "io/file_util.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace erpt::xml {

Document::Document(const std::string& path) : path_(path) {
  text_ = readWholeFile(path, "scene file");
  lineStarts_.push_back(0);
  for (size_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') lineStarts_.push_back(i + 1);
  pugi::xml_parse_result result = doc_.load_buffer(text_.data(), text_.size(), pugi::parse_default);
  if (!result) throw InputError({path, lineOf(result.offset)}, std::string("malformed XML: ") + result.description());
  if (!doc_.document_element()) throw InputError({path, 1}, "malformed XML: no root element");
}

int Document::lineOf(ptrdiff_t offset) const {
  auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), size_t(std::max<ptrdiff_t>(0, offset)));
  return int(it - lineStarts_.begin());
}

SourceLocation Document::where(const pugi::xml_node& node) const { return {path_, lineOf(node.offset_debug())}; }

std::string Defines::substitute(const std::string& text, const SourceLocation& where) const {
  if (text.find('$') == std::string::npos) return text;
  std::string out;
  for (size_t i = 0; i < text.size();) {
    if (text[i] != '$') {
      out += text[i++];
      continue;
    }
    size_t j = i + 1;
    while (j < text.size() && (std::isalnum((unsigned char)text[j]) || text[j] == '_')) ++j;
    std::string name = text.substr(i + 1, j - i - 1);
    auto found = values_.find(name);
    used_.insert(name);
    if (name.empty() || found == values_.end())
      throw InputError(where, "undefined parameter '$" + name + "' (add <default name=\"" + name +
                                  "\" .../> or pass -D " + name + "=VALUE)");
    out += found->second;
    i = j;
  }
  return out;
}

double parseNumber(const std::string& text, const SourceLocation& where, const std::string& what) {
  const char* begin = text.c_str();
  while (std::isspace((unsigned char)*begin)) ++begin;
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(begin, &end);
  while (end && std::isspace((unsigned char)*end)) ++end;
  if (end == begin || *end != '\0') throw InputError(where, "bad number '" + text + "' for " + what);
  if (!std::isfinite(v) || errno == ERANGE) throw InputError(where, "non-finite value '" + text + "' for " + what);
  return v;
}

int parseInteger(const std::string& text, const SourceLocation& where, const std::string& what) {
  double v = parseNumber(text, where, what);
  if (v != std::floor(v) || std::abs(v) > 2147483647.0)
    throw InputError(where, "bad integer '" + text + "' for " + what);
  return int(v);
}

bool parseBoolean(const std::string& text, const SourceLocation& where, const std::string& what) {
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (t == "true" || t == "1") return true;
  if (t == "false" || t == "0") return false;
  throw InputError(where, "bad boolean '" + text + "' for " + what + " (expected true or false)");
}

std::vector<double> parseNumberList(const std::string& text, const SourceLocation& where, const std::string& what) {
  std::vector<double> values;
  std::string token;
  auto flush = [&] {
    if (!token.empty()) values.push_back(parseNumber(token, where, what));
    token.clear();
  };
  for (char c : text) {
    if (c == ',' || std::isspace((unsigned char)c))
      flush();
    else
      token += c;
  }
  flush();
  return values;
}

Vec3 parseVector(const std::string& text, const SourceLocation& where, const std::string& what) {
  std::vector<double> v = parseNumberList(text, where, what);
  if (v.size() == 1) return Vec3(float(v[0]));
  if (v.size() != 3) throw InputError(where, "expected 3 numbers for " + what + ", got '" + text + "'");
  return {float(v[0]), float(v[1]), float(v[2])};
}

std::string normalizeName(const std::string& name) {
  std::string out;
  for (size_t i = 0; i < name.size(); ++i) {
    char c = name[i];
    bool upper = std::isupper((unsigned char)c);
    if (upper && i > 0 && std::islower((unsigned char)name[i - 1])) out += '_';
    out += char(std::tolower((unsigned char)c));
  }
  return out;
}

}  // namespace erpt::xml
