#include "core/delaunay2d.h"

#include "core/canonical_cells.h"
#include "core/error.h"
#include "core/insphere.h"
#include "core/integer_predicates.h"
#include "core/orientation.h"

#include <algorithm>
#include <string>
#include <vector>

namespace tetprobe {

namespace {

constexpr uint32_t kInfinite = 0xFFFFFFFFu;  // the vertex at infinity shared by the hull's outer triangles
constexpr uint32_t kDead = 0xFFFFFFFEu;      // v[0] of a triangle on the free list

// A triangle: three vertices and, per edge k (opposite vertex k), the neighbour across it as
// triangle * 4 + the neighbour's edge. A triangle at infinity holds kInfinite in slot 2; its hull edge
// (slots 0, 1) has the hull on its negative side.
struct Tri {
    uint32_t v[3];
    uint32_t n[3];
};

class Triangulation {
public:
    Triangulation(const float* positions, uint32_t count, uint32_t axis) : count_(count) {
        const uint32_t u = axis == 0 ? 1 : 0, w = axis == 2 ? 1 : 2;
        uv_.resize(size_t(count) * 2);
        for (size_t i = 0; i < count; ++i) {
            uv_[2 * i] = positions[3 * i + u];
            uv_[2 * i + 1] = positions[3 * i + w];
        }
    }

    SimplexMesh run(const std::vector<uint32_t>& order) {
        if (count_ < 3) throw Error(Status::degenerate, "a triangulation needs at least 3 probes");
        start(order);
        for (uint32_t i : order)
            if (!initial_[i]) insert(i);
        return extract();
    }

private:
    struct Boundary {
        uint32_t cell, edge, outside;
        uint32_t v[3];
    };

    const float* point(uint32_t v) const { return uv_.data() + size_t(v) * 2; }

    bool same_point(uint32_t a, uint32_t b) const {
        return point(a)[0] == point(b)[0] && point(a)[1] == point(b)[1];
    }

    [[noreturn]] void duplicate(uint32_t a, uint32_t b) const {
        throw Error(Status::invalid_argument, "probes " + std::to_string(std::min(a, b)) + " and " +
                                                  std::to_string(std::max(a, b)) + " are at the same plane position");
    }

    uint32_t new_cell() {
        if (!free_.empty()) {
            const uint32_t t = free_.back();
            free_.pop_back();
            mark_[t] = 0;
            return t;
        }
        if (tris_.size() >= (size_t(1) << 30)) throw Error(Status::invalid_argument, "too many cells to triangulate");
        tris_.push_back(Tri{});
        mark_.push_back(0);
        return uint32_t(tris_.size() - 1);
    }

    void link(uint32_t t, uint32_t k, uint32_t u, uint32_t j) {
        tris_[t].n[k] = u * 4 + j;
        tris_[u].n[j] = t * 4 + k;
    }

    void start(const std::vector<uint32_t>& order) {
        tris_.reserve(size_t(count_) * 2 + 16);
        mark_.reserve(tris_.capacity());
        initial_.assign(count_, 0);
        met_.assign(size_t(count_) + 1, 0);
        met_generation_.assign(size_t(count_) + 1, 0);
        const uint32_t a = order[0], b = order[1];
        if (same_point(a, b)) duplicate(a, b);
        uint32_t c = kInfinite;
        for (size_t at = 2; at < count_ && c == kInfinite; ++at)
            if (orient2d(point(a), point(b), point(order[at])) != 0) c = order[at];
        if (c == kInfinite) throw Error(Status::degenerate, "the probes span no area (all collinear)");
        initial_[a] = initial_[b] = initial_[c] = 1;
        uint32_t v[3] = {a, b, c};
        if (orient2d(point(a), point(b), point(c)) < 0) std::swap(v[0], v[1]);
        const uint32_t first = new_cell();
        std::copy(v, v + 3, tris_[first].v);
        uint32_t ghost[3];
        for (uint32_t k = 0; k < 3; ++k) {
            ghost[k] = new_cell();
            Tri& g = tris_[ghost[k]];
            g.v[0] = v[(k + 2) % 3];
            g.v[1] = v[(k + 1) % 3];
            g.v[2] = kInfinite;
            link(first, k, ghost[k], 2);
        }
        // Ghost k = (v[k+2], v[k+1], inf) meets ghost k+1 = (v[k], v[k+2], inf) across the edge
        // {v[k+2], inf}: slot 1 of ghost k, slot 0 of ghost k+1.
        for (uint32_t k = 0; k < 3; ++k) link(ghost[k], 1, ghost[(k + 1) % 3], 0);
        last_ = first;
    }

