// Leak control at build time: every edge of the store's cells whose two probes cannot see each other
// (a triangle of the scene crosses the segment between them) becomes a LeakEdge holding, for each of
// its probes, the plane of the first surface the segment meets from it (store_format.h,
// core/leak_plane.h), which the run time tests the query's side against (core/leak_control.h).
#pragma once

#include "bake/progress.h"
#include "bake/scene.h"
#include "core/store_data.h"

#include <cstdint>

namespace tetprobe {

// Fraction of an edge by which the parallel segments that tell a separating surface from a grazing one
// lie beside it (see add_leak_edges).
constexpr double kLeakSeparationOffset = 0.15;
// Pairs farther apart than this (world units, metres by the scene's convention) are not flagged. The side test
// decides which side of a wall a query is on exactly, yet without this limit hiding probes in the large cells
// of sparse sets and in the long cells among all 1 m candidates cost up to 7.8 % on the real levels (wrackdm17
// at 400 probes; 4.5 % at 50 on oa_bases3, 6.7 % with all of oa_bases3's candidates): there a probe behind the
// wall is often a better estimate than the far ones left on the query's side. A stopgap: the scale it stands
// for (how far a probe's light stays representative) is not in the store.
constexpr double kLeakLongestPair = 3.0;

// Casts a ray each way along every cell edge (Embree, local coordinates, on up to `threads` threads,
// 0 = all cores; the result does not depend on it) and fills data.leak_offsets and data.leak_edges;
// leaves both empty when no edge is blocked (the store then has no leak sections). An edge counts as
// blocked only when a surface separates its probes: the four segments parallel to it,
// kLeakSeparationOffset of its length away across it and above and below it, are blocked too (a segment
// grazing a step or a wall's edge joins probes that see the same light). Each side's plane is the first
// surface's (its triangle's normal, turned to face the probe) through the point where the segment meets
// it; a surface found from one end only is a wall of no thickness, the same plane from both. A pair for
// which no float plane separates the probes (a few float steps apart) is left out. Needs positions, origin and
// cells filled; pairs farther apart than kLeakLongestPair are not tested. Reports stage "leak control". Returns the number of blocked edges.
size_t add_leak_edges(const Scene& scene, StoreData& data, uint32_t threads = 0, const Progress& progress = {});

}  // namespace tetprobe
