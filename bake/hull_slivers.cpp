#include "bake/hull_slivers.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace tetprobe {

namespace {

uint64_t edge_key(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    return (uint64_t(a) << 32) | b;
}

// Boundary bookkeeping: how many hull facets touch each probe and (3D) each edge.
struct Boundary {
    std::vector<uint32_t> facets_at_vertex;
    std::unordered_map<uint64_t, uint32_t> facets_at_edge;

    void change(const uint32_t* facet, uint32_t size, int delta) {
        for (uint32_t i = 0; i < size; ++i) facets_at_vertex[facet[i]] += uint32_t(delta);
        if (size == 3) {
            for (uint32_t i = 0; i < 3; ++i) {
                const uint64_t key = edge_key(facet[i], facet[(i + 1) % 3]);
                if (delta > 0) {
                    ++facets_at_edge[key];
                } else if (--facets_at_edge[key] == 0) {
                    facets_at_edge.erase(key);
                }
            }
        }
    }
    bool has_edge(uint32_t a, uint32_t b) const { return facets_at_edge.count(edge_key(a, b)) != 0; }
};

// The d probes of the facet opposite slot k.
uint32_t facet_opposite(const CellSlots& v, uint32_t d, uint32_t k, uint32_t out[3]) {
    uint32_t n = 0;
    for (uint32_t j = 0; j <= d; ++j) {
        if (j != k) out[n++] = v[j];
    }
    return n;
}

double longest_edge(const CellSlots& v, uint32_t d, const std::vector<Eigen::Vector3d>& p) {
    double longest = 0;
    for (uint32_t i = 0; i <= d; ++i) {
        for (uint32_t j = i + 1; j <= d; ++j) longest = std::max(longest, (p[v[i]] - p[v[j]]).norm());
    }
    return longest;
}

// Distance of the probe in slot k from the plane (2D: the line, within the set's plane) of the
// cell's other probes; 0 when those are themselves a sliver (three nearly collinear probes, whose
// plane is no plane: the facet is degenerate and peeled in turn, not a place a probe can be beyond).
double height_over_opposite_facet(const CellSlots& v, uint32_t d, uint32_t k, const std::vector<Eigen::Vector3d>& p,
                                  const SetShape& shape) {
    uint32_t facet[3];
    const uint32_t size = facet_opposite(v, d, k, facet);
    const Eigen::Vector3d& o = p[facet[0]];
    const Eigen::Vector3d across = size == 3 ? Eigen::Vector3d((p[facet[1]] - o).cross(p[facet[2]] - o))
                                             : Eigen::Vector3d((p[facet[1]] - o).cross(shape.axes.col(2)));
    double longest = 0;
    for (uint32_t i = 0; i < size; ++i) {
        for (uint32_t j = i + 1; j < size; ++j) longest = std::max(longest, (p[facet[i]] - p[facet[j]]).norm());
    }
    const double length = across.norm();
    const double facet_thickness = size == 3 ? length / (longest * longest) : 1.0;
    if (!(length > 0) || !(facet_thickness >= kSliverThickness)) return 0;
    return std::fabs(across.dot(p[v[k]] - o)) / length;
}

}  // namespace

double cell_thickness(const SimplexMesh& mesh, size_t cell, const std::vector<Eigen::Vector3d>& p,
                      const SetShape& shape) {
    const uint32_t d = mesh.dimension;
    if (d < 2) return 1;
    const CellSlots& v = mesh.vertices[cell];
    const double longest = longest_edge(v, d, p);
    if (!(longest > 0)) return 0;
    const Eigen::Vector3d a = p[v[1]] - p[v[0]], b = p[v[2]] - p[v[0]];
    if (d == 2) return std::fabs(a.cross(b).dot(shape.axes.col(2))) / (longest * longest);
    return std::fabs(a.cross(b).dot(p[v[3]] - p[v[0]])) / (longest * longest * longest);
}

