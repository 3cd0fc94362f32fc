#include "bake/cell_matrices.h"

#include "core/error.h"

#include <Eigen/LU>
#include <Eigen/QR>

#include <cfloat>
#include <cmath>
#include <string>
#include <utility>

namespace tetprobe {

void anchor_cells_at_central_probe(SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& positions) {
    const uint32_t d = mesh.dimension;
    if (d < 2) return;  // a segment's two probes are equally central
    for (size_t c = 0; c < mesh.cell_count(); ++c) {
        CellSlots& v = mesh.vertices[c];
        CellSlots& n = mesh.neighbours[c];
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (uint32_t k = 0; k <= d; ++k) centroid += positions[v[k]];
        centroid /= double(d + 1);
        uint32_t central = d;
        for (uint32_t k = 0; k < d; ++k) {
            if ((positions[v[k]] - centroid).squaredNorm() < (positions[v[central]] - centroid).squaredNorm()) central = k;
        }
        if (central == d) continue;
        if (d == 2) {
            // A rotation of the three slots (even) that ends with the central probe in slot 2.
            const uint32_t shift = central + 1;
            const CellSlots vv = v, nn = n;
            for (uint32_t k = 0; k < 3; ++k) {
                v[k] = vv[(k + shift) % 3];
                n[k] = nn[(k + shift) % 3];
            }
        } else {
            // Two transpositions (even): central <-> 3, and the other two slots with each other.
            uint32_t others[2], count = 0;
            for (uint32_t k = 0; k < 3; ++k) {
                if (k != central) others[count++] = k;
            }
            std::swap(v[central], v[3]);
            std::swap(n[central], n[3]);
            std::swap(v[others[0]], v[others[1]]);
            std::swap(n[others[0]], n[others[1]]);
        }
    }
}

std::vector<std::array<double, 12>> inner_cell_matrices(const SimplexMesh& mesh,
                                                         const std::vector<Eigen::Vector3d>& positions,
                                                         const SetShape& shape, size_t* degenerate) {
    const uint32_t d = mesh.dimension;
    std::vector<std::array<double, 12>> matrices(mesh.cell_count());
    for (size_t c = 0; c < mesh.cell_count(); ++c) {
        std::array<double, 12>& out = matrices[c];
        out.fill(0.0);
        if (d == 0) continue;
        const CellSlots& v = mesh.vertices[c];
        const Eigen::Vector3d& last = positions[v[d]];
        Eigen::Matrix3d rows = Eigen::Matrix3d::Zero();
        if (d == 1) {
            const Eigen::Vector3d& u = shape.axes.col(0);
            rows.row(0) = u.transpose() / (positions[v[0]] - last).dot(u);
        } else {
            Eigen::Matrix3d edges;
            edges.col(0) = positions[v[0]] - last;
            edges.col(1) = positions[v[1]] - last;
            edges.col(2) = d == 3 ? Eigen::Vector3d(positions[v[2]] - last) : Eigen::Vector3d(shape.axes.col(2));
            const double scale = edges.col(0).norm() * edges.col(1).norm() * edges.col(2).norm();
            const Eigen::PartialPivLU<Eigen::Matrix3d> lu(edges);
            if (std::fabs(lu.determinant()) > 1e-12 * scale) {
                rows = lu.inverse();
            } else {
                Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix3d> cod(edges);
                cod.setThreshold(1e-9);
                rows = cod.pseudoInverse();
                if (degenerate) ++*degenerate;
            }
        }
        for (uint32_t k = 0; k < d; ++k) {
            const Eigen::Vector3d r = rows.row(k).transpose();
            // Relative to the slot-d probe (store_format.h), where every b_k with k < d is zero.
            const double values[4] = {r.x(), r.y(), r.z(), 0.0};
            for (int j = 0; j < 4; ++j) {
                if (!std::isfinite(values[j]) || std::fabs(values[j]) > double(FLT_MAX)) {
                    throw Error(TP_ERROR_INTERNAL, "inner cell " + std::to_string(c) + " is degenerate");
                }
                out[k * 4 + size_t(j)] = values[j];
            }
        }
    }
    return matrices;
}

}  // namespace tetprobe
