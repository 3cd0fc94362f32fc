// What the walk and the exhaustive search both read: a typed view of a store's cells and the exact
// verdict of an inner cell on a query (orientation signs proven by a filter with an exact fallback),
// with the weights of a held point. Included by walk.cpp, outer_cells.cpp and exhaustive_search.cpp.
#pragma once

#include "core/orientation.h"
#include "core/plane_projection.h"
#include "core/store_impl.h"
#include "core/tetrahedron_orientations.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace tetprobe {

// No cell (a neighbour slot on the hull, widened).
constexpr uint32_t kNoCell = 0xFFFFFFFFu;
// Bound of the 2D permanent below: 2 products of the largest |differences|, with room for the
// rounding of that bound itself (the 3D one is in tetrahedron_orientations.h).
constexpr double kOrient2dBoundScale = 2.000001 * kOrient2dErrorFactor;

// max without std::fmax's NaN rules (a libm call); the inputs here are never NaN.
inline double larger(double a, double b) { return a > b ? a : b; }

template <class Index>
constexpr uint32_t none_index() {
    return sizeof(Index) == 2 ? kNone16 : kNone32;
}

// Typed view of a store's cells.
template <class Index>
struct Cells {
    const Store::Impl& s;
    const CellRecord<Index>* records;
    explicit Cells(const Store::Impl& store) : s(store), records(static_cast<const CellRecord<Index>*>(store.cells)) {}

    uint32_t vertex(uint32_t cell, uint32_t slot) const { return records[cell].vertices[slot]; }
    uint32_t neighbour(uint32_t cell, uint32_t slot) const {
        const uint32_t n = records[cell].neighbours[slot];
        return n == none_index<Index>() ? kNoCell : n;
    }
    const float* position(uint32_t probe) const { return s.positions + 3 * size_t(probe); }
    const float* normal(uint32_t probe) const { return s.normals + 3 * size_t(probe); }

    uint32_t start_cell(const float p[3]) const {
        const StoreHeader& h = s.header;
        size_t slot = 0;
        for (int k = 2; k >= 0; --k) {
            const double extent = double(h.bounds_max[k]) - double(h.bounds_min[k]);
            uint32_t index = 0;
            if (extent > 0) {
                const double f = (double(p[k]) - double(h.bounds_min[k])) / extent * double(h.grid[k]);
                if (f >= double(h.grid[k]))
                    index = h.grid[k] - 1;
                else if (f > 0)
                    index = uint32_t(f);
            }
            slot = slot * h.grid[k] + index;
        }
        return static_cast<const Index*>(s.grid_cells)[slot];
    }
};

// An inner cell seen from the query: the orientations D[k] of the query with the facet opposite
// slot k (the cell with vertex k replaced by the query), their exact signs, and the verdict.
struct InnerView {
    enum Verdict { holds, flat, leaves } verdict;
    int exit = -1;     // leaves: the slot of the most negative orientation
    double D[4] = {0, 0, 0, 0};
    int sign[4] = {0, 0, 0, 0};
};

