// Dimension of a probe set: point, line, flat or general. A set thinner than the flat tolerance is
// triangulated in its best-fit plane (or along its best-fit line) instead of being handed to TetGen,
// which crashes on coplanar and collinear input and builds zero-volume cells from nearly coplanar one.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace tetprobe {

struct SetShape {
    uint32_t dimension = 0;   // 0 point, 1 line, 2 flat, 3 general
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    // Columns: principal directions, largest spread first. Line: column 0 is the line. Flat: columns
    // 0 and 1 span the plane, column 2 is its unit normal.
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    double line_distance = 0;    // largest distance of a point from the best-fit line
    double plane_distance = 0;   // ... from the best-fit plane

    // Coordinates of p in the set's own frame reduced to its dimension (unused components zero).
    Eigen::Vector3d reduce(const Eigen::Vector3d& p) const;

    // Flat set: the coordinate (0 x, 1 y, 2 z) along which the plane normal is largest (StoreData::axis).
    uint32_t dropped_axis() const;
    // Line: the coordinate along which the line direction is largest (StoreData::axis).
    uint32_t line_axis() const;

    // Flat set: p's two coordinates other than dropped_axis(), in increasing axis order (the run
    // time's (u, v)). Unlike reduce(), no arithmetic, so the triangulation sees exactly the stored
    // floats and probes exactly collinear in space stay exactly collinear (a rotation rounds them
    // into slivers). An affine map of the plane, exactly a similarity for a plane at a constant
    // coordinate.
    Eigen::Vector2d plane_coordinates(const Eigen::Vector3d& p) const;
};

// A flat (line) set further than this fraction of the diagonal from its fitted plane (line) is
// projected onto it before triangulating; a set closer to it than that is already on it up to the
// fit's own double rounding and is stored exactly as given.
constexpr double kOnSetTolerance = 1e-9;

// Smallest thickness, relative to the diagonal, still treated as 3D (or 2D) whatever the caller's
// tolerance: well above float rounding of the stored coordinates (6e-8 of the diagonal), so that no
// rounding makes a set TetGen sees exactly coplanar (or a plane set exactly collinear).
constexpr double kMinFlatTolerance = 1e-6;

// Fits line and plane (SelfAdjointEigenSolver on the centred covariance, in double) and compares the
// largest distances with max(flat_tolerance, kMinFlatTolerance) * diagonal. One point, or a zero
// diagonal, is dimension 0.
SetShape detect_set_dimension(const std::vector<Eigen::Vector3d>& points, double diagonal, double flat_tolerance);

}  // namespace tetprobe
