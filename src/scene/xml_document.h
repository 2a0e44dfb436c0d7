// Internal to the scene loader: an XML file kept in memory with its line table, so that any
// node can be reported as file:line; plus strict parsing of attribute values.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "erpt/error.h"
#include "erpt/math.h"

namespace erpt::xml {

class Document {
 public:
  // Throws InputError for a missing file or malformed XML (with the parser's line).
  explicit Document(const std::string& path);
  const pugi::xml_node root() const { return doc_.document_element(); }
  const std::string& path() const { return path_; }
  SourceLocation where(const pugi::xml_node& node) const;

 private:
  int lineOf(ptrdiff_t offset) const;
  std::string path_;
  std::string text_;
  std::vector<size_t> lineStarts_;
  pugi::xml_document doc_;
};

// Values of <default> elements and -D overrides, and `$name` substitution.
class Defines {
 public:
  explicit Defines(std::map<std::string, std::string> overrides) : values_(std::move(overrides)) {
    for (const auto& [name, value] : values_) overrides_.insert(name);
  }
  void addDefault(const std::string& name, const std::string& value) {
    values_.emplace(name, value);
    declared_.insert(name);
  }
  std::string substitute(const std::string& text, const SourceLocation& where) const;
  // An override (-D) the scene neither declares with <default> nor uses as $name: a typo the
  // render would otherwise ignore. "" if there is none.
  std::string unusedOverride() const {
    for (const std::string& name : overrides_)
      if (!declared_.count(name) && !used_.count(name)) return name;
    return "";
  }

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> overrides_, declared_;
  mutable std::set<std::string> used_;
};

// Strict conversions: the whole string must be a finite number, else InputError.
double parseNumber(const std::string& text, const SourceLocation& where, const std::string& what);
int parseInteger(const std::string& text, const SourceLocation& where, const std::string& what);
bool parseBoolean(const std::string& text, const SourceLocation& where, const std::string& what);
// Comma- and/or space-separated list of numbers.
std::vector<double> parseNumberList(const std::string& text, const SourceLocation& where, const std::string& what);
Vec3 parseVector(const std::string& text, const SourceLocation& where, const std::string& what);

// "toWorld" -> "to_world", "intIOR" -> "int_ior": both dialects map to one set of names.
std::string normalizeName(const std::string& name);

}  // namespace erpt::xml
