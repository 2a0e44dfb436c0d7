// What the chain machines (ERPT, PMC-ER) ask of a seed before a chain may hold it, and how a
// seed no chain can move is deposited where it is (its own X_f, so no energy is lost).
#pragma once

#include "stages/chain_stages.h"
#include "models/film.h"
#include "core/seeds.h"

namespace erpt {

// Whether a seed is for the chains (not left to the direct-lighting pass).
bool seedForChains(const SeedStore& store, size_t i, bool excludeDirect);
// A seed longer than a chain holds becomes its folded form in place (foldPathTail: vertex
// keep - 1 a tail vertex carrying the factor of the rest, keep = kMaxChainVertices for the
// chains); its contribution and film position do not change. Call before the checks below.
void foldSeedTail(const StepConfig& ctx, SeedStore& store, size_t i, int keep = kMaxChainVertices);
// Why seed `i` (folded) cannot start a moving chain judging by its signature (no mutation the
// strategy may pick applies, a directional light; kInPlaceReasonCount: it can).
InPlaceReason seedSignatureReason(const StepConfig& ctx, const SeedStore& store, size_t i);
// Whether its f is zero or not finite in the measure of a mutation the strategy may pick (a
// chain standing there would accept anything). For seeds that pass seedSignatureReason.
bool seedHasZeroContribution(const StepConfig& ctx, const SeedStore& store, size_t i);
// Adds `energy` (luminance) in the seed's colour rgb(X_f) / lum(X_f) at its film position;
// returns the luminance added.
double depositSeedInPlace(const FilmDensity& density, const SeedStore& store, size_t seed, double energy, Film& film);

}  // namespace erpt
