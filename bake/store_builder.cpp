#include "bake/store_builder.h"

#include "bake/delaunay.h"
#include "bake/flat_delaunay.h"
#include "bake/input_screening.h"
#include "bake/leak_edges.h"
#include "bake/probe_merge.h"
#include "bake/set_dimension.h"
#include "core/canonical_cells.h"
#include "core/cell_order.h"
#include "core/cell_rebuild.h"
#include "core/error.h"
#include "core/hull_normals.h"
#include "core/start_grid.h"
#include "core/store_format.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <tuple>
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

// Probes of a flat set at the same plane coordinates, or of a line at the same coordinate along its
// axis, merge into the first (stored order): the cells cannot tell them apart (their offsets across
// the plane or line were too large to merge them in the set's own coordinates, or no merge tolerance
// was given), and a cell between them would hold no point.
void merge_equal_decided_coordinates(const std::vector<Eigen::Vector3d>& points, const SetShape& shape,
                                     ProbeGroups& groups) {
    std::vector<uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::vector<Eigen::Vector2d> uv(points.size());
    for (size_t j = 0; j < points.size(); ++j)
        uv[j] = shape.dimension == 2 ? shape.plane_coordinates(points[j])
                                     : Eigen::Vector2d(double(float(points[j][shape.line_axis()])), 0.0);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return std::tie(uv[a].x(), uv[a].y(), a) < std::tie(uv[b].x(), uv[b].y(), b);
    });
    ProbeMerge merge;
    merge.group_of.resize(points.size());
    std::iota(merge.group_of.begin(), merge.group_of.end(), 0u);
    bool merged = false;
    for (size_t i = 1; i < order.size(); ++i)
        if (uv[order[i]] == uv[order[i - 1]]) {
            merge.group_of[order[i]] = merge.group_of[order[i - 1]];
            merged = true;
        }
    if (!merged) return;
    std::vector<uint32_t> compact(points.size(), kNone32);
    for (uint32_t j = 0; j < points.size(); ++j) {
        if (merge.group_of[j] != j) continue;
        compact[j] = uint32_t(merge.survivors.size());
        merge.survivors.push_back(j);
    }
    for (auto& g : merge.group_of) g = compact[g];
    groups.apply(merge);
}

// Whether two meshes in canonical form hold the same cells (in any order): b's cells are filed in an
// open-addressing table and every cell of a must be found there once.
bool same_cells(const SimplexMesh& a, const SimplexMesh& b) {
    if (a.cell_count() != b.cell_count()) return false;
    size_t capacity = 16;
    while (capacity < 2 * b.cell_count()) capacity *= 2;
    std::vector<uint32_t> table(capacity, kNone32);  // cell of b, or empty
    std::vector<char> found(b.cell_count(), 0);
    auto slot_of = [&](const CellSlots& v) {
        uint64_t h = 0;
        for (uint32_t x : v) h = (h ^ x) * 0x9E3779B97F4A7C15ull;
        return size_t(h >> 20) & (capacity - 1);
    };
    for (uint32_t c = 0; c < b.cell_count(); ++c) {
        size_t at = slot_of(b.vertices[c]);
        while (table[at] != kNone32) at = (at + 1) & (capacity - 1);
        table[at] = c;
    }
    for (const CellSlots& v : a.vertices) {
        size_t at = slot_of(v);
        while (table[at] != kNone32 && b.vertices[table[at]] != v) at = (at + 1) & (capacity - 1);
        if (table[at] == kNone32 || found[table[at]]) return false;
        found[table[at]] = 1;
    }
    return true;
}

// The inner cells of the stored probes in their own dimension, in canonical form: TetGen's Delaunay
// (a flat set's under an apex), which must be the exact one core rebuilds at load for a layout that
// keeps no cells (core/cell_rebuild.h). Where TetGen 1.5.0 gives other cells (it dies on some
// degenerate sets, and has left out a probe on a straight stretch of a flat set's boundary) or none,
// the store keeps core's, so that every layout stores what a rebuild gives.
SimplexMesh triangulate(const std::vector<Eigen::Vector3d>& points, const std::vector<float>& stored, const SetShape& shape,
                        uint32_t axis) {
    const uint32_t d = shape.dimension, count = uint32_t(points.size());
    SimplexMesh exact = inner_cells(stored.data(), count, d, axis);
    if (d < 2) return exact;  // one cell, or segments: core's code at bake and load alike
    SimplexMesh mesh;
    try {
        if (d == 3) {
            mesh = delaunay_tetrahedralize(points);
        } else {
            std::vector<Eigen::Vector2d> uv(points.size());
            for (size_t j = 0; j < points.size(); ++j) uv[j] = shape.plane_coordinates(points[j]);
            mesh = delaunay_triangulate_plane(uv);
        }
    } catch (const Error& e) {
        if (e.status() != Status::tetgen) throw;
        return exact;
    }
    canonicalise_cells(mesh, stored.data(), axis);
    return same_cells(mesh, exact) ? mesh : exact;
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
    const uint32_t axis = shape.dimension == 2 ? shape.dropped_axis() : shape.dimension == 1 ? shape.line_axis() : 0u;
    if (shape.dimension == 1 || shape.dimension == 2) merge_equal_decided_coordinates(gather(local, groups.kept), shape, groups);
    const std::vector<Eigen::Vector3d> points = gather(local, groups.kept);
    std::vector<float> stored(points.size() * 3);
    for (size_t j = 0; j < points.size(); ++j)
        for (int a = 0; a < 3; ++a) stored[j * 3 + size_t(a)] = float(points[j][a]);
    SimplexMesh mesh = triangulate(points, stored, shape, axis);

    settings.progress.report(0.7f, "storing");
    StoreData data;
    data.flags = settings.flags;
    data.dimension = shape.dimension;
    data.axis = axis;
    for (int a = 0; a < 3; ++a) data.origin[a] = origin[a];
    data.input_probe_count = uint32_t(count);
    const size_t probes = points.size();
    data.positions = stored;
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

    store_cells(std::move(mesh), data);
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
    // Hull normals from the ordered cells, so that they depend on the cells alone.
    const Eigen::Vector3d set_direction = shape.dimension == 2 ? shape.axes.col(2) : shape.axes.col(0);
    const std::vector<Eigen::Vector3d> normals = hull_vertex_normals(data, set_direction);
    data.normals.resize(probes * 3);
    for (size_t j = 0; j < probes; ++j)
        for (int a = 0; a < 3; ++a) data.normals[j * 3 + size_t(a)] = float(normals[j][a]);
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
