// Support for the exactness properties (test_exactness.cpp): building a store from a probe set,
// rotated and offset probe sets, and an exact referee that reads only a loaded Store (its stored
// float32 positions and cell vertices), never the library's own predicates or weights:
// - whether a cell holds a point: Shewchuk's orient3d (TetGen's copy), behind a long double filter
//   whose bound is many orders of magnitude above long double's rounding;
// - reference barycentrics: the four orientations in long double over their sum, from the same
//   float32 positions and the same float32 local query as the library uses.
#pragma once

#include "probe_families.h"

#include "bake/store_builder.h"
#include "capi/tetprobe.h"
#include "core/store.h"
#include "core/store_data.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

// TetGen 1.5's robust predicates (global functions in libtet; REAL is double).
void exactinit(int verbose, int noexact, int nofilter, double maxx, double maxy, double maxz);
double orient3dexact(double* pa, double* pb, double* pc, double* pd);

namespace exactness {

using tetprobe::Location;
using tetprobe::Store;

struct Built {
    tetprobe::StoreData data;
    std::unique_ptr<Store> store;
};

inline Built build(const families::ProbeSet& set, uint32_t flags, double merge_tolerance = 0,
                   const std::vector<float>* sh = nullptr) {
    tetprobe::BuildSettings settings;
    settings.flags = flags & ~uint32_t(TP_BUILD_COMPACT);
    settings.layout = (flags & TP_BUILD_COMPACT) ? tetprobe::kLayoutCompact : tetprobe::kLayoutFast;
    settings.merge_tolerance = merge_tolerance;
    Built b;
    b.data = tetprobe::build_store_data(set.positions.data(), 3 * sizeof(float), sh ? sh->data() : nullptr,
                                        27 * sizeof(float), set.count(), settings);
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(b.data);
    b.store = Store::load(blob.data(), blob.size());
    return b;
}

// An axis-aligned n^3 lattice of the given spacing at offset (every coordinate offset + k * spacing).
inline families::ProbeSet offset_lattice(int n, double spacing, double offset) {
    families::ProbeSet s{"lattice " + std::to_string(n) + "^3, spacing " + std::to_string(spacing) + " at offset " +
                             std::to_string(offset),
                         {}};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) s.add(offset + i * spacing, offset + j * spacing, offset + k * spacing);
    return s;
}

inline families::ProbeSet named(families::ProbeSet s, const std::string& name) {
    s.name = name;
    return s;
}

// The local position a query at world position w is decided at: exactly what the store computes
// (world minus origin in double, rounded to float). Read back through volatile (see test_locate.cpp:
// GCC's SLP vectoriser was seen to drop a rounding to float).
inline void local_of(const Store& store, const float world[3], float local[3]) {
    volatile float out[3];
    for (int a = 0; a < 3; ++a) out[a] = float(double(world[a]) - store.header().origin[a]);
    for (int a = 0; a < 3; ++a) local[a] = out[a];
}

// A world-space float query whose local position is (as near as float allows) the given local point.
inline void world_of(const Store& store, const double local[3], float world[3]) {
    volatile float out[3];
    for (int a = 0; a < 3; ++a) out[a] = float(store.header().origin[a] + local[a]);
    for (int a = 0; a < 3; ++a) world[a] = out[a];
}

inline bool is_inner(const Store& store, int32_t cell) {
    return cell >= 0 && uint32_t(cell) < store.header().inner_cell_count;
}

// The cell's four vertices' stored float positions.
inline void cell_positions(const Store& store, uint32_t cell, const float* P[4], uint32_t vertices[4]) {
    uint32_t neighbours[4];
    store.cell(cell, vertices, neighbours);
    for (int k = 0; k < 4; ++k) P[k] = store.probe_position(vertices[k]);
}

