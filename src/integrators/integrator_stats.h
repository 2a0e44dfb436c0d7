// The integrators' own statistics: how a time-budgeted render adds its passes' statistics
// (IntegratorModule::addStats) and their lines of the end-of-render summary (stderr;
// IntegratorModule::printSummary).
#pragma once

#include "erpt/erpt_settings.h"
#include "erpt/mlt_settings.h"
#include "erpt/pmc_settings.h"
#include "erpt/render.h"

namespace erpt {

void addChainStats(ChainStats& to, const ChainStats& from);  // chain_stats.cpp
void addPmcStats(PmcStats& to, const PmcStats& from);
void addMltStats(MltStats& to, const MltStats& from);

void printErptSummary(const RenderStats& stats);
void printPmcSummary(const RenderStats& stats);
void printMltSummary(const RenderStats& stats);
// The chain step's proposals and acceptance per mutation kind, and its rejections by reason,
// as one line each after `prefix:` (the chain integrators' summaries).
void printChainMoves(const char* prefix, const ChainStats& stats);
void printRejections(const char* prefix, const ChainStats& stats);
// "PREFIX: seeds deposited in place N: <reason> n, ..." (ChainStats::inPlace, the reasons that
// occurred), no line end.
void printInPlaceReasons(const char* prefix, const ChainStats& stats);
// "stage seconds:" and the seconds of each of the chain engine's stages, ending the line.
void printChainStageSeconds(const RenderStats& stats);

}  // namespace erpt
