// The chain integrators' count of seeds deposited in place by reason (ChainStats::inPlace),
// checked on a directionally lit scene, where many are, for that reason.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>

#include "erpt/chain_options.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/test_support.h"

namespace erpt::test {

// Renders tests/data/directional.xml at 32x24 with `s`; the reasons must add up to the total
// the integrator's own statistics give (`totalOf(stats)`), and more than `minDirectional`
// seeds must be in place for the directional light. Returns the render's statistics.
template <class TotalOf>
RenderStats expectInPlaceReasonsAddUp(RenderSettings s, TotalOf&& totalOf, uint64_t minDirectional) {
  s.width = 32;
  s.height = 24;
  RenderStats stats;
  renderImage(loadScene(sourceDir() + "/tests/data/directional.xml"), s, &stats);
  const ChainStats& e = chainStatsOf(stats);
  uint64_t byReason = 0;
  for (uint64_t n : e.inPlace) byReason += n;
  EXPECT_EQ(byReason, totalOf(stats));
  EXPECT_GT(e.inPlace[kInPlaceDirectionalLight], minDirectional);
  return stats;
}

}  // namespace erpt::test
