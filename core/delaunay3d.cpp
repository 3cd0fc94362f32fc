#include "core/delaunay3d.h"

#include "core/canonical_cells.h"
#include "core/error.h"
#include "core/insphere.h"
#include "core/insphere_kernels.h"
#include "core/integer_predicates.h"
#include "core/orientation.h"
#include "core/tetrahedron_orientations.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace tetprobe {

namespace {

constexpr uint32_t kInfinite = 0xFFFFFFFFu;  // the vertex at infinity shared by the hull's outer cells
constexpr uint32_t kDead = 0xFFFFFFFEu;      // v[0] of a cell on the free list

// Facet k of a positively oriented cell, wound so that vertex k lies on its negative side:
// orient3d(v[f0], v[f1], v[f2], v[k]) = -orient3d(v0, v1, v2, v3).
constexpr int kFacet[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// For a new cell with the new point in slot f: its three other facets j, each with the edge it
// shares with the cavity's boundary as a half-edge (end0 -> end1: the facet's outward winding from
// the new point on). The neighbouring new cell holds the same edge the other way round.
struct FacetEdge {
    uint32_t facet, end0, end1;
};
constexpr FacetEdge kFacetEdges[4][3] = {{{1, 3, 2}, {2, 1, 3}, {3, 2, 1}},
                                         {{0, 2, 3}, {2, 3, 0}, {3, 0, 2}},
                                         {{0, 3, 1}, {1, 0, 3}, {3, 1, 0}},
                                         {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}};

// The order points are inserted in: rounds each about four times the size of the one before (a
// point's round is drawn from a hash of its index), each in the given order. Mixing coarse rounds in
// first keeps the cavities small (the biased randomized insertion order of Amenta, Choi and Rote);
// the given space-filling-curve order within a round keeps each walk short and its cells in cache.
// Any order gives the same tessellation.
std::vector<uint32_t> insertion_order(uint32_t count) {
    constexpr int kRounds = 16;
    std::vector<uint32_t> round_of(count), starts(kRounds + 1, 0);
    for (uint32_t i = 0; i < count; ++i) {
        uint32_t h = i * 0x9E3779B1u;
        h ^= h >> 15;
        h *= 0x85EBCA77u;
        h ^= h >> 13;
        int r = 0;
        while ((h & 1u) && r < kRounds - 1) {
            h >>= 1;
            ++r;
        }
        r /= 2;  // trailing ones in pairs: each round a quarter of the next
        round_of[i] = uint32_t(kRounds - 1 - r);  // the rarest rounds first
        ++starts[round_of[i] + 1];
    }
    for (int r = 0; r < kRounds; ++r) starts[r + 1] += starts[r];
    std::vector<uint32_t> order(count);
    for (uint32_t i = 0; i < count; ++i) order[starts[round_of[i]]++] = i;
    return order;
}

// A cell: four vertices and, per facet k (opposite vertex k), the neighbour across it as
// cell * 4 + the neighbour's facet. A cell at infinity holds kInfinite in slot 3 and its hull facet
// (slots 0..2) has the hull on its negative side, the point at infinity on its positive side.
struct Tet {
    uint32_t v[4];
    uint32_t n[4];
    uint32_t mark;  // stamp << 1 | (1 = not in conflict) for the insertion of that stamp
};

// The cells, appended one at a time: a std::vector's push_back stayed a call (about one per new
// cell that the free list cannot give). Appended cells start with mark 0 (no insertion's).
class CellPool {
public:
    void reserve(size_t capacity) {
        if (capacity > capacity_) grow(capacity);
    }
    size_t size() const { return size_; }
    Tet& operator[](size_t i) { return cells_[i]; }
    const Tet& operator[](size_t i) const { return cells_[i]; }
    uint32_t append() {
        if (__builtin_expect(size_ == capacity_, 0)) grow(std::max<size_t>(64, 2 * capacity_));
        cells_[size_].mark = 0;
        return uint32_t(size_++);
    }

private:
    __attribute__((noinline)) void grow(size_t capacity) {
        std::unique_ptr<Tet[]> more(new Tet[capacity]);
        std::copy(cells_.get(), cells_.get() + size_, more.get());
        cells_ = std::move(more);
        capacity_ = capacity;
    }
    std::unique_ptr<Tet[]> cells_;
    size_t size_ = 0, capacity_ = 0;
};

// Pairs the facets of one insertion's new cells across the edges they share: each new facet is
// filed under its half-edge, and meets the facet filed under the reverse one (the cavity's boundary
// is a closed surface wound alike throughout). Filing and finding take no branch on the data (a
// first-or-second test would be a coin toss); the table is kept sparse so that probes rarely
// collide. An empty slot has key 0, which no half-edge has (its ends differ).
class EdgeLinks {
public:
    void start(size_t half_edges) {
        size_t capacity = 256;
        while (capacity < 4 * half_edges) capacity *= 2;
        if (capacity > slots_.size()) slots_.assign(capacity, Slot{});
        mask_ = capacity - 1;
        filed_.resize(half_edges);
        count_ = 0;
    }
    // Files one of at most half_edges facets (as many as start was given).
    void add(uint32_t from, uint32_t to, uint32_t facet) {
        const uint64_t key = uint64_t(from) << 32 | to;
        size_t at = slot_of(key);
        while (slots_[at].key != 0) at = (at + 1) & mask_;
        slots_[at] = Slot{key, facet};
        filed_[count_++] = Filed{key, facet, uint32_t(at)};
    }
    // Calls link(facet, facet across) for every filed facet, then empties the table. Throws if a
    // half-edge has no reverse (the boundary would not be closed: only a broken tessellation).
    template <class Link>
    void finish(Link&& link) {
        for (size_t i = 0; i < count_; ++i) {
            const Filed& f = filed_[i];
            const uint64_t reverse = f.key << 32 | f.key >> 32;
            size_t at = slot_of(reverse);
            while (slots_[at].key != reverse) {
                if (slots_[at].key == 0) throw Error(Status::internal, "a cavity's boundary is not closed");
                at = (at + 1) & mask_;
            }
            link(f.facet, slots_[at].facet);
        }
        for (size_t i = 0; i < count_; ++i) slots_[filed_[i].at].key = 0;
    }

private:
    struct Slot {
        uint64_t key = 0;
        uint32_t facet = 0;
    };
    struct Filed {
        uint64_t key;
        uint32_t facet, at;
    };
    size_t slot_of(uint64_t key) const { return size_t((key * 0x9E3779B97F4A7C15ull) >> 40) & mask_; }
    std::vector<Slot> slots_;
    std::vector<Filed> filed_;
    size_t mask_ = 0, count_ = 0;
};

// The insertion's loops over a cell's four slots or a facet's three edges, unrolled: their indices
// become constants (-O2 does not peel them; about 2% of a rebuild, measured).
#define TP_UNROLL_FULLY _Pragma("GCC unroll 4")
#define TP_TETRAHEDRALIZATION PortableTetrahedralization
#define TP_SPHERE_KERNEL ScalarInsphere
#define TP_ORIENT_KERNEL ScalarOrientations
#include "core/delaunay3d.inl"
#undef TP_TETRAHEDRALIZATION
#undef TP_SPHERE_KERNEL
#undef TP_ORIENT_KERNEL
#ifdef TETPROBE_X86_64
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
#define TP_TETRAHEDRALIZATION Avx2Tetrahedralization
#define TP_SPHERE_KERNEL Avx2Insphere
#define TP_ORIENT_KERNEL Avx2Orientations
#include "core/delaunay3d.inl"
#undef TP_TETRAHEDRALIZATION
#undef TP_SPHERE_KERNEL
#undef TP_ORIENT_KERNEL
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif

SimplexMesh tetrahedralize(const float* positions, uint32_t count, const std::vector<uint32_t>& order, uint64_t max_cells) {
#ifdef TETPROBE_X86_64
    if (cpu_has_avx2() && !std::getenv("TP_NO_AVX2")) return Avx2Tetrahedralization(positions, count, max_cells).run(order);
#endif
    return PortableTetrahedralization(positions, count, max_cells).run(order);
}


}  // namespace

SimplexMesh delaunay_cells_3d(const float* positions, uint32_t count, uint64_t max_cells) {
    return tetrahedralize(positions, count, insertion_order(count), max_cells);
}

SimplexMesh delaunay_cells_3d(const float* positions, uint32_t count, const std::vector<uint32_t>& order) {
    std::vector<char> seen(count, 0);
    for (uint32_t i : order) {
        if (i >= count || seen[i]) throw Error(Status::invalid_argument, "the insertion order names every point once");
        seen[i] = 1;
    }
    return tetrahedralize(positions, count, order, kUnlimitedCells);
}

}  // namespace tetprobe
