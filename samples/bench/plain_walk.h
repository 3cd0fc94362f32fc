// The "naive implementation" peer of the store benchmark: a plain, non-robust visibility walk over
// the store's own inner cells with float barycentric matrices, then the same half-SH blend as the
// floor. No tolerance, no exact predicates, no outer cells: a walk that reaches the hull stops in the
// cell it is in; one that does not settle within kPlainWalkMaxSteps gives up (both are counted).
// Built from a fast-layout format-3 blob (tp_store_blob): its positions, cells and neighbours,
// origin, SH section and input remap; the matrices are computed here, in double, stored as float.
#pragma once

#include "query_sets.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

constexpr uint32_t kPlainWalkMaxSteps = 10000;

// What one step reads, in one 64-byte line: b_k(p) = m[k-1] . (x, y, z, 1) for k = 1..3,
// b_0 = 1 - b_1 - b_2 - b_3; neighbour k (across the facet opposite vertex k) or -1 beyond the hull.
struct alignas(64) PlainCell {
    float m[3][4];
    int32_t neighbour[4];
};

struct PlainWalkMesh {
    double origin[3] = {0, 0, 0};        // queries are world positions; cells are in local units
    std::vector<PlainCell> cells;        // inner cells only, in the blob's order
    std::vector<uint32_t> vertices;      // 4 stored-probe indices per inner cell
    const uint16_t* sh = nullptr;        // the blob's SH section (valid while the store lives)
    size_t sh_stride = 0;                // halves per probe
    std::vector<uint32_t> input_remap;   // input probe -> stored probe
    size_t flat_cells = 0;               // inner cells of zero volume in float32 (all-zero matrix)
};

// Reads a fast-layout, 3-dimensional format-3 blob. False with *why set if the blob is not one.
bool plain_walk_mesh_from_blob(const void* blob, size_t size, PlainWalkMesh* mesh, std::string* why);

struct PlainWalkCounts {
    double steps = 0;       // mean cells stepped per timed query
    size_t hull_stops = 0;  // walks that stopped at the hull (a float slip; the points are inside)
    size_t gave_up = 0;     // walks that hit kPlainWalkMaxSteps
};

// One timed run over the objects' paths (object by object, each carrying its own cell from the last
// frame; frame 0 untimed): walk + weights + blend. Returns seconds; *sink receives a checksum.
double plain_walk_run(const PlainWalkMesh& mesh, const ObjectPaths& paths, float* sink);

// Counts steps, hull stops and give-ups over the same queries (untimed).
PlainWalkCounts plain_walk_count(const PlainWalkMesh& mesh, const ObjectPaths& paths);

}  // namespace bench
