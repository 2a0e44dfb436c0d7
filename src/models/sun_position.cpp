// The sun's zenith angle and azimuth for a date, local time and place: the PSA algorithm of
// Blanco-Muriel, Alarcon-Padilla, Lopez-Moratalla and Lara-Coira (2001), which Mitsuba 0.6's
// sky and sun emitters use. Azimuth is measured from north towards east.
#include <algorithm>
#include <cmath>

#include "models/sun_model.h"

namespace erpt {

namespace {
constexpr double kPiD = 3.14159265358979323846;
double radians(double degrees) { return degrees * kPiD / 180; }
double wrapTwoPi(double a) { return a < 0 ? a + 2 * kPiD : a; }
}  // namespace

SunAngles anglesOf(Vec3 d) {
  SunAngles a;
  a.zenith = std::acos(std::clamp(double(d.y), -1.0, 1.0));
  a.azimuth = std::atan2(double(d.x), -double(d.z));
  if (a.azimuth < 0) a.azimuth += 2 * kPiD;
  return a;
}

Vec3 directionOf(double zenith, double azimuth) {
  return Vec3{float(std::sin(azimuth) * std::sin(zenith)), float(std::cos(zenith)),
              float(-std::cos(azimuth) * std::sin(zenith))};
}

SunAngles sunPosition(const DateTime& time, const Location& location) {
  // Days since JD 2451545.0 (noon UT, 1 January 2000); the Julian day number from the civil
  // date in integer arithmetic (C++ division truncates towards zero, as the algorithm needs).
  const double utHours = time.hour - location.timezone + (time.minute + time.second / 60) / 60;
  const int a = (time.month - 14) / 12;
  const long dayNumber = (1461L * (time.year + 4800 + a)) / 4 + (367L * (time.month - 2 - 12 * a)) / 12 -
                         (3L * ((time.year + 4900 + a) / 100)) / 4 + time.day - 32075;
  const double n = double(dayNumber) - 0.5 + utHours / 24 - 2451545.0;

  // Ecliptic longitude and obliquity (radians, not reduced to [0, 2 pi)).
  const double omega = 2.1429 - 0.0010394594 * n;
  const double meanLongitude = 4.8950630 + 0.017202791698 * n;
  const double meanAnomaly = 6.2400600 + 0.0172019699 * n;
  const double eclipticLongitude = meanLongitude + 0.03341607 * std::sin(meanAnomaly) +
                                   0.00034894 * std::sin(2 * meanAnomaly) - 0.0001134 - 0.0000203 * std::sin(omega);
  const double obliquity = 0.4090928 - 6.2140e-9 * n + 0.0000396 * std::cos(omega);

  // Right ascension and declination.
  const double sinLongitude = std::sin(eclipticLongitude);
  const double rightAscension =
      wrapTwoPi(std::atan2(std::cos(obliquity) * sinLongitude, std::cos(eclipticLongitude)));
  const double declination = std::asin(std::sin(obliquity) * sinLongitude);

  // Local coordinates.
  const double greenwichSiderealHours = 6.6974243242 + 0.0657098283 * n + utHours;
  const double localSidereal = radians(greenwichSiderealHours * 15 + location.longitude);
  const double latitude = radians(location.latitude);
  const double hourAngle = localSidereal - rightAscension;
  SunAngles sun;
  sun.zenith = std::acos(std::cos(latitude) * std::cos(hourAngle) * std::cos(declination) +
                         std::sin(declination) * std::sin(latitude));
  sun.azimuth = wrapTwoPi(std::atan2(-std::sin(hourAngle),
                                     std::tan(declination) * std::cos(latitude) - std::sin(latitude) * std::cos(hourAngle)));
  // Parallax: the observer stands on the Earth's surface, not at its centre.
  const double earthRadiusKm = 6371.01, astronomicalUnitKm = 149597890;
  sun.zenith += earthRadiusKm / astronomicalUnitKm * std::sin(sun.zenith);
  return sun;
}

}  // namespace erpt
