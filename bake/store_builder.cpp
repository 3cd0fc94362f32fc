#include "bake/store_builder.h"

#include "bake/cell_matrices.h"
#include "bake/cell_order.h"
#include "bake/delaunay.h"
#include "bake/flat_delaunay.h"
#include "bake/hull.h"
#include "bake/hull_slivers.h"
#include "bake/input_screening.h"
#include "bake/line_segments.h"
#include "bake/outer_cells.h"
#include "bake/probe_merge.h"
#include "bake/set_dimension.h"
#include "bake/start_grid.h"
#include "core/error.h"
#include "core/store_format.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace tetprobe {

namespace {

void report_progress(const BuildSettings& settings, float fraction, const char* stage) {
    if (settings.progress && settings.progress(settings.progress_user, fraction, stage) != 0) {
        throw Error(TP_ERROR_CANCELLED, "build cancelled");
    }
}

void check_settings(const BuildSettings& settings) {
    if (settings.flags & ~uint32_t(TP_BUILD_NO_EXTRAPOLATION | TP_BUILD_INDEX32)) {
        throw Error(TP_ERROR_INVALID_ARGUMENT, "unknown build flags " + std::to_string(settings.flags));
    }
    if (!(settings.merge_tolerance >= 0 && settings.merge_tolerance <= 1)) {
        throw Error(TP_ERROR_INVALID_ARGUMENT, "merge_tolerance must be in [0, 1]");
    }
    if (!(settings.flat_tolerance >= 0 && settings.flat_tolerance <= 0.1)) {
        throw Error(TP_ERROR_INVALID_ARGUMENT, "flat_tolerance must be in [0, 0.1]");
    }
}

// The probes that survive merging: kept[j] is the input index of stored probe j, group[i] the stored
// probe of input probe i.
struct ProbeGroups {
    std::vector<uint32_t> kept;
    std::vector<uint32_t> group;

    void apply(const ProbeMerge& merge) {
        std::vector<uint32_t> next(merge.survivors.size());
        for (size_t j = 0; j < next.size(); ++j) next[j] = kept[merge.survivors[j]];
        for (auto& g : group) g = merge.group_of[g];
        kept = std::move(next);
    }
};

std::vector<Eigen::Vector3d> gather(const std::vector<Eigen::Vector3d>& all, const std::vector<uint32_t>& which) {
    std::vector<Eigen::Vector3d> out(which.size());
    for (size_t j = 0; j < which.size(); ++j) out[j] = all[which[j]];
    return out;
}

// Merges in the set's own reduced coordinates (a flat set merges probes that differ only across its
// plane, since the triangulation cannot tell them apart) until merging no longer lowers the dimension.
SetShape merge_and_detect(const std::vector<Eigen::Vector3d>& local, double diagonal, const BuildSettings& settings,
                          ProbeGroups& groups) {
    SetShape shape;
    for (int round = 0; round < 8; ++round) {
        const std::vector<Eigen::Vector3d> points = gather(local, groups.kept);
        shape = detect_set_dimension(points, diagonal, settings.flat_tolerance);
        std::vector<Eigen::Vector3d> reduced(points.size());
        for (size_t j = 0; j < points.size(); ++j) reduced[j] = shape.reduce(points[j]);
        const ProbeMerge merge = merge_close_points(reduced, settings.merge_tolerance * diagonal);
        if (merge.merged_count() == 0) return shape;
        groups.apply(merge);
    }
    return detect_set_dimension(gather(local, groups.kept), diagonal, settings.flat_tolerance);
}

// Triangulation of the stored probes in their own dimension.
SimplexMesh triangulate(const std::vector<Eigen::Vector3d>& points, const SetShape& shape) {
    switch (shape.dimension) {
        case 0: {
            SimplexMesh mesh;
            mesh.dimension = 0;
            mesh.add_cell({0, kNone32, kNone32, kNone32}, kNoSlots);
            return mesh;
        }
        case 1: {
            std::vector<double> along(points.size());
            for (size_t j = 0; j < points.size(); ++j) along[j] = shape.reduce(points[j]).x();
            return line_segments(along);
        }
        case 2: {
            std::vector<Eigen::Vector2d> uv(points.size());
            for (size_t j = 0; j < points.size(); ++j) uv[j] = shape.plane_coordinates(points[j]);
            return delaunay_triangulate_plane(uv);
        }
        default: return delaunay_tetrahedralize(points);
    }
}

// TetGen may drop a point it finds coincident with another; such a probe joins its nearest used
// neighbour, so that every stored probe belongs to a cell.
void merge_unused_probes(SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& points, ProbeGroups& groups) {
    std::vector<char> used(points.size(), 0);
    for (const auto& cell : mesh.vertices) {
        for (uint32_t v : cell) {
            if (v < points.size()) used[v] = 1;
        }
    }
    if (std::all_of(used.begin(), used.end(), [](char u) { return u != 0; })) return;
    std::vector<uint32_t> compact(points.size(), kNone32);
    uint32_t next = 0;
    for (size_t j = 0; j < points.size(); ++j) {
        if (used[j]) compact[j] = next++;
    }
    for (size_t j = 0; j < points.size(); ++j) {
        if (used[j]) continue;
        double best = -1;
        for (size_t i = 0; i < points.size(); ++i) {
            if (!used[i]) continue;
            const double d2 = (points[i] - points[j]).squaredNorm();
            if (best < 0 || d2 < best) {
                best = d2;
                compact[j] = compact[i];
            }
        }
    }
    ProbeMerge merge;
    merge.group_of = compact;
    for (size_t j = 0; j < points.size(); ++j) {
        if (used[j]) merge.survivors.push_back(uint32_t(j));
    }
    groups.apply(merge);
    for (auto& cell : mesh.vertices) {
        for (auto& v : cell) {
            if (v < points.size()) v = compact[v];
        }
    }
}

// Gives every inner cell positive orientation (3D volume, 2D area about the plane normal, 1D extent
// along the line), swapping slots 0 and 1 with their neighbours where needed.
void orient_cells(SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& p, const SetShape& shape) {
    for (size_t c = 0; c < mesh.cell_count(); ++c) {
        const CellSlots& v = mesh.vertices[c];
        double orientation = 1;
        if (mesh.dimension == 3) {
            orientation = (p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]).dot(p[v[3]] - p[v[0]]);
        } else if (mesh.dimension == 2) {
            orientation = (p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]).dot(shape.axes.col(2));
        } else if (mesh.dimension == 1) {
            orientation = (p[v[1]] - p[v[0]]).dot(shape.axes.col(0));
        }
        if (orientation < 0) {
            std::swap(mesh.vertices[c][0], mesh.vertices[c][1]);
            std::swap(mesh.neighbours[c][0], mesh.neighbours[c][1]);
        }
    }
}

}  // namespace

