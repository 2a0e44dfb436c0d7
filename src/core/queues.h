// SoA queue types built from queue_fields.h: the path tracer's paths, vertices and seeds, BDPT's subpaths.
#pragma once

#include "core/queue_fields.h"
#include "core/soa.h"

namespace erpt {

ERPT_SOA_STRUCT(DirectSampleQueue, ERPT_DIRECT_SAMPLE_FIELDS)
ERPT_SOA_STRUCT(PathQueue, ERPT_PATH_FIELDS)
ERPT_SOA_STRUCT(PathSlotQueue, ERPT_PATH_SLOT_FIELDS)
ERPT_SOA_STRUCT(VertexQueue, ERPT_VERTEX_FIELDS)
// A path vertex as a plain value (ERPT's chains): loadPathVertex(queue, i), storePathVertex().
ERPT_SOA_VIEW(PathVertex, VertexQueue, ERPT_PATH_VERTEX_FIELDS)
ERPT_SOA_STRUCT(SeedQueue, ERPT_SEED_FIELDS)
ERPT_SOA_STRUCT(BdptVertexQueue, ERPT_BDPT_VERTEX_FIELDS)
ERPT_SOA_STRUCT(BdptWalkQueue, ERPT_BDPT_WALK_FIELDS)
ERPT_SOA_STRUCT(BdptConnectionQueue, ERPT_BDPT_CONNECTION_FIELDS)

// kTailVertex: the last vertex a chain holds of a path longer than kMaxChainVertices; it keeps
// its position, and its shading normal field holds the fixed factor of itself and everything
// after it (erpt_path.h, foldPathTail).
enum VertexKind : uint8_t { kEyeVertex = 0, kNonSpecularVertex, kSpecularVertex, kLightVertex, kEnvironmentVertex, kTailVertex };

}  // namespace erpt