// d is the store's dimension, passed by a walk compiled for it (so that the other branches vanish).
template <class Index>
inline __attribute__((always_inline)) InnerView view_inner_cell(const Cells<Index>& cells, uint32_t cell, const float q[3],
                                                                uint32_t d) {
    const Store::Impl& s = cells.s;
    InnerView v;
    const float* P[4];
    for (uint32_t k = 0; k <= d; ++k) P[k] = cells.position(cells.vertex(cell, k));
    if (d == 3) {
        const Orientations o = ScalarOrientations::of(P, q);
        const double bound = o.bound;
        for (int k = 0; k < 4; ++k) v.D[k] = o.D[k];
        if ((v.D[0] > bound) & (v.D[1] > bound) & (v.D[2] > bound) & (v.D[3] > bound)) {  // the common case
            v.sign[0] = v.sign[1] = v.sign[2] = v.sign[3] = 1;
            v.verdict = InnerView::holds;
            return v;
        }
        bool uncertain = false;
        for (int k = 0; k < 4; ++k) {
            if (v.D[k] > bound) {
                v.sign[k] = 1;
            } else if (v.D[k] < -bound) {
                v.sign[k] = -1;
            } else {
                const float* w[4] = {P[0], P[1], P[2], P[3]};
                w[k] = q;
                v.sign[k] = orient3d_exact(w[0], w[1], w[2], w[3]);
                uncertain = true;
            }
        }
        // A held point the filter could not decide (on or near a facet, or in a sliver): its weights
        // from exact orientations, so that they keep double precision however thin the cell.
        if (uncertain && v.sign[0] >= 0 && v.sign[1] >= 0 && v.sign[2] >= 0 && v.sign[3] >= 0) {
            for (int k = 0; k < 4; ++k) {
                const float* w[4] = {P[0], P[1], P[2], P[3]};
                w[k] = q;
                v.D[k] = v.sign[k] > 0 ? orient3d_exact_value(w[0], w[1], w[2], w[3]) : 0.0;
            }
        }
    } else if (d == 2) {
        float uv[3][2], quv[2];
        project_to_plane(q, s.axis, quv);
        double a[3][2];
        double mu = 0, mv = 0;
        for (int i = 0; i < 3; ++i) {
            project_to_plane(P[i], s.axis, uv[i]);
            a[i][0] = double(uv[i][0]) - double(quv[0]);
            a[i][1] = double(uv[i][1]) - double(quv[1]);
            mu = larger(mu, std::fabs(a[i][0]));
            mv = larger(mv, std::fabs(a[i][1]));
        }
        auto cross = [&](int i, int j) { return a[i][0] * a[j][1] - a[j][0] * a[i][1]; };
        v.D[0] = cross(1, 2);
        v.D[1] = cross(2, 0);
        v.D[2] = cross(0, 1);
        const double bound = kOrient2dBoundScale * (mu * mv);
        bool uncertain = false;
        for (int k = 0; k < 3; ++k) {
            if (v.D[k] > bound) {
                v.sign[k] = 1;
            } else if (v.D[k] < -bound) {
                v.sign[k] = -1;
            } else {
                const float* w[3] = {uv[0], uv[1], uv[2]};
                w[k] = quv;
                v.sign[k] = orient2d_exact(w[0], w[1], w[2]);
                uncertain = true;
            }
        }
        if (uncertain && v.sign[0] >= 0 && v.sign[1] >= 0 && v.sign[2] >= 0) {
            for (int k = 0; k < 3; ++k) {
                const float* w[3] = {uv[0], uv[1], uv[2]};
                w[k] = quv;
                v.D[k] = v.sign[k] > 0 ? orient2d_exact_value(w[0], w[1], w[2]) : 0.0;
            }
        }
    } else if (d == 1) {
        // The difference of two floats in double has the exact sign.
        v.D[0] = double(P[1][s.axis]) - double(q[s.axis]);
        v.D[1] = double(q[s.axis]) - double(P[0][s.axis]);
        for (int k = 0; k < 2; ++k) v.sign[k] = v.D[k] > 0 ? 1 : (v.D[k] < 0 ? -1 : 0);
    } else {
        v.D[0] = 1;
        v.sign[0] = 1;
    }
    bool inside = true, any_positive = false;
    double most_negative = std::numeric_limits<double>::infinity();
    for (uint32_t k = 0; k <= d; ++k) {
        if (v.sign[k] < 0) {
            inside = false;
            // The most negative computed value among the exactly negative ones (any would do).
            if (v.exit < 0 || v.D[k] < most_negative) most_negative = v.D[k], v.exit = int(k);
        }
        any_positive |= v.sign[k] > 0;
    }
    v.verdict = inside ? (any_positive ? InnerView::holds : InnerView::flat) : InnerView::leaves;
    return v;
}

// Weights of a held point: the orientations over their sum, those of exact sign 0 exactly 0.
template <class Index>
inline __attribute__((always_inline)) void set_inner_weights(const Cells<Index>& cells, uint32_t cell, const InnerView& v,
                                                             Location& loc, uint32_t d) {
    const uint32_t used = d + 1;
    double w[4] = {0, 0, 0, 0}, sum = 0;
    for (uint32_t k = 0; k < used; ++k) {
        w[k] = v.sign[k] > 0 ? larger(v.D[k], 0.0) : 0.0;
        sum += w[k];
    }
    if (!(sum > 0)) {  // every positive orientation rounded to zero: share equally among them
        sum = 0;
        for (uint32_t k = 0; k < used; ++k) sum += w[k] = v.sign[k] > 0 ? 1.0 : 0.0;
    }
    const double scale = 1.0 / sum;
    for (uint32_t k = 0; k < 4; ++k) {
        loc.probes[k] = cells.vertex(cell, k < used ? k : 0);
        loc.weights[k] = k < used ? float(w[k] * scale) : 0.0f;
    }
    loc.cell = int32_t(cell);
    loc.kind = CellKind::inner;
}

}  // namespace tetprobe
