#include "kernels/bdpt_mis.h"

namespace erpt {

namespace {
// p_j / p_s for every strategy j, as a running product outward from s: strategy j + 1 takes
// vertex x_{k-j} from the light side where strategy j took it from the camera side. The light
// vertex x_k itself is sampled by the camera (j = 0), next-event estimation (j = 1) or emission
// (j >= 2): its density is kept apart (lightTerm) so that a zero next-event density never
// divides.
double lightTerm(const BdptMisPath& path, int j) {
  if (j == 0) return path.cameraDensity[path.k];
  if (j == 1 && path.k > 1) return path.nextEventDensity;
  return path.lightDensity[path.k];  // emission (k = 1, s = 1: the light point connected to the camera)
}

// The ratio of the vertex densities x_0 .. x_{k-1} of strategy j + 1 to strategy j.
double stepRatio(const BdptMisPath& path, int j) {
  if (j == 0) return 1;  // j = 0 -> 1 moves only the light vertex
  const int i = path.k - j;
  return double(path.lightDensity[i]) / double(path.cameraDensity[i]);
}
}  // namespace

bool bdptStrategyPossible(const BdptMisPath& path, int s) {
  const int k = path.k, t = k + 1 - s;
  if (s < 0 || t < 1) return false;
  if (s == 0) return path.lightHittable && !path.specular[k];
  if (k == 1 && s == 1 && !path.lightSeenByLightTracing) return false;
  // The connection x_{t-1} -- x_t: neither end may be a Dirac lobe (the light vertex x_k never is).
  return !path.specular[t - 1] && (t == k || !path.specular[t]);
}

float bdptMisWeight(const BdptMisPath& path, int s) {
  const int k = path.k;
  const double own = lightTerm(path, s);
  if (!(own > 0)) return 0.0f;
  double sum = 1, ratio = 1;  // ratio: densities of x_0 .. x_{k-1}, strategy j over strategy s
  for (int j = s; j < k; ++j) {  // towards the light: j + 1
    const double denominator = path.cameraDensity[k - j];
    if (j > 0 && !(denominator > 0)) break;  // s's own density: only a float underflow gets here
    ratio *= stepRatio(path, j);
    if (bdptStrategyPossible(path, j + 1)) {
      const double r = ratio * lightTerm(path, j + 1) / own;
      sum += r * r;
    }
  }
  ratio = 1;
  for (int j = s; j > 0; --j) {  // towards the camera: j - 1
    const double step = stepRatio(path, j - 1);
    if (j - 1 > 0 && !(step > 0)) break;
    if (j - 1 > 0) ratio /= step;
    if (bdptStrategyPossible(path, j - 1)) {
      const double r = ratio * lightTerm(path, j - 1) / own;
      sum += r * r;
    }
  }
  const double w = 1.0 / sum;
  return float(w == w ? w : 0.0);
}

}  // namespace erpt
