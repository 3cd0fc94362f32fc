// The store benchmark's probe-volume row: a 16^3 volume (Unity's Light Probe Proxy Volume) around moving objects.
#pragma once

#include "query_sets.h"

#include "capi/tetprobe.h"

namespace bench {

// Points a side of the timed volume, and its cell size (a 4-unit object sampled 16 times a side).
constexpr uint32_t kVolumeSide = 16;
constexpr float kVolumeCell = 0.25f;

// ns per grid point of tp_store_sample_volume (plain L2, packed) on 16^3 volumes centred on the first objects of
// paths (pulled in to stay within the objects' range), frame after frame, each volume keeping its own hint between
// frames as a renderer does.
double time_volume_points(const tp_store* store, const ObjectPaths& paths, float* sink);

// Cells the walk steps through per grid point on the same volumes (tp_store_locate's steps along the volume's walk,
// one hint carried): why a volume point costs more than a coherent object's query, whose hint is 2 cm behind.
double volume_steps_per_point(const tp_store* store, const ObjectPaths& paths);

}  // namespace bench