size_t peel_hull_slivers(SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& positions, const SetShape& shape) {
    const uint32_t d = mesh.dimension;
    if (d < 2) return 0;
    const size_t cells = mesh.cell_count();
    std::vector<char> alive(cells, 1);
    std::vector<uint32_t> cells_at_vertex(positions.size(), 0);
    Boundary boundary;
    boundary.facets_at_vertex.assign(positions.size(), 0);
    std::vector<uint32_t> work;
    for (size_t c = 0; c < cells; ++c) {
        for (uint32_t k = 0; k <= d; ++k) ++cells_at_vertex[mesh.vertices[c][k]];
        for (uint32_t k = 0; k <= d; ++k) {
            if (mesh.neighbours[c][k] != kNone32) continue;
            uint32_t facet[3];
            boundary.change(facet, facet_opposite(mesh.vertices[c], d, k, facet), +1);
            work.push_back(uint32_t(c));
        }
    }

    size_t peeled = 0;
    while (!work.empty()) {
        const uint32_t c = work.back();
        work.pop_back();
        if (!alive[c]) continue;
        const CellSlots& v = mesh.vertices[c];
        uint32_t hull_slots = 0, open = 0;
        for (uint32_t k = 0; k <= d; ++k) {
            if (mesh.neighbours[c][k] == kNone32) ++hull_slots;
        }
        if (hull_slots == 0 || hull_slots == d + 1) continue;
        if (cell_thickness(mesh, c, positions, shape) >= kSliverThickness) continue;
        // Every probe keeps a cell.
        bool keeps = true;
        for (uint32_t k = 0; k <= d; ++k) keeps = keeps && cells_at_vertex[v[k]] > 1;
        if (!keeps) continue;
        // The boundary stays a manifold: a probe that becomes a hull vertex was not one already, an
        // edge that becomes a hull edge was not one already, a probe that leaves the hull has no other
        // hull facet.
        for (uint32_t k = 0; k <= d; ++k) {
            if (mesh.neighbours[c][k] != kNone32) open |= 1u << k;
        }
        bool manifold = true;
        if (hull_slots == 1) {
            for (uint32_t k = 0; k <= d; ++k) {
                if (!(open & (1u << k))) manifold = boundary.facets_at_vertex[v[k]] == 0;
            }
        } else if (d == 3 && hull_slots == 2) {
            uint32_t ends[2], n = 0;
            for (uint32_t k = 0; k <= 3; ++k) {
                if (!(open & (1u << k))) ends[n++] = v[k];
            }
            manifold = !boundary.has_edge(ends[0], ends[1]);
        } else {
            // d = 2 with 2 hull edges, d = 3 with 3 hull facets: the one open slot's probe is in every
            // hull facet of this cell and must be in no other.
            for (uint32_t k = 0; k <= d; ++k) {
                if (open & (1u << k)) manifold = boundary.facets_at_vertex[v[k]] == hull_slots;
            }
        }
        if (!manifold) continue;
        // Each exposed facet becomes hull with the probe opposite it beyond it by its height: that
        // must be sliver-thin too. A needle (three close probes and a far one) is thin by volume,
        // yet can leave a probe far outside a new hull facet, whose outer cell then answers there.
        const double depth = kSliverThickness * longest_edge(v, d, positions);
        bool shallow = true;
        for (uint32_t k = 0; k <= d; ++k) {
            if (open & (1u << k)) shallow = shallow && height_over_opposite_facet(v, d, k, positions, shape) < depth;
        }
        if (!shallow) continue;

        alive[c] = 0;
        ++peeled;
        for (uint32_t k = 0; k <= d; ++k) --cells_at_vertex[v[k]];
        for (uint32_t k = 0; k <= d; ++k) {
            uint32_t facet[3];
            const uint32_t size = facet_opposite(v, d, k, facet);
            const uint32_t n = mesh.neighbours[c][k];
            if (n == kNone32) {
                boundary.change(facet, size, -1);
                continue;
            }
            boundary.change(facet, size, +1);
            for (uint32_t j = 0; j <= d; ++j) {
                if (mesh.neighbours[n][j] == c) mesh.neighbours[n][j] = kNone32;
            }
            work.push_back(n);
        }
    }
    if (peeled == 0) return 0;

    std::vector<uint32_t> renumber(cells, kNone32);
    uint32_t next = 0;
    for (size_t c = 0; c < cells; ++c) {
        if (alive[c]) renumber[c] = next++;
    }
    SimplexMesh kept;
    kept.dimension = d;
    for (size_t c = 0; c < cells; ++c) {
        if (!alive[c]) continue;
        CellSlots links = mesh.neighbours[c];
        for (auto& link : links) {
            if (link != kNone32) link = renumber[link];
        }
        kept.add_cell(mesh.vertices[c], links);
    }
    mesh = std::move(kept);
    return peeled;
}

}  // namespace tetprobe
