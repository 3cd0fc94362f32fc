// The boundary of the inner cells (the convex hull of the probes, in the set's own dimension) and the
// hull vertex normals along which the outer cells' rays leave it.
#pragma once

#include "bake/set_dimension.h"
#include "bake/simplex_mesh.h"

#include <Eigen/Core>

#include <vector>

namespace tetprobe {

struct HullFacet {
    // d probes (slots 0..d-1, rest kNone32), wound outward (exact-predicate conventions of
    // store_format.h, for positively oriented inner cells): 3D orient3d(P0, P1, P2, x) > 0 for x beyond
    // the facet; 2D orient2d(P0, P1, x) > 0 beyond, in the plane coordinates; 1D the end probe.
    CellSlots probes = kNoSlots;
    uint32_t inner_cell = 0;  // the inner cell the facet bounds
    uint32_t inner_slot = 0;  // that cell's slot opposite the facet
};

struct Hull {
    std::vector<HullFacet> facets;
    // Per probe: unit hull vertex normal, zero for probes not on the hull. 3D: angle-weighted mean of
    // the incident facet normals; 2D: mean of the incident edges' in-plane outward normals; 1D: the
    // line direction pointing away from the set.
    std::vector<Eigen::Vector3d> vertex_normals;
};

// Collects every facet of mesh without a neighbour (dimension 1..3). positions are the probes'
// local positions; shape gives the plane normal (2D) or line direction (1D).
Hull find_hull(const SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& positions, const SetShape& shape);

}  // namespace tetprobe
