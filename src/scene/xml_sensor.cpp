// <sensor>, its <film>, <rfilter> and <sampler>.
#include <cmath>
#include <cstdlib>

#include "scene_builder.h"

namespace erpt::xml {

void SceneBuilder::sensor(const Document& doc, const pugi::xml_node& node) {
  if (sawSensor_) {
    scene_.warnings.add(doc.where(node), "more than one <sensor>; using the first");
    return;
  }
  sawSensor_ = true;
  std::vector<pugi::xml_node> children;
  Properties props = readProperties(doc, node, &children);
  std::string type = attribute(doc, node, "type");
  if (type != "perspective" && type != "thinlens")
    throw InputError(doc.where(node), "unsupported sensor type '" + type + "'");
  CameraSettings& cam = scene_.camera;
  if (type == "thinlens") {
    cam.apertureRadius = props.getFloat("aperture_radius", 0.03f);  // Mitsuba's defaults
    cam.focusDistance = props.getFloat("focus_distance", 0.0f);
    if (!props.find("focus_distance")) throw InputError(doc.where(node), "thinlens needs a 'focus_distance'");
    if (!(cam.apertureRadius >= 0 && cam.apertureRadius < 1e6f))
      throw InputError(props.find("aperture_radius")->where, "aperture_radius must be >= 0");
    if (!(cam.focusDistance > 0 && cam.focusDistance < 1e30f))
      throw InputError(props.find("focus_distance")->where, "focus_distance must be > 0");
  }
  cam.toWorld = props.getTransform("to_world");
  if (std::abs(cam.toWorld.determinant3x3()) < 1e-12)
    throw InputError(props.find("to_world")->where, "the sensor's to_world transform is singular");
  // Rotations, reflections and translations only, as in Mitsuba 0.6 and 3: a scaled camera
  // frame has no meaning for a pinhole or a lens, and a large scale would overflow the
  // single-precision ray directions.
  for (int c = 0; c < 3; ++c) {
    const double len = std::sqrt(cam.toWorld(0, c) * cam.toWorld(0, c) + cam.toWorld(1, c) * cam.toWorld(1, c) +
                                 cam.toWorld(2, c) * cam.toWorld(2, c));
    if (std::abs(len - 1) > 1e-3)
      throw InputError(props.find("to_world")->where, "the sensor's to_world has a scale factor (" + std::to_string(len) +
                                                          "); a camera transform may only rotate, mirror and translate");
  }
  std::string axis = props.getString("fov_axis", "x");
  if (!props.find("fov") && props.find("focal_length")) {
    // Mitsuba's 35 mm film equivalent: the diagonal field of view of a 36 x 24 mm frame.
    const Property* f = props.find("focal_length");
    std::string text = f->value;
    if (text.size() > 2 && text.compare(text.size() - 2, 2, "mm") == 0) text.resize(text.size() - 2);
    char* end = nullptr;
    const double mm = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !(mm > 0) || !std::isfinite(mm))
      throw InputError(f->where, "focal_length must look like '50mm' (a positive length in mm), not '" + f->value + "'");
    cam.fovDegrees = float(2 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2 * mm)) * 180 / kPi);
    axis = "diagonal";
  }
  cam.fovDegrees = props.getFloat("fov", cam.fovDegrees);
  if (!(cam.fovDegrees > 0 && cam.fovDegrees < 180))
    throw InputError(props.find("fov")->where, "fov must be between 0 and 180 degrees");
  if (axis == "x") cam.fovAxis = FovAxis::X;
  else if (axis == "y") cam.fovAxis = FovAxis::Y;
  else if (axis == "diagonal") cam.fovAxis = FovAxis::Diagonal;
  else if (axis == "smaller") cam.fovAxis = FovAxis::Smaller;
  else if (axis == "larger") cam.fovAxis = FovAxis::Larger;
  else throw InputError(props.find("fov_axis")->where, "unknown fov_axis '" + axis + "' (x, y, diagonal, smaller, larger)");
  cam.nearClip = props.getFloat("near_clip", cam.nearClip);
  cam.farClip = props.getFloat("far_clip", cam.farClip);
  if (!(cam.nearClip > 0 && cam.farClip > cam.nearClip))
    throw InputError(doc.where(node), "need 0 < near_clip < far_clip");
  props.warnUnused(scene_.warnings);

  for (const pugi::xml_node& child : children) {
    std::string tag = child.name();
    if (tag == "film") {
      film(doc, child);
    } else if (tag == "sampler") {
      Properties sp = readProperties(doc, child);
      scene_.integrator.spp = sp.getInt("sample_count", scene_.integrator.spp);
      if (scene_.integrator.spp < 1) throw InputError(sp.find("sample_count")->where, "sample_count must be at least 1");
      sp.find("seed");  // Mitsuba's sampler seed; ours comes from --seed
      sp.warnUnused(scene_.warnings);
    } else {
      scene_.warnings.add(doc.where(child), "<" + tag + "> inside <sensor> is not supported; ignored");
    }
  }
}

void SceneBuilder::film(const Document& doc, const pugi::xml_node& node) {
  std::vector<pugi::xml_node> children;
  Properties props = readProperties(doc, node, &children);
  FilmSettings& f = scene_.film;
  f.width = props.getInt("width", f.width);
  f.height = props.getInt("height", f.height);
  if (f.width < 1 || f.height < 1 || f.width > 65536 || f.height > 65536)
    throw InputError(doc.where(node), "film size must be between 1 and 65536 pixels per side");
  // The output format follows the -o file name; these only matter to Mitsuba's own writer.
  for (const char* ignored : {"file_format", "pixel_format", "component_format", "banner", "high_quality_edges"})
    props.find(ignored);
  props.warnUnused(scene_.warnings);
  for (const pugi::xml_node& child : children) {
    if (std::string(child.name()) != "rfilter") {
      scene_.warnings.add(doc.where(child), std::string("<") + child.name() + "> inside <film> is not supported; ignored");
      continue;
    }
    Properties fp = readProperties(doc, child);
    std::string type = attribute(doc, child, "type");
    if (type == "box") f.filter = FilterKind::Box;
    else if (type == "tent") f.filter = FilterKind::Tent;
    else if (type == "gaussian") f.filter = FilterKind::Gaussian;
    else scene_.warnings.add(doc.where(child), "rfilter '" + type + "' is not supported; using gaussian");
    fp.warnUnused(scene_.warnings);
  }
}

}  // namespace erpt::xml
