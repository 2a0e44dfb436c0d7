// Daylight as Mitsuba 0.6's `sky` emitter defines it: the Hosek-Wilkie (2012) analytic sky-dome
// model in its RGB form, for a sun placed as sun_model.h says, in the sky frame described there.
#pragma once

#include "erpt/image_io.h"
#include "erpt/math.h"
#include "models/sun_model.h"

namespace erpt {

// The model for one sun position, turbidity (1-10) and per-channel ground albedo (0-1).
class HosekWilkieSky {
 public:
  // Throws std::invalid_argument when a parameter is outside the model's range or the sun is
  // below the horizon (the model has no night sky).
  HosekWilkieSky(double turbidity, Color albedo, SunAngles sun);

  // Linear RGB radiance arriving from sky-frame direction (theta, phi): Mitsuba 0.6's scale
  // (the model's tristimulus values divided by the sum of the CIE Y samples, 106.856980),
  // zero below the horizon.
  Color radiance(double theta, double phi) const;
  // The model's value for a view at zenith angle theta and angle gamma from the sun, per
  // channel, before Mitsuba's scale (exposed for the tests).
  double modelRadiance(int channel, double theta, double gamma) const;
  const SunAngles& sun() const { return sun_; }

 private:
  double config_[3][9];
  double scale_[3];
  SunAngles sun_;
};

struct SkySettings {
  double turbidity = 3;
  Color albedo = Color(0.2f);  // Mitsuba 0.6's code default (its manual says 0.15)
  SunAngles sun;
  double stretch = 1;     // zenith angles are divided by this (1-2) to reach below the horizon
  bool extend = false;    // Mitsuba 0.6's "extend": the horizon's colour continues below it, fading out
  int resolution = 512;   // width of the environment map (height = width / 2)
  float scale = 1;
};

// Throws std::invalid_argument naming the first setting outside its range (turbidity 1-10,
// albedo 0-1, stretch 1-2, resolution 2-8192, a finite scale >= 0, the sun above the horizon).
void checkSkySettings(const SkySettings& settings);

// The sky drawn into a latitude-longitude image of resolution x resolution / 2 pixels, each
// pixel holding the radiance along its centre's direction (Mitsuba 0.6 does the same and then
// renders an `envmap`).
RgbImage rasterizeSky(const SkySettings& settings);

}  // namespace erpt