    uint32_t locate(uint32_t p) {
        const float* q = point(p);
        uint32_t t = last_, from = 3, rotation = 0;
        const size_t cap = 4 * tris_.size() + 64;
        for (size_t steps = 0; steps < cap; ++steps) {
            const Tri& cell = tris_[t];
            if (cell.v[2] == kInfinite) return t;
            const float* x[3] = {point(cell.v[0]), point(cell.v[1]), point(cell.v[2])};
            uint32_t exit = 3;
            rotation = rotation == 2 ? 0 : rotation + 1;
            for (uint32_t j = 0; j < 3 && exit == 3; ++j) {
                const uint32_t k = (j + rotation) % 3;
                if (k == from) continue;
                const float* y[3] = {x[0], x[1], x[2]};
                y[k] = q;
                if (orient2d_fast(y[0], y[1], y[2]) < 0) exit = k;
            }
            if (exit == 3) return t;
            from = cell.n[exit] & 3;
            t = cell.n[exit] >> 2;
        }
        return locate_by_search(p);
    }

    uint32_t locate_by_search(uint32_t p) const {
        const float* q = point(p);
        uint32_t seen_from_outside = kInfinite;
        for (uint32_t t = 0; t < tris_.size(); ++t) {
            const Tri& cell = tris_[t];
            if (cell.v[0] == kDead) continue;
            if (cell.v[2] == kInfinite) {
                if (seen_from_outside == kInfinite && orient2d(point(cell.v[0]), point(cell.v[1]), q) > 0) seen_from_outside = t;
                continue;
            }
            bool inside = true;
            for (uint32_t k = 0; k < 3 && inside; ++k) {
                const float* y[3] = {point(cell.v[0]), point(cell.v[1]), point(cell.v[2])};
                y[k] = q;
                inside = orient2d(y[0], y[1], y[2]) >= 0;
            }
            if (inside) return t;
        }
        if (seen_from_outside == kInfinite) throw Error(Status::internal, "point location failed");
        return seen_from_outside;
    }

    bool in_conflict(uint32_t t, uint32_t p) {
        const uint32_t state = mark_[t];
        if ((state >> 1) == stamp_) return (state & 1u) == 0;
        const Tri& cell = tris_[t];
        bool conflict;
        if (cell.v[2] != kInfinite) {
            const float* const points[4] = {point(cell.v[0]), point(cell.v[1]), point(cell.v[2]), point(p)};
            const uint32_t indices[4] = {cell.v[0], cell.v[1], cell.v[2], p};
            conflict = incircle_perturbed(points, indices) > 0;
        } else {
            const int side = orient2d_fast(point(cell.v[0]), point(cell.v[1]), point(p));
            conflict = side > 0 || (side == 0 && in_conflict(cell.n[2] >> 2, p));
        }
        mark_[t] = stamp_ << 1 | (conflict ? 0u : 1u);
        if (conflict) {
            cavity_.push_back(t);
            stack_.push_back(t);
        }
        return conflict;
    }

