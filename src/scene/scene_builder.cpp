#include "scene_builder.h"

#include "referenced_file.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "models/blackbody.h"

namespace erpt::xml {

namespace fs = std::filesystem;

namespace {
constexpr int kMaxIncludeDepth = 16;  // deeper nesting is almost surely an include cycle

bool isValueTag(const std::string& tag) {
  return tag == "float" || tag == "integer" || tag == "boolean" || tag == "string" || tag == "rgb" ||
         tag == "srgb" || tag == "spectrum" || tag == "point" || tag == "vector";
}
}  // namespace

SceneBuilder::SceneBuilder(Scene& scene, const LoadOptions& options)
    : scene_(scene), defines_(options.defines), tessellateSpheres_(options.tessellateSpheres) {}

std::string SceneBuilder::attribute(const Document& doc, const pugi::xml_node& node, const char* name, bool required) {
  pugi::xml_attribute a = node.attribute(name);
  if (!a) {
    if (required)
      throw InputError(doc.where(node), std::string("<") + node.name() + "> needs the attribute '" + name + "'");
    return {};
  }
  return defines_.substitute(a.value(), doc.where(node));
}

namespace {

std::string lowerCase(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The existing path that equals `p` up to letter case, one component at a time (the first
// match in directory order when several differ only in case); empty if there is none.
fs::path findIgnoringCase(const fs::path& p) {
  fs::path found = p.root_path();
  for (const fs::path& part : p.relative_path()) {
    const fs::path exact = found / part;
    std::error_code ec;
    if (fs::exists(exact, ec)) {
      found = exact;
      continue;
    }
    const std::string want = lowerCase(part.string());
    fs::path match;
    for (fs::directory_iterator it(found.empty() ? fs::path(".") : found, ec), end; !ec && it != end; it.increment(ec))
      if (lowerCase(it->path().filename().string()) == want) {
        match = it->path();
        break;
      }
    if (match.empty()) return {};
    found = found.empty() ? match.filename() : found / match.filename();
  }
  return found;
}

}  // namespace

std::string SceneBuilder::resolvePath(const Document& doc, const std::string& relative,
                                      const SourceLocation& where) const {
  fs::path p(relative);
  if (!p.is_absolute()) p = (fs::path(doc.path()).parent_path() / p).lexically_normal();
  std::error_code ec;
  if (fs::exists(p, ec)) return p.string();
  const fs::path other = findIgnoringCase(p);
  if (other.empty()) return p.string();  // the caller reports it missing
  scene_.warnings.add(where, "file '" + p.string() + "' not found; using '" + other.string() +
                                 "' (the same name in other letter case)");
  return other.string();
}

void SceneBuilder::requireFile(const std::string& path, const SourceLocation& where, const std::string& what) const {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(where, what + " '" + path + "' not found");
  if (fs::is_directory(status)) throw InputError(where, what + " '" + path + "' is a directory");
}

void SceneBuilder::loadFile(const std::string& path, int includeDepth) {
  const Document& doc = documents_.emplace_back(path);
  pugi::xml_node root = doc.root();
  if (std::string(root.name()) != "scene")
    throw InputError(doc.where(root), std::string("expected <scene> as the root element, found <") + root.name() + ">");
  if (includeDepth == 0) {
    sceneElement_ = doc.where(root);
    std::string version = root.attribute("version").value();
    if (version.empty()) {
      scene_.warnings.add(doc.where(root), "<scene> has no version attribute; assuming Mitsuba 3 (3.0.0)");
      majorVersion_ = 3;
    } else {
      majorVersion_ = parseInteger(version.substr(0, version.find('.')), doc.where(root), "the scene version");
    }
  }
  for (pugi::xml_node child : root.children())
    if (child.type() == pugi::node_element) sceneChild(doc, child, includeDepth);
}

void SceneBuilder::sceneChild(const Document& doc, const pugi::xml_node& node, int includeDepth) {
  std::string tag = node.name();
  if (tag == "default") {
    defines_.addDefault(attribute(doc, node, "name"), attribute(doc, node, "value"));
  } else if (tag == "include") {
    include(doc, node, includeDepth);
  } else if (tag == "integrator") {
    integrator(doc, node);
  } else if (tag == "sensor") {
    sensor(doc, node);
  } else if (tag == "shape") {
    shape(doc, node);
  } else if (tag == "bsdf") {
    bsdf(doc, node);
  } else if (tag == "texture") {
    texture(doc, node);
  } else if (tag == "emitter") {
    emitter(doc, node, -1);
  } else {
    scene_.warnings.add(doc.where(node), "<" + tag + "> is not supported; ignored");
  }
}

void SceneBuilder::include(const Document& doc, const pugi::xml_node& node, int includeDepth) {
  if (includeDepth >= kMaxIncludeDepth)
    throw InputError(doc.where(node), "includes nested more than 16 deep (an include cycle?)");
  std::string file = resolvePath(doc, attribute(doc, node, "filename"), doc.where(node));
  requireFile(file, doc.where(node), "included file");
  readReferencedFile(doc.where(node), [&] { loadFile(file, includeDepth + 1); });
}

Properties SceneBuilder::readProperties(const Document& doc, const pugi::xml_node& node,
                                        std::vector<pugi::xml_node>* children) {
  Properties props(std::string("<") + node.name() + " type=\"" + node.attribute("type").value() + "\">",
                   doc.where(node));
  for (pugi::xml_node child : node.children()) {
    if (child.type() != pugi::node_element) continue;
    std::string tag = child.name();
    SourceLocation where = doc.where(child);
    bool named = !child.attribute("name").empty();
    std::string name = named ? normalizeName(attribute(doc, child, "name")) : "";
    Property p;
    p.tag = tag;
    p.where = where;
    if (isValueTag(tag)) {
      if (!named) throw InputError(where, "<" + tag + "> needs the attribute 'name'");
      if ((tag == "point" || tag == "vector") && child.attribute("value").empty()) {
        auto coord = [&](const char* c) {
          std::string v = attribute(doc, child, c, false);
          return v.empty() ? std::string("0") : v;
        };
        p.value = coord("x") + "," + coord("y") + "," + coord("z");
      } else {
        p.value = attribute(doc, child, "value");
      }
      props.set(name, p);
    } else if (tag == "transform") {
      p.transform = readTransform(doc, child);
      props.set(name, p);
    } else if (tag == "texture" && named) {
      p.texture = texture(doc, child);
      props.set(name, p);
    } else if (tag == "ref" && named && textureIds_.count(attribute(doc, child, "id"))) {
      p.tag = "texture";
      p.texture = textureIds_.at(attribute(doc, child, "id"));
      props.set(name, p);
    } else if (tag == "blackbody") {
      if (!named) throw InputError(where, "<blackbody> needs the attribute 'name'");
      p.value = blackbodyValue(doc, child);
      props.set(name, p);
    } else if (children) {
      children->push_back(child);
    } else {
      scene_.warnings.add(where, "<" + tag + "> is not supported inside <" + node.name() + ">; ignored");
    }
  }
  // A parameter given under another name its plugin takes (a Mitsuba 0.6 alias) gets the name
  // the plugin readers use.
  if (hasParameterAliases(node.name())) resolveAliases(node.name(), attribute(doc, node, "type", false), props);
  return props;
}

// Mitsuba 0.6's <blackbody temperature="3500K" scale="..."/>: its linear sRGB colour
// (blackbody.h), written out as the numbers an <rgb> would hold.
std::string SceneBuilder::blackbodyValue(const Document& doc, const pugi::xml_node& node) {
  const SourceLocation where = doc.where(node);
  std::string temperature = attribute(doc, node, "temperature");
  while (!temperature.empty() && std::isspace(static_cast<unsigned char>(temperature.back()))) temperature.pop_back();
  if (!temperature.empty() && (temperature.back() == 'K' || temperature.back() == 'k')) temperature.pop_back();
  const double kelvin = parseNumber(temperature, where, "the blackbody temperature");
  if (!(kelvin > 0 && kelvin < 1e6)) throw InputError(where, "blackbody temperature must be in (0, 1e6) kelvin");
  const std::string scaleText = attribute(doc, node, "scale", false);
  const double scale = scaleText.empty() ? 1.0 : parseNumber(scaleText, where, "the blackbody scale");
  if (!std::isfinite(scale)) throw InputError(where, "blackbody scale must be finite");
  const Color rgb = blackbodyLinearRgb(kelvin) * float(scale);
  char text[96];
  std::snprintf(text, sizeof text, "%.9g, %.9g, %.9g", double(rgb.x), double(rgb.y), double(rgb.z));
  return text;
}

Transform SceneBuilder::readTransform(const Document& doc, const pugi::xml_node& node) {
  Transform result;
  for (pugi::xml_node op : node.children()) {
    if (op.type() != pugi::node_element) continue;
    std::string tag = op.name();
    SourceLocation where = doc.where(op);
    auto num = [&](const char* a, double fallback) {
      std::string v = attribute(doc, op, a, false);
      return v.empty() ? fallback : parseNumber(v, where, std::string("'") + a + "' of <" + tag + ">");
    };
    auto vec = [&](const char* a) { return parseVector(attribute(doc, op, a), where, std::string("'") + a + "'"); };
    Transform t;
    if (tag == "translate" || tag == "scale") {
      double d = tag == "scale" ? 1.0 : 0.0;
      Vec3 v(float(num("x", d)), float(num("y", d)), float(num("z", d)));
      if (!op.attribute("value").empty()) v = vec("value");
      t = tag == "scale" ? Transform::scale(v.x, v.y, v.z) : Transform::translate(v.x, v.y, v.z);
    } else if (tag == "rotate") {
      Vec3 axis(float(num("x", 0)), float(num("y", 0)), float(num("z", 0)));
      if (!op.attribute("value").empty()) axis = vec("value");
      if (length(axis) == 0) throw InputError(where, "<rotate> needs a non-zero axis");
      t = Transform::rotate(axis.x, axis.y, axis.z, num("angle", 0));
    } else if (tag == "matrix") {
      std::vector<double> v = parseNumberList(attribute(doc, op, "value"), where, "<matrix>");
      if (v.size() == 16) {
        for (int i = 0; i < 16; ++i) t.m[i] = v[i];
      } else if (v.size() == 9) {
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) t(r, c) = v[r * 3 + c];
      } else {
        throw InputError(where, "<matrix> needs 16 (or 9) numbers, got " + std::to_string(v.size()));
      }
      // A bottom row (0 0 0 w) is the affine map scaled by w in homogeneous coordinates: divide
      // it out. Any other bottom row is a projective map, which no to_world can be.
      const double w = t(3, 3);
      if (t(3, 0) != 0 || t(3, 1) != 0 || t(3, 2) != 0 || w == 0)
        throw InputError(where, "<matrix> is projective (bottom row must be 0 0 0 w with w != 0)");
      for (double& e : t.m) e /= w;
    } else if (tag == "lookat" || tag == "lookAt") {
      Vec3 origin = vec("origin"), target = vec("target");
      Vec3 dir = target - origin;
      Vec3 up = op.attribute("up").empty() ? Vec3(0, 1, 0) : vec("up");
      if (length(dir) == 0) throw InputError(where, "<lookat> origin and target coincide");
      if (length(cross(up, dir)) == 0) {
        if (!op.attribute("up").empty()) throw InputError(where, "<lookat> up is parallel to the view direction");
        up = Vec3(1, 0, 0);
      }
      t = Transform::lookAt(origin, target, up);
    } else {
      throw InputError(where, "unknown transform operation <" + tag + ">");
    }
    std::string defect = t.defect();
    if (!defect.empty()) throw InputError(where, "<" + tag + "> " + defect);
    result = t * result;  // document order: each operation applies after the previous ones
    defect = result.defect();
    if (!defect.empty()) throw InputError(where, "the transform up to this <" + tag + "> " + defect);
  }
  return result;
}

void SceneBuilder::integrator(const Document& doc, const pugi::xml_node& node) {
  std::vector<pugi::xml_node> children;
  Properties props = readProperties(doc, node, &children);
  std::string type = attribute(doc, node, "type");
  // Wrappers such as Mitsuba 3's `aov` or `moment` hold the real integrator inside.
  for (const pugi::xml_node& child : children)
    if (std::string(child.name()) == "integrator") {
      scene_.warnings.add(doc.where(node), "integrator '" + type + "' is not supported; using the nested one");
      integrator(doc, child);
      return;
    }
  scene_.integrator.type = type;
  scene_.integrator.maxDepth = props.getInt("max_depth", scene_.integrator.maxDepth);
  if (scene_.integrator.maxDepth < -1 || scene_.integrator.maxDepth == 0)
    throw InputError(props.find("max_depth")->where, "max_depth must be -1 (unbounded) or at least 1");
  props.warnUnused(scene_.warnings);
}

}  // namespace erpt::xml
