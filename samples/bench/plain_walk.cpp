#include "plain_walk.h"

#include "blob_sh.h"

#include "bench_timing.h"
#include "core/half.h"
#include "core/store_format.h"

#include <cmath>
#include <cstring>

namespace bench {
namespace {

using namespace tetprobe;

enum class Stop { inside, hull, gave_up };

// The walk: from `cell`, step across the facet of the most negative barycentric coordinate until
// none is negative. Leaves the final cell in *cell and its barycentrics in w.
inline Stop walk(const PlainWalkMesh& mesh, const float q[3], int32_t* cell, float w[4], uint32_t* steps) {
    int32_t c = *cell;
    for (uint32_t s = 0; s < kPlainWalkMaxSteps; ++s) {
        const PlainCell& pc = mesh.cells[size_t(c)];
        w[1] = pc.m[0][0] * q[0] + pc.m[0][1] * q[1] + pc.m[0][2] * q[2] + pc.m[0][3];
        w[2] = pc.m[1][0] * q[0] + pc.m[1][1] * q[1] + pc.m[1][2] * q[2] + pc.m[1][3];
        w[3] = pc.m[2][0] * q[0] + pc.m[2][1] * q[1] + pc.m[2][2] * q[2] + pc.m[2][3];
        w[0] = 1.0f - w[1] - w[2] - w[3];
        int k = 0;
        for (int i = 1; i < 4; ++i)
            if (w[i] < w[k]) k = i;
        if (w[k] >= 0.0f) {
            *cell = c, *steps = s;
            return Stop::inside;
        }
        const int32_t next = pc.neighbour[k];
        if (next < 0) {
            *cell = c, *steps = s;
            return Stop::hull;
        }
        c = next;
    }
    *cell = c, *steps = kPlainWalkMaxSteps;
    return Stop::gave_up;
}

inline void to_local(const PlainWalkMesh& mesh, const float* p, float q[3]) {
    for (int k = 0; k < 3; ++k) q[k] = float(double(p[k]) - mesh.origin[k]);
}

// Cell 0 as the start of frame 0 (the blob puts it near the centre of the cloud).
std::vector<int32_t> first_cells(const PlainWalkMesh& mesh, const ObjectPaths& paths) {
    std::vector<int32_t> cells(paths.objects, 0);
    for (size_t o = 0; o < paths.objects; ++o) {
        float q[3], w[4];
        uint32_t steps;
        to_local(mesh, paths.at(o, 0), q);
        walk(mesh, q, &cells[o], w, &steps);
    }
    return cells;
}

template <typename Index>
Index read_index(const uint8_t* base, size_t i) {
    Index v;
    std::memcpy(&v, base + i * sizeof(Index), sizeof v);
    return v;
}

}  // namespace

bool plain_walk_mesh_from_blob(const void* blob, size_t size, PlainWalkMesh* mesh, std::string* why) {
    const uint8_t* bytes = static_cast<const uint8_t*>(blob);
    if (size < kHeaderSize) return *why = "blob shorter than its header", false;
    StoreHeader h;
    std::memcpy(&h, bytes, sizeof h);
    if (h.format_version != kStoreFormatVersion) return *why = "not a blob of this format", false;
    if (h.layout != kLayoutFast) return *why = "the plain walk reads the fast layout's neighbours", false;
    if (h.position_encoding != kPositionsFloat32) return *why = "the plain walk reads float positions", false;
    if (h.dimension != 3) return *why = "the plain walk needs a 3-dimensional probe set", false;
    SectionEntry s[kSectionCount];
    std::memcpy(s, bytes + sizeof(StoreHeader), sizeof s);
    for (const SectionEntry& e : s)
        if (e.offset > size || e.size > size - e.offset) return *why = "section out of the blob", false;
    const bool wide = (h.flags & kFlagIndex32) != 0;
    const size_t index_bytes = wide ? 4 : 2;
    const uint32_t none = wide ? kNone32 : kNone16;
    if (s[kSectionPositions].size != 12ull * h.probe_count || s[kSectionCells].size != 8ull * index_bytes * h.cell_count ||
        h.inner_cell_count > h.cell_count)
        return *why = "section sizes do not match the header's counts", false;
    bench::BlobSh sh;
    if (!bench::read_blob_sh(blob, size, &sh)) return *why = "the plain walk reads half SH", false;

    for (int k = 0; k < 3; ++k) mesh->origin[k] = h.origin[k];
    mesh->sh = sh.sh;
    mesh->sh_stride = sh.stride;
    mesh->input_remap = std::move(sh.input_remap);

    const float* pos = reinterpret_cast<const float*>(bytes + s[kSectionPositions].offset);
    const uint8_t* cells = bytes + s[kSectionCells].offset;
    const auto index = [&](size_t i) -> uint32_t {
        return wide ? read_index<uint32_t>(cells, i) : read_index<uint16_t>(cells, i);
    };
    const uint32_t inner = h.inner_cell_count;
    mesh->cells.assign(inner, PlainCell{});
    mesh->vertices.resize(4ull * inner);
    for (uint32_t c = 0; c < inner; ++c) {
        double p[4][3];
        for (int k = 0; k < 4; ++k) {
            const uint32_t v = index(8ull * c + k);
            if (v >= h.probe_count) return *why = "inner cell with a vertex out of range", false;
            mesh->vertices[4ull * c + k] = v;
            for (int j = 0; j < 3; ++j) p[k][j] = pos[3ull * v + j];
            const uint32_t n = index(8ull * c + 4 + k);
            mesh->cells[c].neighbour[k] = (n == none || n >= inner) ? -1 : int32_t(n);
        }
        // Rows of the inverse of [p1-p0, p2-p0, p3-p0] (columns), by cofactors, in double.
        double e[3][3];
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) e[j][k] = p[k + 1][j] - p[0][j];
        const double c00 = e[1][1] * e[2][2] - e[1][2] * e[2][1], c01 = e[1][2] * e[2][0] - e[1][0] * e[2][2],
                     c02 = e[1][0] * e[2][1] - e[1][1] * e[2][0];
        const double det = e[0][0] * c00 + e[0][1] * c01 + e[0][2] * c02;
        if (det == 0.0) {
            // Flat in float32 (a sliver whose stored positions round onto one plane): a naive walk
            // has no answer here; it stops in such a cell with the weights (1, 0, 0, 0). Counted.
            ++mesh->flat_cells;
            continue;
        }
        const double inv[3][3] = {
            {c00 / det, (e[0][2] * e[2][1] - e[0][1] * e[2][2]) / det, (e[0][1] * e[1][2] - e[0][2] * e[1][1]) / det},
            {c01 / det, (e[0][0] * e[2][2] - e[0][2] * e[2][0]) / det, (e[0][2] * e[1][0] - e[0][0] * e[1][2]) / det},
            {c02 / det, (e[0][1] * e[2][0] - e[0][0] * e[2][1]) / det, (e[0][0] * e[1][1] - e[0][1] * e[1][0]) / det}};
        for (int k = 0; k < 3; ++k) {
            for (int j = 0; j < 3; ++j) mesh->cells[c].m[k][j] = float(inv[k][j]);
            mesh->cells[c].m[k][3] = float(-(inv[k][0] * p[0][0] + inv[k][1] * p[0][1] + inv[k][2] * p[0][2]));
        }
    }
    return true;
}

