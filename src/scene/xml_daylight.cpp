// Mitsuba 0.6's daylight emitters: `sky` (the Hosek-Wilkie sky), `sun` (the Preetham sun
// disk) and `sunsky` (both), for a sun placed by date, time and place or by `sun_direction`.
// As in Mitsuba 0.6 they are drawn into one environment map; a `sun` and a `sky` given as two
// emitters are added into the same map. A sun radius scale of 0 makes the sun a directional
// light instead.
#include <cmath>
#include <stdexcept>

#include "erpt/environment_map.h"
#include "models/sky_model.h"
#include "models/sun_model.h"
#include "scene_builder.h"

namespace erpt::xml {

namespace {

// The date-and-place parameters; Mitsuba 0.6 refuses them together with a sun direction.
const char* const kTimeAndPlace[] = {"year", "month", "day", "hour", "minute", "second", "latitude", "longitude", "timezone"};

SunAngles sunFromProperties(const Properties& props, const Transform& toWorld, const SourceLocation& where) {
  if (props.has("sun_direction")) {
    for (const char* name : kTimeAndPlace)
      if (props.has(name))
        throw InputError(where, std::string("give either 'sun_direction' or the date, time and place ('") + name +
                                    "'), not both");
    const Vec3 world = props.getPoint("sun_direction", Vec3(0.0f));
    const Vec3 local = toWorld.inverse().vector(world);
    const float length = std::sqrt(dot(local, local));
    if (!(length > 0) || !std::isfinite(length)) throw InputError(where, "'sun_direction' must be a non-zero vector");
    return anglesOf(local / length);
  }
  DateTime time;
  Location place;
  time.year = props.getInt("year", time.year);
  time.month = props.getInt("month", time.month);
  time.day = props.getInt("day", time.day);
  time.hour = props.getFloat("hour", float(time.hour));
  time.minute = props.getFloat("minute", float(time.minute));
  time.second = props.getFloat("second", float(time.second));
  place.latitude = props.getFloat("latitude", float(place.latitude));
  place.longitude = props.getFloat("longitude", float(place.longitude));
  place.timezone = props.getFloat("timezone", float(place.timezone));
  if (time.month < 1 || time.month > 12) throw InputError(where, "'month' must be in 1-12");
  if (time.day < 1 || time.day > 31) throw InputError(where, "'day' must be in 1-31");
  if (time.year < -4000 || time.year > 10000) throw InputError(where, "'year' must be in -4000-10000");
  if (!(std::fabs(place.latitude) <= 90)) throw InputError(where, "'latitude' must be in [-90, 90] degrees");
  for (double v : {time.hour, time.minute, time.second, place.longitude, place.timezone})
    if (!std::isfinite(v) || std::fabs(v) > 1e5) throw InputError(where, "the time and place must be finite numbers");
  return sunPosition(time, place);
}

bool sameTransform(const Transform& a, const Transform& b) {
  for (int i = 0; i < 16; ++i)
    if (std::fabs(a.m[size_t(i)] - b.m[size_t(i)]) > 1e-9) return false;
  return true;
}

}  // namespace

int SceneBuilder::daylight(const std::string& type, Properties& props, const SourceLocation& where) {
  const Transform toWorld = props.getTransform("to_world");
  const bool hasSky = type != "sun", hasSun = type != "sky";
  // Mitsuba 0.6: `scale` scales the sky and the sun, which `sky_scale` / `sun_scale` override.
  const float scale = props.getFloat("scale", 1.0f);
  SkySettings sky;
  sky.scale = type == "sunsky" ? props.getFloat("sky_scale", scale) : scale;
  const float sunScale = type == "sunsky" ? props.getFloat("sun_scale", scale) : scale;
  sky.turbidity = props.getFloat("turbidity", float(sky.turbidity));
  sky.stretch = props.getFloat("stretch", float(sky.stretch));
  sky.resolution = props.getInt("resolution", sky.resolution);
  if (hasSky) {
    sky.albedo = props.getColor("albedo", sky.albedo);
    sky.extend = props.getBool("extend", sky.extend);
  }
  const double radiusScale = hasSun ? props.getFloat("sun_radius_scale", 1.0f) : 1.0;
  sky.sun = sunFromProperties(props, toWorld, where);

  RgbImage image;
  try {
    checkSkySettings(sky);  // a lone sun needs the same turbidity, sun height and resolution
    if (!(radiusScale >= 0 && radiusScale <= 100)) throw std::invalid_argument("sun_radius_scale must be in [0, 100]");
    if (!(sunScale >= 0) || !std::isfinite(sunScale)) throw std::invalid_argument("the scales must be finite numbers >= 0");
    if (hasSky) {
      image = rasterizeSky(sky);
    } else {
      image.width = sky.resolution;
      image.height = sky.resolution / 2;
      image.pixels.assign(size_t(image.width) * image.height, Color(0.0f));
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(where, type + ": " + e.what());
  }
  if (hasSun) {
    // The radiance follows the true sun height; the disk is drawn where `stretch` puts it.
    const Color radiance = sunRadiance(sky.sun.zenith, sky.turbidity) * sunScale;
    const SunAngles drawn{sky.sun.zenith * sky.stretch, sky.sun.azimuth};
    if (radiusScale > 0) {
      addSunToImage(image, drawn, radiance, radiusScale);
    } else {
      Emitter sun;
      sun.kind = EmitterKind::Directional;
      sun.radiance = radiance * float(2 * 3.14159265358979 * (1 - std::cos(kSunAngularRadius)));
      sun.axis = normalize(toWorld.vector(-directionOf(drawn.zenith, drawn.azimuth)));
      scene_.emitters.push_back(sun);
    }
  }
  props.find("sampling_weight");
  props.warnUnused(scene_.warnings);
  if (!hasSky && radiusScale == 0) return int(scene_.emitters.size()) - 1;  // a sun that is only a direction

  // A second daylight emitter (a `sun` beside a `sky`) adds to the first one's map.
  if (daylight_) {
    if (daylight_->image.width != image.width || daylight_->image.height != image.height ||
        !sameTransform(daylight_->toWorld, toWorld))
      throw InputError(where, type + " and the daylight emitter before it need the same resolution and to_world to be "
                                     "combined into one environment");
    for (size_t i = 0; i < image.pixels.size(); ++i) daylight_->image.pixels[i] += image.pixels[i];
  } else {
    if (scene_.environment()) throw InputError(where, "only one environment emitter is supported");
    Emitter e;
    e.kind = EmitterKind::Constant;
    scene_.emitters.push_back(e);
    daylight_ = Daylight{std::move(image), toWorld, int(scene_.emitters.size()) - 1};
  }
  Emitter& e = scene_.emitters[size_t(daylight_->emitter)];
  try {
    e.map = std::make_shared<const EnvironmentMap>(daylight_->image, 1.0f, toWorld);
  } catch (const std::invalid_argument& ex) {
    throw InputError(where, type + ": " + ex.what());
  }
  e.radiance = e.map->mean();
  return daylight_->emitter;
}

}  // namespace erpt::xml
