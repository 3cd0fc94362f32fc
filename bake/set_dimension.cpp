#include "bake/set_dimension.h"

#include <Eigen/Geometry>
#include <Eigen/Eigenvalues>

#include <algorithm>

namespace tetprobe {

Eigen::Vector3d SetShape::reduce(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d local = axes.transpose() * (p - centre);
    switch (dimension) {
        case 0: return Eigen::Vector3d::Zero();
        case 1: return Eigen::Vector3d(local.x(), 0, 0);
        case 2: return Eigen::Vector3d(local.x(), local.y(), 0);
        default: return p - centre;
    }
}

uint32_t SetShape::dropped_axis() const {
    Eigen::Index dropped = 0;
    axes.col(2).cwiseAbs().maxCoeff(&dropped);
    return uint32_t(dropped);
}

uint32_t SetShape::line_axis() const {
    Eigen::Index along = 0;
    axes.col(0).cwiseAbs().maxCoeff(&along);
    return uint32_t(along);
}

Eigen::Vector2d SetShape::plane_coordinates(const Eigen::Vector3d& p) const {
    const uint32_t dropped = dropped_axis();
    const int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;  // the other two, in increasing order
    return Eigen::Vector2d(p[u], p[v]);
}

SetShape detect_set_dimension(const std::vector<Eigen::Vector3d>& points, double diagonal, double flat_tolerance) {
    SetShape shape;
    if (points.empty()) return shape;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& p : points) centre += p;
    centre /= double(points.size());
    shape.centre = centre;
    if (points.size() == 1 || !(diagonal > 0)) return shape;

    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const auto& p : points) {
        const Eigen::Vector3d d = p - centre;
        covariance += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    // Eigen sorts eigenvalues ascending; the frame wants the largest spread first.
    const Eigen::Matrix3d& v = solver.eigenvectors();
    shape.axes.col(0) = v.col(2).normalized();
    shape.axes.col(1) = v.col(1).normalized();
    shape.axes.col(2) = shape.axes.col(0).cross(shape.axes.col(1)).normalized();

    for (const auto& p : points) {
        const Eigen::Vector3d d = p - centre;
        const double along = d.dot(shape.axes.col(0));
        shape.line_distance = std::max(shape.line_distance, (d - along * shape.axes.col(0)).norm());
        shape.plane_distance = std::max(shape.plane_distance, std::fabs(d.dot(shape.axes.col(2))));
    }

    const double tolerance = std::max(flat_tolerance, kMinFlatTolerance) * diagonal;
    if (shape.line_distance <= tolerance) {
        shape.dimension = 1;
    } else if (shape.plane_distance <= tolerance) {
        shape.dimension = 2;
    } else {
        shape.dimension = 3;
    }
    return shape;
}

}  // namespace tetprobe
