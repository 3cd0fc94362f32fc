// The hull of the inner cells (the convex hull of the probes, in the set's own dimension) and the
// outer cells over it: one open cell per hull facet, swept along its probes' hull normals, so that
// queries outside the hull extrapolate continuously. Only the links are built here: the run time
// computes an outer cell's shape from its probes' positions and normals, so the cells and their
// neighbours do not depend on the normals.
#pragma once

#include "core/simplex_mesh.h"

#include <cstdint>
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

// The facet of a positively oriented cell (vertex slots 0..d) opposite `slot`, wound outward: by slot
// order alone, no arithmetic, so that a flat cell's facet is wound like its neighbours'.
CellSlots hull_facet_probes(const uint32_t* cell_vertices, uint32_t slot, uint32_t dimension);

// Every facet of mesh without a neighbour (dimension 1..3), in cell and slot order.
std::vector<HullFacet> find_hull_facets(const SimplexMesh& mesh);

struct OuterCells {
    std::vector<CellSlots> vertices;    // probes in slots 0..d-1 (the facet's winding), kOuter32 in slot d
    std::vector<CellSlots> neighbours;  // global cell ids: slot d the inner cell, slots < d outer cells
};

// The outer cells of facets over `inner` (whose cells are numbered 0..inner.cell_count()-1; outer
// cell i becomes global cell inner.cell_count() + i), linking each facet's inner cell to its outer
// cell. Outer cells are neighbours where their facets share d-1 probes; in 1D an outer cell has no
// outer neighbour (neighbour 0 is kNone32). Throws Error(Status::internal) if the hull is not closed.
OuterCells build_outer_cells(SimplexMesh& inner, const std::vector<HullFacet>& facets);

}  // namespace tetprobe
