// Barycentric matrices of the inner cells: the affine rows that turn a local position into the
// cell's barycentric coordinates, computed in double from the stored (local) positions.
#pragma once

#include "bake/set_dimension.h"
#include "bake/simplex_mesh.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace tetprobe {

// Puts each inner cell's most central probe (nearest the cell's centroid) in slot d, by an even
// permutation of its slots (vertices with their neighbours: orientation kept). The rows are relative
// to slot d, so their float error grows with a query's distance from it; in a needle (three close
// probes and a far one) the far probe as anchor would cost ~1e-4 exactly where the cell is thin.
void anchor_cells_at_central_probe(SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& positions);

// Row-major 3x4 per inner cell, relative to the slot-d probe P_d (store_format.h):
// b_k = M[k].xyz . (p - P_d) + M[k].w for k < d (w is zero), rows >= d zero. 3D inverts
// [P0-P3, P1-P3, P2-P3]; 2D inverts [P0-P2, P1-P2, n] and keeps rows 0 and 1 (so a query's offset
// along the plane normal n is ignored: the triangulation is extruded); 1D measures along the line
// direction u, b0 = (p-P1).u / (P0-P1).u, so that neighbouring segments split space by the same
// planes even when the probes are only nearly collinear. Inversion is Eigen's partial-pivot LU; a
// cell too flat for it (relative thickness below 1e-12, possible only inside the hull where cospherical
// probes meet) gets the pseudo-inverse instead, so its rows stay finite; *degenerate counts those.
std::vector<std::array<double, 12>> inner_cell_matrices(const SimplexMesh& mesh,
                                                         const std::vector<Eigen::Vector3d>& positions,
                                                         const SetShape& shape, size_t* degenerate = nullptr);

}  // namespace tetprobe