double plain_walk_run(const PlainWalkMesh& mesh, const ObjectPaths& paths, float* sink) {
    const std::vector<int32_t> start = first_cells(mesh, paths);
    float acc = 0;
    const Clock::time_point t0 = Clock::now();
    for (size_t o = 0; o < paths.objects; ++o) {
        int32_t cell = start[o];
        for (size_t f = 1; f < paths.frames; ++f) {
            float q[3], w[4], out[27];
            uint32_t steps;
            to_local(mesh, paths.at(o, f), q);
            walk(mesh, q, &cell, w, &steps);
            const uint32_t* v = &mesh.vertices[4 * size_t(cell)];
            const uint16_t* sh[4] = {mesh.sh + mesh.sh_stride * v[0], mesh.sh + mesh.sh_stride * v[1],
                                     mesh.sh + mesh.sh_stride * v[2], mesh.sh + mesh.sh_stride * v[3]};
            blend_sh_halves(sh, w, out);
            acc += out[0];
        }
    }
    const double seconds = seconds_since(t0);
    *sink += acc;
    return seconds;
}

PlainWalkCounts plain_walk_count(const PlainWalkMesh& mesh, const ObjectPaths& paths) {
    const std::vector<int32_t> start = first_cells(mesh, paths);
    PlainWalkCounts counts;
    for (size_t o = 0; o < paths.objects; ++o) {
        int32_t cell = start[o];
        for (size_t f = 1; f < paths.frames; ++f) {
            float q[3], w[4];
            uint32_t steps;
            to_local(mesh, paths.at(o, f), q);
            const Stop stop = walk(mesh, q, &cell, w, &steps);
            counts.steps += steps;
            counts.hull_stops += stop == Stop::hull;
            counts.gave_up += stop == Stop::gave_up;
        }
    }
    counts.steps /= double(paths.timed_queries());
    return counts;
}

}  // namespace bench
