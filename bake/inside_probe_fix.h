// Fixing the probes of a user's set that are inside geometry (bake/inside_test.h): drop them, or
// push each out to a nearby free point at least `margin` from every surface. Never silent: a probe
// that cannot be pushed out is an error naming it.
#pragma once

#include "bake/scene.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

enum class InsideFix : uint32_t { drop = 0, push = 1 };

// Returns the fixed positions (3 floats each): for drop, the probes outside in their order; for
// push, every probe, the inside ones moved. A pushed probe goes to the nearest of these points that
// is outside and clear by margin: the point at margin in front of the nearest surface, and the points
// at margin in front of where each of the inside test's rays leaves the solid. Throws
// Error(Status::scene) when the inside test cannot decide or a probe has no such point, and
// Error(Status::invalid_argument) for a negative or non-finite margin.
std::vector<float> fix_inside_probes(const Scene& scene, const std::vector<float>& positions, InsideFix fix,
                                     double margin, uint32_t threads);

}  // namespace tetprobe
