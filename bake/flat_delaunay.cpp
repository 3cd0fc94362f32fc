#include "bake/flat_delaunay.h"

#include "bake/delaunay.h"
#include "core/error.h"

#include <algorithm>
#include <utility>

namespace tetprobe {

SimplexMesh delaunay_triangulate_plane(const std::vector<Eigen::Vector2d>& uv) {
    if (uv.size() < 3) throw Error(Status::internal, "triangulation needs at least 3 points");
    Eigen::Vector2d lo = uv[0], hi = uv[0], centroid = Eigen::Vector2d::Zero();
    for (const auto& p : uv) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        centroid += p;
    }
    centroid /= double(uv.size());
    const double height = (hi - lo).norm();

    std::vector<Eigen::Vector3d> points;
    points.reserve(uv.size() + 1);
    for (const auto& p : uv) points.emplace_back(p.x(), p.y(), 0.0);
    const uint32_t apex = uint32_t(uv.size());
    points.emplace_back(centroid.x(), centroid.y(), height);

    // TetGen 1.5.0 sometimes leaves out a probe that sits exactly on a straight stretch of the
    // boundary (seen with four collinear hull probes); another apex changes its insertion order and
    // keeps it. The builder merges a probe left out by every attempt into its nearest neighbour.
    const Eigen::Vector3d apexes[] = {{centroid.x(), centroid.y(), height},
                                      {lo.x() + 0.31 * (hi.x() - lo.x()), lo.y() + 0.67 * (hi.y() - lo.y()), 2.7 * height},
                                      {lo.x() + 0.83 * (hi.x() - lo.x()), lo.y() + 0.21 * (hi.y() - lo.y()), 0.6 * height}};
    SimplexMesh tets;
    for (const Eigen::Vector3d& apex_position : apexes) {
        points[apex] = apex_position;
        tets = delaunay_tetrahedralize(points);
        std::vector<char> used(points.size(), 0);
        for (const CellSlots& v : tets.vertices)
            for (uint32_t index : v)
                if (index < used.size()) used[index] = 1;
        if (std::all_of(used.begin(), used.end(), [](char u) { return u != 0; })) break;
    }

    // Tetrahedron t becomes triangle t: drop the apex slot and keep the other three in order, with
    // their neighbours (the neighbour across the facet opposite a base vertex is the tetrahedron over
    // the adjacent triangle; the one opposite the apex is outside the pyramid).
    SimplexMesh mesh;
    mesh.dimension = 2;
    mesh.vertices.reserve(tets.cell_count());
    mesh.neighbours.reserve(tets.cell_count());
    for (size_t t = 0; t < tets.cell_count(); ++t) {
        const CellSlots& v = tets.vertices[t];
        const auto apex_slot = std::find(v.begin(), v.end(), apex) - v.begin();
        if (apex_slot == 4) {
            throw Error(Status::tetgen, "TetGen returned a flat tetrahedron in a plane triangulation");
        }
        CellSlots vertices = kNoSlots, neighbours = kNoSlots;
        int slot = 0;
        for (int k = 0; k < 4; ++k) {
            if (k == apex_slot) continue;
            vertices[size_t(slot)] = v[size_t(k)];
            neighbours[size_t(slot)] = tets.neighbours[t][size_t(k)];
            ++slot;
        }
        // orient3d(t0, t1, t2, apex) = orient2d(t0, t1, t2) x height, and moving the apex from its slot
        // to slot 3 takes 3 - apex_slot transpositions: undoing an odd count keeps every triangle
        // wound as its tetrahedron (TetGen winds them all alike), even a triangle of collinear probes.
        if ((3 - apex_slot) % 2 != 0) {
            std::swap(vertices[0], vertices[1]);
            std::swap(neighbours[0], neighbours[1]);
        }
        mesh.add_cell(vertices, neighbours);
    }
    return mesh;
}

}  // namespace tetprobe
