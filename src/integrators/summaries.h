// The integrators' own lines of the end-of-render summary (stderr), which their modules print
// (IntegratorModule::printSummary).
#pragma once

#include "erpt/render.h"

namespace erpt {

void printErptSummary(const RenderStats& stats);
void printPmcSummary(const RenderStats& stats);
void printMltSummary(const RenderStats& stats);
// The chain step's proposals and acceptance per mutation kind, and its rejections by reason,
// as one line each after `prefix:` (ERPT's and MLT's summaries).
void printChainMoves(const char* prefix, const ErptStats& stats);
void printRejections(const char* prefix, const ErptStats& stats);

}  // namespace erpt
