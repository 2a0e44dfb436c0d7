// The deposit stage's consecutive-sample filter drops only what it should: with the filter off
// nothing is dropped, wherever a deposit lands inside the film density's support (a tent or
// gaussian filter's reaches beyond the image, where film positions are negative).
#include <gtest/gtest.h>

#include "models/film.h"
#include "models/film_density.h"
#include "models/pixel_filter.h"
#include "stages/chain_stages.h"

namespace erpt {
namespace {

struct OneSlot {
  ChainQueue chains;
  ProposalQueue proposals;
  DepositQueue deposits;
  OneSlot(float x, float y) {
    chains.resize(1);
    proposals.resize(1);
    deposits.resize(kDepositsPerStep);
    chains.filmX[0] = x, chains.filmY[0] = y;
    chains.step[0] = 1;  // it took a step this round
    deposits.setRow(0, DepositQueue::Row{x, y, Color(1.0f)});
  }
};

TEST(ChainDeposit, NothingIsDroppedWithTheFilterOffAnywhereInTheFilmSupport) {
  const PixelFilter tent(FilterKind::Tent);
  const FilmDensity density(tent, 7, 5);
  for (const auto& [x, y] : std::vector<std::pair<float, float>>{{-0.25f, -0.25f}, {-0.25f, 2.5f}, {3.5f, -0.4f}, {6.5f, 4.5f}, {7.25f, 5.25f}}) {
    ASSERT_GT(density.density(x, y), 0.0f) << x << ", " << y;
    OneSlot s(x, y);
    Film film(7, 5);
    DepositFilters off;  // maxConsecutive 0: the consecutive-sample filter is off
    const double deposited = applyDeposits(s.chains, s.proposals, s.deposits, IndexRange{0, 1}, density, film, off);
    EXPECT_EQ(off.discarded, 0u) << "at " << x << ", " << y;
    EXPECT_NEAR(deposited, 1.0, 1e-6) << "at " << x << ", " << y;
    double total = 0;
    const RgbImage image = film.resolve(1.0);
    for (const Color& c : image.pixels) total += c.y;
    EXPECT_NEAR(total, 1.0, 1e-5) << "at " << x << ", " << y;
  }
}

TEST(ChainDeposit, TheFilterDropsARunOnOnePixelIncludingOneBeyondTheImage) {
  const PixelFilter tent(FilterKind::Tent);
  const FilmDensity density(tent, 7, 5);
  OneSlot s(-0.25f, -0.25f);
  Film film(7, 5);
  DepositFilters filter;
  filter.maxConsecutive = 2;
  for (int step = 1; step <= 4; ++step) {
    s.chains.step[0] = uint32_t(step);
    applyDeposits(s.chains, s.proposals, s.deposits, IndexRange{0, 1}, density, film, filter);
  }
  EXPECT_EQ(filter.discarded, 2u);  // steps 3 and 4 extend the run beyond 2
}

}  // namespace
}  // namespace erpt
