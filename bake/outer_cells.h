// Outer cells: one open cell per hull facet, swept along the rays from its probes in the direction
// of their hull vertex normals, so that queries outside the hull extrapolate continuously.
#pragma once

#include "bake/hull.h"
#include "bake/simplex_mesh.h"

#include <vector>

namespace tetprobe {

struct OuterCells {
    std::vector<CellSlots> vertices;    // probes in slots 0..d-1 (the facet's winding), kOuter32 in slot d
    std::vector<CellSlots> neighbours;  // global cell ids: slot d the inner cell, slots < d outer cells
};

// Builds the outer cells of hull over `inner` (whose cells are numbered 0..inner.cell_count()-1; outer
// cell i becomes global cell inner.cell_count() + i) and links each facet's inner cell to its outer
// cell. The run time computes an outer cell's polynomial from its probes' positions and normals, so
// only the links are built here. In 1D an outer cell has no outer neighbour (neighbour 0 is kNone32).
OuterCells build_outer_cells(SimplexMesh& inner, const Hull& hull);

}  // namespace tetprobe
