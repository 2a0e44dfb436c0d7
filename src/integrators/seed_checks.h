// What the chain machines (ERPT, PMC-ER) ask of a seed before a chain may hold it, and how a
// seed no chain can move is deposited where it is (its own X_f, so no energy is lost).
#pragma once

#include "stages/chain_stages.h"
#include "models/film.h"
#include "core/seeds.h"

namespace erpt {

// Whether a seed is for the chains (not left to the direct-lighting pass).
bool seedForChains(const SeedStore& store, size_t i, bool excludeDirect);
// Why seed `i` cannot start a moving chain judging by its signature (too long, no mutation the
// strategy may pick applies; kInPlaceReasonCount: it can).
InPlaceReason seedSignatureReason(const StepConfig& ctx, const SeedStore& store, size_t i);
// Whether its f is zero or not finite in the measure of a mutation the strategy may pick (a
// chain standing there would accept anything). For seeds that pass seedSignatureReason.
bool seedHasZeroContribution(const StepConfig& ctx, const SeedStore& store, size_t i);
// Adds `energy` (luminance) in the seed's colour rgb(X_f) / lum(X_f) at its film position;
// returns the luminance added.
double depositSeedInPlace(const FilmDensity& density, const SeedStore& store, size_t seed, double energy, Film& film);

}  // namespace erpt