// Exact sign of det[b - a, c - a, d - a] (the library's orient3d convention): a long double
// evaluation where it is far beyond its rounding error, else TetGen's orient3dexact (float inputs
// are exact in double), whose sign convention is checked once on a known tetrahedron, not assumed.
inline int exact_orient(const float a[3], const float b[3], const float c[3], const float d[3]) {
    long double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = (long double)b[k] - a[k];
        v[k] = (long double)c[k] - a[k];
        w[k] = (long double)d[k] - a[k];
    }
    const long double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                            u[2] * (v[0] * w[1] - v[1] * w[0]);
    const long double permanent =
        std::fabs(u[0]) * (std::fabs(v[1] * w[2]) + std::fabs(v[2] * w[1])) +
        std::fabs(u[1]) * (std::fabs(v[0] * w[2]) + std::fabs(v[2] * w[0])) +
        std::fabs(u[2]) * (std::fabs(v[0] * w[1]) + std::fabs(v[1] * w[0]));
    // long double rounds at 2^-64 relative; 1e-15 of the permanent is ~1e4 times any possible error
    // (differences of floats that are more than 2^40 apart in exponent do not occur in these sets, but
    // even then the error stays far below this bound).
    if (det > 1e-15L * permanent) return 1;
    if (-det > 1e-15L * permanent) return -1;
    static const double convention = [] {
        exactinit(0, 0, 0, 1.0, 1.0, 1.0);
        double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, z[3] = {0, 0, 1};
        return orient3dexact(o, x, y, z) > 0 ? 1.0 : -1.0;  // sign of det[x, y, z] = +1
    }();
    double pa[3], pb[3], pc[3], pd[3];
    for (int k = 0; k < 3; ++k) pa[k] = a[k], pb[k] = b[k], pc[k] = c[k], pd[k] = d[k];
    const double r = convention * orient3dexact(pa, pb, pc, pd);
    return r > 0 ? 1 : (r < 0 ? -1 : 0);
}

// The exact signs of the orientations of q with the facets of a cell: sign[k] is the orientation of
// the cell with vertex k replaced by q (all positive: q strictly inside a positively oriented cell).
inline void exact_signs(const float* P[4], const float q[3], int sign[4]) {
    for (int k = 0; k < 4; ++k) {
        const float* w[4] = {P[0], P[1], P[2], P[3]};
        w[k] = q;
        sign[k] = exact_orient(w[0], w[1], w[2], w[3]);
    }
}

// Inner cell holds q (inside or on its boundary), exactly; the cell itself must be positively oriented.
inline bool cell_holds(const Store& store, uint32_t cell, const float q[3]) {
    const float* P[4];
    uint32_t v[4];
    cell_positions(store, cell, P, v);
    if (exact_orient(P[0], P[1], P[2], P[3]) <= 0) return false;
    int sign[4];
    exact_signs(P, q, sign);
    return sign[0] >= 0 && sign[1] >= 0 && sign[2] >= 0 && sign[3] >= 0;
}

// Whether any inner cell holds q exactly (O(cells)).
inline bool any_inner_cell_holds(const Store& store, const float q[3]) {
    for (uint32_t c = 0; c < store.header().inner_cell_count; ++c)
        if (cell_holds(store, c, q)) return true;
    return false;
}

// Reference barycentrics of q in inner cell `cell` (slot order), in long double from the stored
// floats; weights of exact sign 0 are exactly 0.
inline void reference_weights(const Store& store, uint32_t cell, const float q[3], long double w[4]) {
    const float* P[4];
    uint32_t v[4];
    cell_positions(store, cell, P, v);
    int sign[4];
    exact_signs(P, q, sign);
    long double D[4], sum = 0;
    for (int k = 0; k < 4; ++k) {
        const float* x[4] = {P[0], P[1], P[2], P[3]};
        x[k] = q;
        long double a[3][3];
        for (int i = 1; i < 4; ++i)
            for (int c = 0; c < 3; ++c) a[i - 1][c] = (long double)x[i][c] - x[0][c];
        D[k] = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        if (sign[k] == 0) D[k] = 0;
        sum += D[k];
    }
    for (int k = 0; k < 4; ++k) w[k] = D[k] / sum;
}

// Stored probe -> weight, zero weights dropped.
inline std::map<uint32_t, float> weight_map(const Location& loc) {
    std::map<uint32_t, float> m;
    for (int k = 0; k < 4; ++k)
        if (loc.weights[k] != 0) m[loc.probes[k]] += loc.weights[k];
    return m;
}

inline std::string describe(const Location& loc) {
    std::ostringstream out;
    out.precision(9);
    out << "cell " << loc.cell << (loc.kind == tetprobe::CellKind::inner ? " inner" : " outer") << " status "
        << int(loc.status) << " fallback " << loc.fallback << " steps " << loc.steps << " probes/weights:";
    for (int k = 0; k < 4; ++k) out << " " << loc.probes[k] << ":" << loc.weights[k];
    return out.str();
}

inline std::string describe_point(const float p[3]) {
    std::ostringstream out;
    out.precision(9);
    out << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    return out.str();
}

}  // namespace exactness
