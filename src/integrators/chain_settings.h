// What the chain drivers (ChainLanes, PMC-ER's population) read of the user's options besides
// the step's (StepSettings): how seeds become chains and the deposit filters.
#pragma once

#include "erpt/erpt_settings.h"

namespace erpt {

struct ChainSettings {
  int chainLength = ErptSettings{}.chainLength;            // m: steps of every chain
  int maxChainsPerSeed = ErptSettings{}.maxChainsPerSeed;  // chains one seed may start
  int directSamples = ErptSettings{}.directSamples;        // > 0: one-bounce seeds are the direct pass's
  int maxConsecutive = ErptSettings{}.maxConsecutive;      // consecutive-sample filter (0: off)
  int pmFilterRadius = ErptSettings{}.pmFilterRadius;      // proposed-mutations filter (-1: off)
  bool chainMaps = ErptSettings{}.chainMaps;               // tally the mutations and acceptance maps
};

inline ChainSettings chainSettingsOf(const ErptSettings& s) {
  return ChainSettings{s.chainLength, s.maxChainsPerSeed, s.directSamples, s.maxConsecutive, s.pmFilterRadius, s.chainMaps};
}

}  // namespace erpt
