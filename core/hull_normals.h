// The hull vertex normals along which the outer cells' rays leave the hull, computed from a finished
// store's hull facets in their stored order (its outer cells, or without extrapolation its inner
// cells' facets without neighbour), so that the same cells give the same normals however they were
// triangulated: the builder stores them; a loader that rebuilds cells could recompute them.
#pragma once

#include "core/store_data.h"

#include <Eigen/Core>

#include <vector>

namespace tetprobe {

// Per probe of data (cells finished: store_format.h's conventions): the unit hull vertex normal, zero
// for probes not on the hull. 3D: angle-weighted mean of the incident facets' flat-region normals,
// untangled where averaging mirrored a skinny facet; 2D: mean of the incident edges' in-plane
// outward normals; 1D: the line direction pointing away from the set. set_direction is the flat
// set's unit plane normal (2D) or the line's direction (1D), unused in 3D.
std::vector<Eigen::Vector3d> hull_vertex_normals(const StoreData& data, const Eigen::Vector3d& set_direction);

}  // namespace tetprobe
