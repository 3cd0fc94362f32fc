#include "bake/cell_matrices.h"

#include "core/error.h"

#include <Eigen/LU>
#include <Eigen/QR>

#include <cfloat>
#include <cmath>
#include <string>

namespace tetprobe {

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
            const double w = -r.dot(last);
            const double values[4] = {r.x(), r.y(), r.z(), w};
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
