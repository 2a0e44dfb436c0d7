// The parts ERPT, PMC-ER and MLT share around their chains: the direct-lighting pass that
// takes the one-bounce paths off the chains (--direct-samples), the image they show (the
// chains' image plus the direct pass, then the proposed-mutations filter), and the rules
// between the options they share.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "erpt/erpt_settings.h"
#include "erpt/render.h"
#include "stages/chain_stages.h"

namespace erpt {

// Throws UsageError for shared options that do not fit together (--direct-samples 0).
void validateChainOptions(const ChainOptions& options);
// Time-budgeted passes of ERPT, PMC-ER and MLT: the direct pass's samples per pixel follow the
// pass's share of the configured spp.
void scaleDirectSamples(const RenderSettings& whole, RenderSettings& pass);
// The direct-lighting pass of ERPT, PMC-ER and MLT (--direct-samples N > 0; else an empty image),
// with its own random stream; adds its rays and stage times to `stats`.
RgbImage renderDirectPass(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
// The image ERPT and PMC-ER show: `chains` (the chains' image, resolved) plus `direct` (when
// not empty), then the proposed-mutations filter when `tally` (complete proposals per pixel)
// is given. With `extras`, the filter's extra images (proposals, raw, chains) go there.
RgbImage redistributionImage(const RenderSettings& settings, RgbImage chains, const RgbImage& direct,
                             const std::vector<uint32_t>* tally,
                             std::vector<std::pair<std::string, RgbImage>>* extras);

// --chain-maps: appends "mutations" (proposals per pixel) and "acceptance" (their mean
// acceptance probability; 0 where none went) to `extras`, when the tallies hold them.
void addChainMaps(const ProposalTallies& tallies, int width, int height,
                  std::vector<std::pair<std::string, RgbImage>>& extras);

}  // namespace erpt
