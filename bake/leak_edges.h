// Leak control at build time: every edge of the store's cells whose two probes cannot see each other
// (a triangle of the scene crosses the segment between them) becomes a LeakEdge with the ramp over
// which a query's visibility passes from one probe to the other (store_format.h, core/leak_control.h).
#pragma once

#include "bake/progress.h"
#include "bake/scene.h"
#include "core/store_data.h"

#include <cstdint>

namespace tetprobe {

// Fraction of an edge by which the ramp reaches beyond the wall on either side: visibility changes
// over at least a tenth of the edge, so that it varies continuously (and not as a step) near a thin wall.
constexpr double kLeakRampMargin = 0.05;
// Fraction of an edge by which the parallel segments that tell a separating surface from a grazing one
// lie beside it (see add_leak_edges).
constexpr double kLeakSeparationOffset = 0.15;
// Pairs farther apart than this (world units, metres by the scene's convention) are not flagged: in the large
// cells of a sparse set the share of weight the visibility ramp reads (core/leak_control.h) no longer tells
// which side of the wall a query is on, and hiding a probe there cost up to 3 % on the real levels at 50-200
// probes and with all 1 m candidates of two levels (3 % and 6 %).
constexpr double kLeakLongestPair = 3.0;

// Casts a ray each way along every cell edge (Embree, local coordinates, on up to `threads` threads,
// 0 = all cores; the result does not depend on it) and fills data.leak_offsets and data.leak_edges;
// leaves both empty when no edge is blocked (the store then has no leak sections). An edge counts as
// blocked only when a surface separates its probes: the four segments parallel to it,
// kLeakSeparationOffset of its length away across it and above and below it, are blocked too (a segment
// grazing a step or a wall's edge joins probes that see the same light). Needs positions, origin and
// cells filled. Reports stage "leak control". Returns the number of blocked edges.
size_t add_leak_edges(const Scene& scene, StoreData& data, uint32_t threads = 0, const Progress& progress = {});

}  // namespace tetprobe
