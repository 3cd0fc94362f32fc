// The exact peer of the store benchmark: CGAL's Delaunay_triangulation_3 (Exact_predicates_
// inexact_constructions_kernel) on the same probes, `locate(p, hint)` with the object's previous cell
// as hint, barycentric weights in double from the located cell, then the same half-SH blend as the
// floor. CGAL is optional and lives only in this benchmark: without it (TETPROBE_BENCH_CGAL unset)
// cgal_peer_available() is false and the peer is skipped.
#pragma once

#include "query_sets.h"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace bench {

bool cgal_peer_available();

class CgalPeer {
public:
    // Triangulates count world positions (3 floats each); vertex info i is probe_of[i], the index
    // whose SH the blend reads (sh + sh_stride * probe_of[i], 27 halves). Null without CGAL.
    static std::unique_ptr<CgalPeer> build(const float* positions, const uint32_t* probe_of, size_t count,
                                           const uint16_t* sh, size_t sh_stride);
    ~CgalPeer();

    // One timed run over the objects' paths (object by object, each with its own hint cell from
    // the last frame; frame 0 untimed): locate + weights + blend. Returns seconds; *sink receives a
    // checksum. *outside counts queries that landed in an infinite cell (none expected).
    double run(const ObjectPaths& paths, float* sink, size_t* outside = nullptr) const;

    // Locate + weights in double, no blend (the locate benchmark): over the objects' paths, each object
    // with its own hint (frame 0 untimed), or over points with the hint of the previous point
    // (carry_hint) or none (CGAL then starts from a cell of its own choosing). Returns seconds.
    double locate_paths(const ObjectPaths& paths, float* sink) const;
    double locate_points(const float* points, size_t count, bool carry_hint, float* sink) const;

private:
    struct Impl;
    explicit CgalPeer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace bench
