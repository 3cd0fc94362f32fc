// The canonical form of inner cells: one slot order per oriented cell, so that two triangulations
// with the same cells (TetGen's at bake time, core's when a store is rebuilt at load) store them
// identically, whatever order either listed their vertices in. Slots 0..d hold the cell's probes in
// increasing index, then slots 0 and 1 are swapped when that order is negatively oriented (the
// store's cells are positive: store_format.h); neighbours follow their slots.
#pragma once

#include "core/simplex_mesh.h"

#include <cstddef>
#include <cstdint>

namespace tetprobe {

// The exact orientation sign of a cell in the stored coordinates: 3D orient3d of slots 0..3, 2D
// orient2d of slots 0..2 in the two coordinates other than axis, 1D the sign of slot 1 minus slot 0
// along axis. positions: 3 floats per probe.
int cell_orientation(const CellSlots& vertices, uint32_t dimension, uint32_t axis, const float* positions);

// Puts one cell in canonical form, given the orientation sign of its current slot order (a flat cell,
// sign 0, keeps the increasing order).
void canonicalise_cell(CellSlots& vertices, CellSlots& neighbours, uint32_t dimension, int orientation);

// Every cell of mesh in canonical form, each orientation decided exactly on positions; returns the
// number of flat cells (zero orientation), which a Delaunay triangulation never has.
size_t canonicalise_cells(SimplexMesh& mesh, const float* positions, uint32_t axis);

}  // namespace tetprobe