StoreData build_store_data(const float* positions, size_t position_stride, const float* sh, size_t sh_stride,
                           size_t count, const BuildSettings& settings) {
    check_settings(settings);
    report_progress(settings, 0.0f, "screening");
    const ScreenedProbes input = screen_probe_input(positions, position_stride, sh, sh_stride, count);

    // Local frame: centred on the probes' centroid, rounded to float exactly as stored, so that every
    // later stage computes (in double) with the coordinates a query will see.
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    for (const auto& p : input.positions) origin += p;
    origin /= double(count);
    std::vector<Eigen::Vector3d> local(count);  // float-exact; flat and line sets later projected
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
    for (size_t i = 0; i < count; ++i) {
        for (int a = 0; a < 3; ++a) local[i][a] = double(float(input.positions[i][a] - origin[a]));
        lo = lo.cwiseMin(local[i]);
        hi = hi.cwiseMax(local[i]);
    }
    const double diagonal = (hi - lo).norm();

    report_progress(settings, 0.1f, "merging");
    ProbeGroups groups;
    groups.kept.resize(count);
    std::iota(groups.kept.begin(), groups.kept.end(), 0u);
    groups.group = groups.kept;
    SetShape shape = merge_and_detect(local, diagonal, settings, groups);

    // A flat (line) set is stored on its fitted plane (line): the queries' extrusion across the plane
    // is then the orthogonal projection every later stage and the run time assume. A set already on
    // it keeps its coordinates, so that probes exactly collinear stay so (and exact at queries).
    const double off_set = shape.dimension == 1 ? shape.line_distance : shape.plane_distance;
    if ((shape.dimension == 1 || shape.dimension == 2) && off_set > kOnSetTolerance * diagonal) {
        for (uint32_t i : groups.kept) {
            const Eigen::Vector3d on_set = shape.centre + shape.axes * shape.reduce(local[i]);
            for (int a = 0; a < 3; ++a) local[i][a] = double(float(on_set[a]));
        }
    }

    report_progress(settings, 0.2f, "triangulating");
    std::vector<Eigen::Vector3d> points = gather(local, groups.kept);
    SimplexMesh mesh = triangulate(points, shape);
    const size_t before = points.size();
    merge_unused_probes(mesh, points, groups);
    if (groups.kept.size() != before) points = gather(local, groups.kept);
    orient_cells(mesh, points, shape);
    peel_hull_slivers(mesh, points, shape);

    report_progress(settings, 0.6f, "hull");
    Hull hull;
    if (shape.dimension >= 1) {
        hull = find_hull(mesh, points, shape);
    } else {
        hull.vertex_normals.assign(points.size(), Eigen::Vector3d::Zero());
    }
    // Rays leave along the normals exactly as stored (float), so a query's roots match the rows.
    std::vector<Eigen::Vector3d> normals(points.size());
    for (size_t j = 0; j < points.size(); ++j) normals[j] = hull.vertex_normals[j].cast<float>().cast<double>();
    const bool extrapolate = !(settings.flags & TP_BUILD_NO_EXTRAPOLATION) && shape.dimension >= 1;
    OuterCells outer;
    if (extrapolate) outer = build_outer_cells(mesh, hull, points, normals, shape.axes.col(2));

    report_progress(settings, 0.7f, "matrices");
    anchor_cells_at_central_probe(mesh, points);  // the outer cells link to cells, not slots: safe here
    const std::vector<std::array<double, 12>> inner_matrices = inner_cell_matrices(mesh, points, shape);

    StoreData data;
    data.flags = ((settings.flags & TP_BUILD_NO_EXTRAPOLATION) ? kFlagNoExtrapolation : 0u) |
                 ((settings.flags & TP_BUILD_INDEX32) ? kFlagIndex32 : 0u);
    data.dimension = shape.dimension;
    for (int a = 0; a < 3; ++a) data.origin[a] = origin[a];
    data.input_probe_count = uint32_t(count);
    const size_t probes = points.size();
    data.positions.resize(probes * 3);
    data.normals.resize(probes * 3);
    for (size_t j = 0; j < probes; ++j) {
        for (int a = 0; a < 3; ++a) {
            data.positions[j * 3 + size_t(a)] = float(points[j][a]);
            data.normals[j * 3 + size_t(a)] = float(normals[j][a]);
        }
    }
    // A stored probe's SH is the mean of every input probe merged into it.
    std::vector<double> sh_sum(probes * 27, 0.0);
    std::vector<uint32_t> members(probes, 0);
    for (size_t i = 0; i < count; ++i) {
        const uint32_t j = groups.group[i];
        ++members[j];
        for (size_t c = 0; c < 27; ++c) sh_sum[j * 27 + c] += input.sh[i * 27 + c];
    }
    data.sh.resize(probes * 27);
    for (size_t j = 0; j < probes; ++j) {
        for (size_t c = 0; c < 27; ++c) data.sh[j * 27 + c] = float(sh_sum[j * 27 + c] / members[j]);
    }
    data.probe_source = groups.kept;
    data.input_remap = groups.group;

    data.inner_cell_count = uint32_t(mesh.cell_count());
    const size_t cells = mesh.cell_count() + outer.vertices.size();
    data.cell_vertices.reserve(cells * 4);
    data.cell_neighbours.reserve(cells * 4);
    for (size_t c = 0; c < mesh.cell_count(); ++c) {
        data.cell_vertices.insert(data.cell_vertices.end(), mesh.vertices[c].begin(), mesh.vertices[c].end());
        data.cell_neighbours.insert(data.cell_neighbours.end(), mesh.neighbours[c].begin(), mesh.neighbours[c].end());
    }
    for (size_t c = 0; c < outer.vertices.size(); ++c) {
        data.cell_vertices.insert(data.cell_vertices.end(), outer.vertices[c].begin(), outer.vertices[c].end());
        data.cell_neighbours.insert(data.cell_neighbours.end(), outer.neighbours[c].begin(), outer.neighbours[c].end());
    }
    data.inner_matrices.reserve(inner_matrices.size() * 12);
    for (const auto& m : inner_matrices) {
        for (double value : m) data.inner_matrices.push_back(float(value));
    }
    data.outer_matrices.reserve(outer.matrices.size() * 16);
    for (const auto& m : outer.matrices) {
        for (double value : m) data.outer_matrices.push_back(float(value));
    }
    for (int a = 0; a < 3; ++a) {
        data.bounds_min[a] = data.positions[size_t(a)];
        data.bounds_max[a] = data.positions[size_t(a)];
    }
    for (size_t j = 0; j < probes; ++j) {
        for (int a = 0; a < 3; ++a) {
            data.bounds_min[a] = std::min(data.bounds_min[a], data.positions[j * 3 + size_t(a)]);
            data.bounds_max[a] = std::max(data.bounds_max[a], data.positions[j * 3 + size_t(a)]);
        }
    }

    report_progress(settings, 0.85f, "ordering");
    order_cells_for_locality(data);
    report_progress(settings, 0.9f, "grid");
    build_start_grid(data);
    report_progress(settings, 1.0f, "done");
    return data;
}

}  // namespace tetprobe
