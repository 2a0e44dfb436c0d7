#include "chain_options.h"

namespace erpt {

OptionSpec mutationsPerPixelOption() {
  return integerOption("mutations-per-pixel", "mutations per pixel M (ERPT: sets e_d = spp e_ave / M)", 1, 1 << 24,
                       [](auto& s) -> auto& { return chainOf(s).mutationsPerPixel; });
}

std::vector<OptionSpec> perturbationOptions() {
  return {
      choiceOption<MutationStrategy>(
          "mutation-strategy",
          "paper (caustic perturbation for L...SDE paths, lens otherwise), mixed (a coin when both apply), lens or "
          "caustic (one kind only)",
          {{"paper", MutationStrategy::Paper},
           {"mixed", MutationStrategy::Mixed},
           {"lens", MutationStrategy::LensOnly},
           {"caustic", MutationStrategy::CausticOnly}},
          [](auto& s) -> auto& { return chainOf(s).strategy; }),
      realOption("lens-radius", "size in pixels of lens perturbations (4.5 = the paper's 9x9 square)", 0, 10000,
                 [](auto& s) -> auto& { return chainOf(s).lensRadius; }, /*minOpen=*/true),
      choiceOption<LensShape>("lens-shape",
                              "lens perturbations move the film position uniformly in a square of half-side "
                              "--lens-radius (square, the paper's) or in a disk of that radius (disk, PMC-ER's)",
                              {{"square", LensShape::Square}, {"disk", LensShape::Disk}},
                              [](auto& s) -> auto& { return chainOf(s).lensShape; }),
      choiceOption<CausticAngle>("caustic-angle",
                                 "caustic perturbation angle: erpt (density 1/theta on [1e-4, 0.1] rad) or veach "
                                 "(uniform in [0, theta_max], PMC-ER eq. 6, for an image move of --lens-radius pixels)",
                                 {{"erpt", CausticAngle::Erpt}, {"veach", CausticAngle::Veach}},
                                 [](auto& s) -> auto& { return chainOf(s).causticAngle; }),
  };
}

OptionSpec directSamplesOption() {
  return integerOption("direct-samples",
                       "one-bounce paths by a direct-lighting pass with N samples per pixel; -1: the chains render "
                       "them too, as in the ERPT paper",
                       -1, 65536, [](auto& s) -> auto& { return chainOf(s).directSamples; });
}

OptionSpec seedsOption() {
  return choiceOption<SeedSampler>(
      "seeds",
      "the seed sampler, also of the pilot and the direct pass: path (the path tracer) or bdpt (bidirectional path "
      "tracing, whose light tracing finds caustics of small lights)",
      {{"path", SeedSampler::Path}, {"bdpt", SeedSampler::Bdpt}}, [](auto& s) -> auto& { return chainOf(s).seeds; });
}

OptionSpec bidirectionalMutationOption() {
  return realOption("bidir-mutation",
                    "probability that a chain step (MLT: one that is not a large step) proposes Veach's "
                    "bidirectional mutation, which deletes a subpath and regenerates it from both ends",
                    0, 1, [](auto& s) -> auto& { return chainOf(s).bidirectionalMutation; });
}

OptionSpec manifoldPerturbationOption() {
  return realOption("manifold-perturbation",
                    "probability that a chain step on a path with a specular chain after its first non-specular "
                    "vertex (a caustic seen through glass or in a mirror) proposes the manifold perturbation: the film "
                    "position moves in a disk of the perturbation radius and the specular chain is walked on its "
                    "manifold to the next fixed vertex (docs/manifold.md)",
                    0, 1, [](auto& s) -> auto& { return chainOf(s).manifoldPerturbation; });
}

OptionSpec chainMapsOption() {
  OptionSpec maps("chain-maps",
                  "also writes OUT-mutations.exr (the chains' proposals per pixel, by their film positions) and "
                  "OUT-acceptance.exr (their mean acceptance probability)",
                  OptionKind::Flag);
  maps.set = [](RenderSettings& s, const std::string&) { chainOf(s).chainMaps = true; };
  maps.get = [](const RenderSettings& s) { return chainOf(s).chainMaps ? "true" : "false"; };
  return maps;
}

std::vector<OptionSpec> depositOptions() {
  OptionSpec pmFilter("pm-filter",
                      "proposed-mutations noise filter (ERPT paper 4.4; biased) of radius 3 unless "
                      "--pm-filter-radius says otherwise; also writes OUT-raw.exr (unfiltered) and "
                      "OUT-proposals.exr (the tally)",
                      OptionKind::Flag);
  pmFilter.set = [](RenderSettings& s, const std::string&) {
    if (chainOf(s).pmFilterRadius < 0) chainOf(s).pmFilterRadius = 3;  // the paper's 7x7
  };
  pmFilter.get = [](const RenderSettings& s) { return chainOf(s).pmFilterRadius >= 0 ? "true" : "false"; };
  return {
      choiceOption<bool>("deposit", "paper (all of a step's energy at the chain's path) or expected ((1-q) at y, q at z)",
                         {{"paper", false}, {"expected", true}},
                         [](auto& s) -> auto& { return chainOf(s).expectedDeposit; }),
      pmFilter,
      integerOption("pm-filter-radius", "box radius of the proposed-mutations filter (3 = the paper's 7x7; -1: off)",
                    -1, 1000, [](auto& s) -> auto& { return chainOf(s).pmFilterRadius; }),
      integerOption("max-consecutive",
                    "consecutive-sample noise filter (ERPT paper 4.4; biased): a chain's deposits are dropped after "
                    "N in a row on one pixel (paper: 10-20; 0: off)",
                    0, 1 << 30, [](auto& s) -> auto& { return chainOf(s).maxConsecutive; }),
  };
}

void addOptions(std::vector<OptionSpec>& to, const std::vector<OptionSpec>& more) {
  to.insert(to.end(), more.begin(), more.end());
}

}  // namespace erpt