    void insert(uint32_t p) {
        const uint32_t seed = locate(p);
        const Tri& found = tris_[seed];
        if (found.v[2] != kInfinite)
            for (uint32_t k = 0; k < 3; ++k)
                if (same_point(found.v[k], p)) duplicate(found.v[k], p);

        ++stamp_;
        cavity_.clear();
        stack_.clear();
        boundary_.clear();
        mark_[seed] = stamp_ << 1;
        cavity_.push_back(seed);
        stack_.push_back(seed);
        while (!stack_.empty()) {
            const uint32_t c = stack_.back();
            stack_.pop_back();
            for (uint32_t k = 0; k < 3; ++k) {
                const uint32_t across = tris_[c].n[k];
                if (in_conflict(across >> 2, p)) continue;
                Boundary b;
                b.cell = c;
                b.edge = k;
                b.outside = across;
                boundary_.push_back(b);
            }
        }
        for (Boundary& b : boundary_) {
            std::copy(tris_[b.cell].v, tris_[b.cell].v + 3, b.v);
            b.v[b.edge] = p;
        }
        for (uint32_t c : cavity_) {
            tris_[c].v[0] = kDead;
            free_.push_back(c);
        }

        // New triangles meet across the edges through p, named by their other vertex (each vertex
        // of the cavity's boundary ends exactly two of its edges).
        if (++met_stamp_ == 0) {
            std::fill(met_generation_.begin(), met_generation_.end(), 0u);
            met_stamp_ = 1;
        }
        uint32_t finite = kInfinite;
        for (const Boundary& b : boundary_) {
            const uint32_t t = new_cell();
            std::copy(b.v, b.v + 3, tris_[t].v);
            link(t, b.edge, b.outside >> 2, b.outside & 3);
            for (uint32_t j = 0; j < 3; ++j) {
                if (j == b.edge) continue;
                const uint32_t other = b.v[3 - j - b.edge];
                const size_t slot = other == kInfinite ? count_ : other;
                if (met_generation_[slot] != met_stamp_) {
                    met_generation_[slot] = met_stamp_;
                    met_[slot] = t * 4 + j;
                } else {
                    link(t, j, met_[slot] >> 2, met_[slot] & 3);
                }
            }
            if (finite == kInfinite && tris_[t].v[2] != kInfinite) finite = t;
        }
        if (finite != kInfinite) last_ = finite;
    }

    SimplexMesh extract() const {
        std::vector<uint32_t> index(tris_.size(), kNone32);
        uint32_t cells = 0;
        for (uint32_t t = 0; t < tris_.size(); ++t)
            if (tris_[t].v[0] != kDead && tris_[t].v[2] != kInfinite) index[t] = cells++;
        SimplexMesh mesh;
        mesh.dimension = 2;
        mesh.vertices.assign(cells, kNoSlots);
        mesh.neighbours.assign(cells, kNoSlots);
        for (uint32_t t = 0; t < tris_.size(); ++t) {
            if (index[t] == kNone32) continue;
            CellSlots& v = mesh.vertices[index[t]];
            CellSlots& n = mesh.neighbours[index[t]];
            for (uint32_t k = 0; k < 3; ++k) {
                v[k] = tris_[t].v[k];
                n[k] = index[tris_[t].n[k] >> 2];
            }
            canonicalise_cell(v, n, 2, 1);  // every triangle is built counter-clockwise
        }
        return mesh;
    }

    uint32_t count_;
    std::vector<float> uv_;
    std::vector<Tri> tris_;
    std::vector<uint32_t> mark_;
    std::vector<uint32_t> free_;
    std::vector<char> initial_;
    std::vector<uint32_t> cavity_, stack_;
    std::vector<Boundary> boundary_;
    std::vector<uint32_t> met_, met_generation_;
    uint32_t met_stamp_ = 0, stamp_ = 0, last_ = 0;
};

}  // namespace

SimplexMesh delaunay_cells_2d(const float* positions, uint32_t count, uint32_t axis) {
    std::vector<uint32_t> order(count);
    for (uint32_t i = 0; i < count; ++i) order[i] = i;
    return Triangulation(positions, count, axis).run(order);
}

SimplexMesh delaunay_cells_2d(const float* positions, uint32_t count, uint32_t axis, const std::vector<uint32_t>& order) {
    std::vector<char> seen(count, 0);
    for (uint32_t i : order) {
        if (i >= count || seen[i]) throw Error(Status::invalid_argument, "the insertion order names every point once");
        seen[i] = 1;
    }
    if (order.size() != count) throw Error(Status::invalid_argument, "the insertion order names every point once");
    return Triangulation(positions, count, axis).run(order);
}

}  // namespace tetprobe
