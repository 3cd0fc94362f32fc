// Coherent queries timed the same way by the store and locate benchmarks: objects moving along paths,
// each keeping its cell hint between frames, next to the blend-only floor on the same probes and weights.
#pragma once

#include "blob_sh.h"
#include "query_sets.h"

#include "capi/tetprobe.h"

#include <cstdint>
#include <vector>

namespace bench {

// Each object's cell at frame 0 (untimed): the first hint of the timed frames.
std::vector<int32_t> first_hints(const tp_store* store, const ObjectPaths& paths);

// ns per tp_store_interpolate, object by object, each carrying its own hint from the last frame.
double time_coherent_single(const tp_store* store, const ObjectPaths& paths, float* sink);

// ns per blend of the floor: the same 4 x 27 half -> float blend (core/half.h) of the same probes with the
// same weights as the coherent queries (found first, untimed, by tp_store_locate), no search.
double time_blend_floor(const tp_store* store, const BlobSh& blob, const ObjectPaths& paths, float* sink);
// The same with core's blend kernel of the blob's SH encoding (sh_blend.h), reading its records: what a
// query of that store pays for its blend and decode.
double time_blend_floor_records(const tp_store* store, const BlobSh& blob, const ObjectPaths& paths, float* sink);

}  // namespace bench
