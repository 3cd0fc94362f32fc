#include "bake/store_builder.h"

#include "bake/cell_order.h"
#include "bake/delaunay.h"
#include "bake/exact_orientation.h"
#include "bake/flat_delaunay.h"
#include "bake/hull.h"
#include "bake/input_screening.h"
#include "bake/leak_edges.h"
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

void check_settings(const BuildSettings& settings) {
    if (settings.flags & ~kBuildFlags) {
        throw Error(Status::invalid_argument, "unknown build flags " + std::to_string(settings.flags));
    }
    if (!(settings.merge_tolerance >= 0 && settings.merge_tolerance <= 1)) {
        throw Error(Status::invalid_argument, "merge_tolerance must be in [0, 1]");
    }
    if (!(settings.flat_tolerance >= 0 && settings.flat_tolerance <= 0.1)) {
        throw Error(Status::invalid_argument, "flat_tolerance must be in [0, 0.1]");
    }
    if (settings.occlusion && (settings.occlusion_lights < 1 || settings.occlusion_lights > kOcclusionChannels)) {
        throw Error(Status::invalid_argument, "occlusion_lights is " + std::to_string(settings.occlusion_lights) +
                                                  ": occlusion covers 1 to 4 mixed lights");
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

// The points of `which`, in canonical order (by rank), for sums whose rounding must not depend on
// the order the caller gave the probes in.
std::vector<Eigen::Vector3d> gather_canonical(const std::vector<Eigen::Vector3d>& all, std::vector<uint32_t> which,
                                              const std::vector<uint32_t>& rank) {
    std::sort(which.begin(), which.end(), [&](uint32_t a, uint32_t b) { return rank[a] < rank[b]; });
    return gather(all, which);
}

// Merges in the set's own reduced coordinates (a flat set merges probes that differ only across its
// plane, since the triangulation cannot tell them apart) until merging no longer lowers the dimension.
// Merging runs in the caller's order (the first given of a group survives); the shape is fitted to
// the survivors in canonical order.
SetShape merge_and_detect(const std::vector<Eigen::Vector3d>& local, const std::vector<uint32_t>& rank,
                          double diagonal, const BuildSettings& settings, ProbeGroups& groups) {
    SetShape shape;
    for (int round = 0; round < 8; ++round) {
        shape = detect_set_dimension(gather_canonical(local, groups.kept, rank), diagonal, settings.flat_tolerance);
        std::vector<Eigen::Vector3d> reduced(groups.kept.size());
        for (size_t j = 0; j < groups.kept.size(); ++j) {
            const Eigen::Vector3d& p = local[groups.kept[j]];
            reduced[j] = shape.dimension == 3 ? p : shape.reduce(p);
        }
        const ProbeMerge merge = merge_close_points(reduced, settings.merge_tolerance * diagonal);
        if (merge.merged_count() == 0) return shape;
        groups.apply(merge);
    }
    return detect_set_dimension(gather_canonical(local, groups.kept, rank), diagonal, settings.flat_tolerance);
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
            // Ordered by the stored coordinate along the line's main axis (what the run time compares).
            std::vector<double> along(points.size());
            for (size_t j = 0; j < points.size(); ++j) along[j] = points[j][shape.line_axis()];
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

// Gives every inner cell positive orientation, decided exactly on the stored coordinates
// (store_format.h): 3D orient3d(v0, v1, v2, v3) > 0, 2D orient2d(v0, v1, v2) > 0 in the plane
// coordinates, 1D v0 < v1 along the line's axis. TetGen winds all its cells alike, so its convention
// is read from the signs and turned into ours for every cell by one swap of slots 0 and 1 (with their
// neighbours); a cell of zero orientation (exactly flat on the stored floats) keeps that consistent
// winding. Returns the number of flat cells.
size_t orient_cells(SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& p, const SetShape& shape) {
    const size_t cells = mesh.cell_count();
    if (mesh.dimension == 0) return 0;
    std::vector<int8_t> sign(cells);
    if (mesh.dimension == 3) {
        for (size_t c = 0; c < cells; ++c) {
            const CellSlots& v = mesh.vertices[c];
            sign[c] = int8_t(orient3d_sign(p[v[0]].data(), p[v[1]].data(), p[v[2]].data(), p[v[3]].data()));
        }
    } else if (mesh.dimension == 2) {
        std::vector<Eigen::Vector2d> uv(p.size());
        for (size_t j = 0; j < p.size(); ++j) uv[j] = shape.plane_coordinates(p[j]);
        for (size_t c = 0; c < cells; ++c) {
            const CellSlots& v = mesh.vertices[c];
            sign[c] = int8_t(orient2d_sign(uv[v[0]].data(), uv[v[1]].data(), uv[v[2]].data()));
        }
    } else {
        const uint32_t axis = shape.line_axis();
        for (size_t c = 0; c < cells; ++c) {
            const CellSlots& v = mesh.vertices[c];
            sign[c] = int8_t((p[v[1]][axis] > p[v[0]][axis]) - (p[v[1]][axis] < p[v[0]][axis]));
        }
    }
    size_t positive = 0, negative = 0;
    for (int8_t s : sign) {
        positive += s > 0;
        negative += s < 0;
    }
    // A flat cell follows the majority; any other cell is swapped exactly when it is negative (a
    // cell against the majority would mean TetGen wound cells differently: it is righted alone).
    const bool flip_flat = negative > positive;
    size_t flat = 0;
    for (size_t c = 0; c < cells; ++c) {
        flat += sign[c] == 0;
        if (sign[c] < 0 || (sign[c] == 0 && flip_flat)) {
            std::swap(mesh.vertices[c][0], mesh.vertices[c][1]);
            std::swap(mesh.neighbours[c][0], mesh.neighbours[c][1]);
        }
    }
    return flat;
}

// Occlusion of the stored probes: the rounded mean over the input probes merged into each; unused
// channels 255 (unshadowed).
void store_occlusion(const BuildSettings& settings, size_t count, StoreData& data) {
    const size_t probes = data.probe_count();
    std::vector<uint32_t> sum(probes * kOcclusionChannels, 0), members(probes, 0);
    for (size_t i = 0; i < count; ++i) {
        const uint8_t* in = settings.occlusion + i * settings.occlusion_stride;
        const uint32_t j = data.input_remap[i];
        ++members[j];
        for (uint32_t c = 0; c < kOcclusionChannels; ++c) sum[j * kOcclusionChannels + c] += in[c];
    }
    data.occlusion_lights = settings.occlusion_lights;
    data.occlusion.resize(probes * kOcclusionChannels);
    for (size_t j = 0; j < probes; ++j)
        for (uint32_t c = 0; c < kOcclusionChannels; ++c)
            data.occlusion[j * kOcclusionChannels + c] =
                c < settings.occlusion_lights
                    ? uint8_t((sum[j * kOcclusionChannels + c] + members[j] / 2) / members[j])
                    : uint8_t(255);
}

}  // namespace

StoreData build_store_data(const float* positions, size_t position_stride, const float* sh, size_t sh_stride,
                           size_t count, const BuildSettings& settings) {
    check_settings(settings);
    settings.progress.report(0.0f, "screening");
    const ScreenedProbes input = screen_probe_input(positions, position_stride, sh, sh_stride, count);

    // Local frame: centred on the centre of the probes' bounding box (which, unlike a centroid sum,
    // does not depend on their order), rounded to float exactly as stored, so that every later stage
    // computes with the coordinates a query will see.
    Eigen::Vector3d world_lo = input.positions[0], world_hi = input.positions[0];
    for (const auto& p : input.positions) {
        world_lo = world_lo.cwiseMin(p);
        world_hi = world_hi.cwiseMax(p);
    }
    const Eigen::Vector3d origin = 0.5 * (world_lo + world_hi);
    std::vector<Eigen::Vector3d> local(count);  // float-exact; flat and line sets later projected
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
    for (size_t i = 0; i < count; ++i) {
        for (int a = 0; a < 3; ++a) local[i][a] = double(float(input.positions[i][a] - origin[a]));
        lo = lo.cwiseMin(local[i]);
        hi = hi.cwiseMax(local[i]);
    }
    const double diagonal = (hi - lo).norm();
    // The canonical order: along a space-filling curve over the bounds, ties by coordinates.
    const std::vector<uint32_t> canonical = curve_order(local, lo, hi);
    std::vector<uint32_t> rank(count);
    for (uint32_t r = 0; r < count; ++r) rank[canonical[r]] = r;

    settings.progress.report(0.1f, "merging");
    ProbeGroups groups;
    groups.kept.resize(count);
    std::iota(groups.kept.begin(), groups.kept.end(), 0u);
    groups.group = groups.kept;
    SetShape shape = merge_and_detect(local, rank, diagonal, settings, groups);

    // A flat (line) set is stored on its fitted plane (line), each probe moved along the axis the run
    // time drops (plane) or across the axis it keeps (line): the coordinates a query is decided in
    // stay exactly the probe's own, so a query at an input probe still weighs it exactly 1. A set
    // already on it keeps its coordinates, so that probes exactly collinear stay so.
    const double off_set = shape.dimension == 1 ? shape.line_distance : shape.plane_distance;
    if ((shape.dimension == 1 || shape.dimension == 2) && off_set > kOnSetTolerance * diagonal) {
        const Eigen::Vector3d normal = shape.axes.col(2), direction = shape.axes.col(0);
        const uint32_t dropped = shape.dropped_axis(), along = shape.line_axis();
        for (uint32_t i : groups.kept) {
            Eigen::Vector3d on_set = local[i];
            if (shape.dimension == 2) {
                // The point with the same kept coordinates on the plane n . (x - centre) = 0.
                on_set[dropped] = shape.centre[dropped];
                on_set[dropped] -= normal.dot(on_set - shape.centre) / normal[dropped];
            } else {
                on_set = shape.centre + direction * ((local[i][along] - shape.centre[along]) / direction[along]);
                on_set[along] = local[i][along];
            }
            for (int a = 0; a < 3; ++a) local[i][a] = double(float(on_set[a]));
        }
    }

    // Stored probes (and TetGen's input) in canonical order, whatever order the caller gave.
    {
        std::vector<uint32_t> by_rank(groups.kept.size());
        std::iota(by_rank.begin(), by_rank.end(), 0u);
        std::sort(by_rank.begin(), by_rank.end(),
                  [&](uint32_t a, uint32_t b) { return rank[groups.kept[a]] < rank[groups.kept[b]]; });
        ProbeMerge reorder;
        reorder.survivors = by_rank;
        reorder.group_of.resize(by_rank.size());
        for (uint32_t j = 0; j < by_rank.size(); ++j) reorder.group_of[by_rank[j]] = j;
        groups.apply(reorder);
    }

    settings.progress.report(0.2f, "triangulating");
    std::vector<Eigen::Vector3d> points = gather(local, groups.kept);
    SimplexMesh mesh = triangulate(points, shape);
    const size_t before = points.size();
    merge_unused_probes(mesh, points, groups);
    if (groups.kept.size() != before) points = gather(local, groups.kept);
    orient_cells(mesh, points, shape);

    settings.progress.report(0.6f, "hull");
    Hull hull;
    if (shape.dimension >= 1) {
        hull = find_hull(mesh, points, shape);
    } else {
        hull.vertex_normals.assign(points.size(), Eigen::Vector3d::Zero());
    }
    const bool extrapolate = !(settings.flags & kFlagNoExtrapolation) && shape.dimension >= 1;
    OuterCells outer;
    if (extrapolate) outer = build_outer_cells(mesh, hull);

    settings.progress.report(0.7f, "storing");
    StoreData data;
    data.flags = settings.flags;
    data.dimension = shape.dimension;
    data.axis = shape.dimension == 2 ? shape.dropped_axis() : shape.dimension == 1 ? shape.line_axis() : 0u;
    for (int a = 0; a < 3; ++a) data.origin[a] = origin[a];
    data.input_probe_count = uint32_t(count);
    const size_t probes = points.size();
    data.positions.resize(probes * 3);
    data.normals.resize(probes * 3);
    for (size_t j = 0; j < probes; ++j) {
        for (int a = 0; a < 3; ++a) {
            data.positions[j * 3 + size_t(a)] = float(points[j][a]);
            data.normals[j * 3 + size_t(a)] = float(hull.vertex_normals[j][a]);
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
    data.cell_vertices.resize(cells * 4);
    data.cell_neighbours.resize(cells * 4);
    for (size_t c = 0; c < mesh.cell_count(); ++c) {
        std::copy_n(mesh.vertices[c].begin(), 4, &data.cell_vertices[c * 4]);
        std::copy_n(mesh.neighbours[c].begin(), 4, &data.cell_neighbours[c * 4]);
    }
    for (size_t c = 0, at = mesh.cell_count() * 4; c < outer.vertices.size(); ++c, at += 4) {
        std::copy_n(outer.vertices[c].begin(), 4, &data.cell_vertices[at]);
        std::copy_n(outer.neighbours[c].begin(), 4, &data.cell_neighbours[at]);
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

    settings.progress.report(0.85f, "ordering");
    order_cells_for_locality(data);
    if (settings.occlusion) store_occlusion(settings, count, data);
    if (settings.scene) {
        add_leak_edges(*settings.scene, data, settings.threads, settings.progress.part(0.87f, 0.9f));
    }
    settings.progress.report(0.9f, "grid");
    build_start_grid(data);
    settings.progress.report(1.0f, "done");
    return data;
}

}  // namespace tetprobe
