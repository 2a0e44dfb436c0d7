// pssmlt's and mmlt's statistics after a render: the bootstrap, the chains, acceptance by step kind.
#include <cstdio>

#include "integrators/primary_sample_mlt.h"

namespace erpt {

void addPssmltStats(PssmltStats& to, const PssmltStats& from) {
  to.b = from.b;  // the passes of a timed render share one bootstrap
  to.bootstrapSamples += from.bootstrapSamples;
  to.chains += from.chains;
  to.chainLength = from.chainLength;
  to.smallSteps += from.smallSteps, to.smallAccepted += from.smallAccepted;
  to.largeSteps += from.largeSteps, to.largeAccepted += from.largeAccepted;
  to.invalidProposals += from.invalidProposals;
  to.rays += from.rays;
  to.bootstrapSeconds += from.bootstrapSeconds;
  to.chainSeconds += from.chainSeconds;
}

void printPrimarySampleSummary(const char* name, const RenderStats& stats) {
  const PssmltStats& p = pssmltStatsOf(stats);
  const auto share = [](uint64_t part, uint64_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; };
  const uint64_t steps = p.smallSteps + p.largeSteps;
  std::fprintf(stderr, "%s: b %.6g (bootstrap: %llu samples, %.2f s)\n", name, p.b, (unsigned long long)p.bootstrapSamples,
               p.bootstrapSeconds);
  std::fprintf(stderr,
               "%s: %llu chains x %llu steps, %llu steps (%.2f M/s in %.2f s); accepted: small steps %.1f%%, large "
               "steps %.1f%%; %llu invalid proposals\n",
               name, (unsigned long long)p.chains, (unsigned long long)p.chainLength, (unsigned long long)steps,
               p.chainSeconds > 0 ? double(steps) / p.chainSeconds * 1e-6 : 0.0, p.chainSeconds,
               share(p.smallAccepted, p.smallSteps), share(p.largeAccepted, p.largeSteps),
               (unsigned long long)p.invalidProposals);
}

}  // namespace erpt
