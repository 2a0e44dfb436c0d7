// Every integrator's options as declared (include/erpt/options.h): the defaults are values the
// options take, text round-trips, ranges and choices refuse what they do not take, with the
// option's name in the message, and render() applies the same ranges to programmatic settings.
#include <gtest/gtest.h>

#include "erpt/erpt_settings.h"
#include "erpt/pmc_settings.h"
#include "erpt/integrators.h"
#include "erpt/options.h"
#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

std::vector<std::pair<const IntegratorModule*, const OptionSpec*>> everyOption() {
  std::vector<std::pair<const IntegratorModule*, const OptionSpec*>> all;
  for (const IntegratorModule& m : integratorModules())
    for (const OptionSpec& o : m.options) all.emplace_back(&m, &o);
  return all;
}

TEST(OptionTable, DefaultsAreInRangeAndRoundTrip) {
  for (const auto& [module, option] : everyOption()) {
    SCOPED_TRACE(module->name + " " + option->flag());
    const RenderSettings defaults;
    EXPECT_NO_THROW(checkOptionRange(*option, defaults));
    ASSERT_TRUE(option->get);
    ASSERT_TRUE(option->set);
    if (option->kind == OptionKind::Flag) continue;
    RenderSettings s;
    option->set(s, option->defaultText());
    EXPECT_EQ(option->get(s), option->defaultText());
  }
}

TEST(OptionTable, EachOptionIsDeclaredOnceWithOneMeaning) {
  // An option several integrators share comes from one declaration: same kind, range, help.
  for (const auto& [m1, o1] : everyOption())
    for (const auto& [m2, o2] : everyOption()) {
      if (o1->name != o2->name) continue;
      SCOPED_TRACE(o1->flag() + " in " + m1->name + " and " + m2->name);
      EXPECT_EQ(o1->help, o2->help);
      EXPECT_EQ(o1->allowed(), o2->allowed());
      EXPECT_EQ(o1->defaultText(), o2->defaultText());
    }
  for (const IntegratorModule& m : integratorModules())
    for (size_t i = 0; i < m.options.size(); ++i)
      for (size_t j = i + 1; j < m.options.size(); ++j) EXPECT_NE(m.options[i].name, m.options[j].name) << m.name;
}

TEST(OptionTable, RangesAndChoicesRefuseWhatTheyDoNotTake) {
  for (const auto& [module, option] : everyOption()) {
    SCOPED_TRACE(module->name + " " + option->flag());
    RenderSettings s;
    std::vector<std::string> bad;
    if (option->kind == OptionKind::Integer)
      bad = {formatOptionNumber(option->min - 1), formatOptionNumber(option->max + 1), "1.5", "x", ""};
    if (option->kind == OptionKind::Real) bad = {formatOptionNumber(option->max * 2 + 1), "nan", "inf", "x", ""};
    if (option->kind == OptionKind::Real && option->min > -1e300) bad.push_back(formatOptionNumber(option->min - 1));
    if (option->kind == OptionKind::Choice) bad = {"nonsense", ""};
    if (option->kind == OptionKind::List) bad = {"1,,2", "a", ""};
    for (const std::string& text : bad) {
      try {
        option->set(s, text);
        ADD_FAILURE() << "accepted '" << text << "'";
      } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find(option->flag()), std::string::npos) << e.what();
      }
    }
  }
}

TEST(OptionTable, RenderRefusesProgrammaticSettingsOutOfRange) {
  // Fields set directly, as a caller of the API could: the declared ranges still hold.
  const Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  RenderSettings s;
  s.integrator = "erpt";
  s.width = 8, s.height = 6, s.spp = 1;
  erptOf(s).chainLength = 0;
  RenderStats stats;
  try {
    render(scene, s, stats);
    FAIL() << "rendered with --chain-length 0";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--chain-length must be in [1, 16777216]"), std::string::npos) << e.what();
  }
  erptOf(s).chainLength = 10;
  chainOf(s).lensRadius = 0;
  EXPECT_THROW(render(scene, s, stats), UsageError);
  chainOf(s).lensRadius = 4.5f;
  s.integrator = "pmc-er";
  pmcOf(s).resampleRate = 2;
  EXPECT_THROW(render(scene, s, stats), UsageError);
}

TEST(OptionTable, ApplyingOptionsSetsOnlyTheIntegratorsOwnAndRefusesOnesWithoutEffect) {
  RenderSettings s;
  applyOptions(integratorNamed("erpt"), {{"chain-length", "7"}, {"population", "3"}, {"pm-filter", "true"}}, s);
  EXPECT_EQ(erptOf(s).chainLength, 7);
  EXPECT_EQ(pmcOf(s).population, PmcSettings{}.population);  // not an ERPT option: left to the front end's scope check
  EXPECT_EQ(chainOf(s).pmFilterRadius, 3);
  RenderSettings p;
  EXPECT_THROW(applyOptions(integratorNamed("pmc-er"), {{"pmc-adapt", "off"}, {"pmc-region", "8"}}, p), UsageError);
  RenderSettings q;
  applyOptions(integratorNamed("pmc-er"), {{"pmc-adapt", "region"}, {"pmc-region", "8"}, {"radii", "2,7.5"}}, q);
  EXPECT_EQ(pmcOf(q).regionSize, 8);
  EXPECT_EQ(pmcOf(q).radii, (std::vector<float>{2, 7.5f}));
}

}  // namespace
}  // namespace erpt
