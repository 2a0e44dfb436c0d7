// What the chain drivers (ChainLanes, PMC-ER's population) read of the user's options besides
// the step's (StepSettings): how seeds become chains and the deposit filters.
#pragma once

#include "erpt/erpt_settings.h"

namespace erpt {

struct ChainSettings {
  int chainLength = ErptSettings{}.chainLength;            // m: steps of every chain
  int maxChainsPerSeed = ErptSettings{}.maxChainsPerSeed;  // chains one seed may start
  int directSamples = ChainOptions{}.directSamples;        // > 0: one-bounce seeds are the direct pass's
  int maxConsecutive = ChainOptions{}.maxConsecutive;      // consecutive-sample filter (0: off)
  int pmFilterRadius = ChainOptions{}.pmFilterRadius;      // proposed-mutations filter (-1: off)
  bool chainMaps = ChainOptions{}.chainMaps;               // tally the mutations and acceptance maps
};

// ERPT's chains take its chain length and cap; PMC-ER's and MLT's keep the defaults (MLT sets
// its own length).
inline ChainSettings chainSettingsOf(const ChainOptions& c, const ErptSettings& e = ErptSettings{}) {
  return ChainSettings{e.chainLength, e.maxChainsPerSeed, c.directSamples, c.maxConsecutive, c.pmFilterRadius, c.chainMaps};
}

}  // namespace erpt
