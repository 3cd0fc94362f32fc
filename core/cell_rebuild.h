// A store's cells from its stored probes alone: what a layout that keeps no cells (issue 17) rebuilds
// at load, and what the builder stores for every layout. Both run this file's steps, in this order:
//   1. inner_cells: the probes' triangulation in their dimension (one cell; segments along the line;
//      exact Delaunay triangles or tetrahedra, delaunay2d.h / delaunay3d.h), canonical form;
//   2. store_cells: the inner cells and, unless kFlagNoExtrapolation, the outer cells over their hull;
//   3. order_cells_for_locality (cell_order.h): the locality order, cell 0 near the centre;
//   4. build_start_grid (start_grid.h).
// The builder takes step 1 from TetGen where TetGen agrees (bake/store_builder.cpp); every later step
// depends only on which cells there are, never on the order they were listed in, so a rebuild gives
// the stored cells index for index.
#pragma once

#include "core/delaunay3d.h"
#include "core/simplex_mesh.h"
#include "core/store_data.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

// Step 1 for probe_count probes (3 finite floats each, as a validated store holds them) of the given
// dimension (0..3) and axis (store_format.h). Throws Error(Status::degenerate) when the probes do not
// span that dimension, and Error(Status::invalid_argument) for two probes a cell could not tell apart
// or an axis that does not fit the dimension.
// max_cells bounds a tetrahedralization's live cells (delaunay3d.h); a line's or flat set's cells are
// linear in the probes.
SimplexMesh inner_cells(const float* positions, uint32_t probe_count, uint32_t dimension, uint32_t axis,
                        uint64_t max_cells = kUnlimitedCells);

// Step 2: fills data.inner_cell_count, cell_vertices and cell_neighbours from mesh (of data.dimension,
// numbering data's probes), with outer cells unless data.flags has kFlagNoExtrapolation.
void store_cells(SimplexMesh mesh, StoreData& data);

// Steps 2 and 3 at once: the same cells in the same order as store_cells then order_cells_for_locality
// (data's positions and bounds set), written once into their ordered places instead of copied first.
void store_cells_in_locality_order(SimplexMesh mesh, StoreData& data);

struct RebuiltCells {
    uint32_t inner_cell_count = 0;
    std::vector<uint32_t> cell_vertices;    // 4 per cell (kNone32, kOuter32 as in StoreData)
    std::vector<uint32_t> cell_neighbours;  // 4 per cell
    uint32_t grid[3] = {1, 1, 1};
    std::vector<uint32_t> grid_cells;       // grid[0] * grid[1] * grid[2]
};

// Steps 1 to 4 for a loaded store: positions (3 floats per probe, local), the header's dimension,
// axis, bounds and start grid dimensions, and whether it extrapolates (no kFlagNoExtrapolation).
// Gives exactly the cells, neighbours and start grid the builder stored for these probes in the
// layouts that keep them (tests/unit/test_cell_rebuild.cpp proves it on every hard-case family), on
// any platform: every step is exact predicates, integers and plain IEEE arithmetic. Allocates (like
// any Delaunay, adversarial sets such as probes on two skew lines make quadratically many cells: a
// loader of untrusted blobs passes max_cells); throws Error as inner_cells and fill_start_grid do
// and for bounds that are not finite and ordered, which a loader reports as an invalid blob.
RebuiltCells rebuild_cells(const float* positions, uint32_t probe_count, uint32_t dimension, uint32_t axis,
                           bool extrapolate, const float bounds_min[3], const float bounds_max[3],
                           const uint32_t grid[3], uint64_t max_cells = kUnlimitedCells);

}  // namespace tetprobe
