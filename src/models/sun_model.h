// The sun as Mitsuba 0.6's `sun` and `sunsky` emitters define it: placed from a date, time and
// place (or given directly), its radiance from the attenuated solar spectrum of Preetham,
// Shirley and Smits (1999), and drawn into an environment map as a small disk.
//
// Directions use Mitsuba 0.6's sky frame: +y is the zenith; a direction at zenith angle theta
// and azimuth phi is (sin phi sin theta, cos theta, -cos phi sin theta), so azimuth 0 lies
// along -z and azimuth 90 degrees (east, for a sun placed by date) along +x. This is also
// the frame of the environment maps the sky and sun are drawn into (environment_map.h), so a
// pixel's centre at (theta, phi) = ((y + 0.5) pi / H, (x + 0.5) 2 pi / W) looks along that
// direction.
#pragma once

#include "erpt/image_io.h"
#include "erpt/math.h"

namespace erpt {

// Where the sun is, in the sky frame: zenith angle and azimuth in radians.
struct SunAngles {
  double zenith = 0, azimuth = 0;
};

struct DateTime {
  int year = 2010, month = 7, day = 10;
  double hour = 15, minute = 0, second = 0;  // local time
};
struct Location {
  double latitude = 35.6894, longitude = 139.6917, timezone = 9;  // degrees, degrees, hours (Tokyo)
};

// The sun's position seen from `location` at `time` (Blanco-Muriel et al. 2001, "Computing the
// solar vector", the PSA algorithm; ~0.5 arc minutes; no daylight saving time).
SunAngles sunPosition(const DateTime& time, const Location& location);
// Zenith angle and azimuth of a unit direction in the sky frame, and back.
SunAngles anglesOf(Vec3 direction);
Vec3 directionOf(double zenith, double azimuth);

// The sun disk's angular radius (Mitsuba 0.6: half of an apparent diameter of 0.5358 degrees).
constexpr double kSunAngularRadius = 0.5358 / 2 * 3.14159265358979323846 / 180;

// Radiance of the sun disk seen through the atmosphere with the sun at `zenith` (radians) and
// the given turbidity: the extraterrestrial solar spectrum times the transmittances of Rayleigh
// scattering, aerosols, ozone, mixed gases and water vapour along the relative optical mass,
// converted to linear RGB as spectrum.h says (W / (m^2 sr nm), as Mitsuba 0.6's RGB build).
Color sunRadiance(double zenith, double turbidity);

// Adds the sun to a lat-long image of the sky frame: the power of a disk of radiance
// `radiance` and kSunAngularRadius, spread uniformly over a disk `radiusScale` times as wide
// (Mitsuba's sun_radius_scale keeps the power), binned into the pixels by stratified samples
// of the disk and divided by each pixel's solid angle.
void addSunToImage(RgbImage& image, SunAngles sun, Color radiance, double radiusScale);

}  // namespace erpt
