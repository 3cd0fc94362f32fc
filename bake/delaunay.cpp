#include "bake/delaunay.h"

#include "core/error.h"

#include <tetgen.h>

#include <cmath>
#include <mutex>
#include <string>

namespace tetprobe {

namespace {

std::mutex& tetgen_mutex() {
    static std::mutex mutex;
    return mutex;
}

// Slot of `cell` whose vertex does not appear in `other` (the shared facet is opposite it), or -1.
int slot_not_shared(const int* cell, const int* other) {
    int found = -1;
    for (int k = 0; k < 4; ++k) {
        bool shared = false;
        for (int j = 0; j < 4; ++j) shared = shared || cell[k] == other[j];
        if (!shared) {
            if (found >= 0) return -1;
            found = k;
        }
    }
    return found;
}

}  // namespace

SimplexMesh delaunay_tetrahedralize(const std::vector<Eigen::Vector3d>& points) {
    // Last line of defence: these inputs crash TetGen, so they must never reach it.
    if (points.size() < 4) throw Error(TP_ERROR_INTERNAL, "tetrahedralization needs at least 4 points");
    for (const auto& p : points) {
        if (!p.allFinite()) throw Error(TP_ERROR_INTERNAL, "non-finite point reached the tetrahedralization");
    }
    if (points.size() > size_t(INT32_MAX / 4)) throw Error(TP_ERROR_INVALID_ARGUMENT, "too many points for TetGen");

    tetgenio in, out;
    in.firstnumber = 0;
    in.numberofpoints = int(points.size());
    in.pointlist = new REAL[points.size() * 3];
    for (size_t i = 0; i < points.size(); ++i) {
        for (int a = 0; a < 3; ++a) in.pointlist[i * 3 + a] = points[i][a];
    }

    {
        // Q quiet, n neighbours, z zero-based, J keep every input point's number.
        std::lock_guard<std::mutex> lock(tetgen_mutex());
        try {
            tetrahedralize(const_cast<char*>("QnzJ"), &in, &out);
        } catch (int code) {
            throw Error(TP_ERROR_TETGEN, "TetGen failed with code " + std::to_string(code));
        }
    }

    if (out.numberoftetrahedra <= 0 || !out.tetrahedronlist || !out.neighborlist || out.numberofcorners < 4) {
        throw Error(TP_ERROR_TETGEN, "TetGen returned no tetrahedra");
    }
    SimplexMesh mesh;
    mesh.dimension = 3;
    const int count = out.numberoftetrahedra;
    const int corners = out.numberofcorners;
    mesh.vertices.resize(size_t(count));
    mesh.neighbours.assign(size_t(count), kNoSlots);
    for (int t = 0; t < count; ++t) {
        for (int k = 0; k < 4; ++k) {
            const int v = out.tetrahedronlist[t * corners + k];
            if (v < 0 || size_t(v) >= points.size()) throw Error(TP_ERROR_TETGEN, "TetGen returned a bad vertex index");
            mesh.vertices[size_t(t)][size_t(k)] = uint32_t(v);
        }
    }
    // TetGen lists four neighbours per tetrahedron; place each at the slot of the vertex it does not
    // share, which is the store's convention whatever TetGen's own order.
    for (int t = 0; t < count; ++t) {
        const int* cell = &out.tetrahedronlist[t * corners];
        for (int j = 0; j < 4; ++j) {
            const int n = out.neighborlist[t * 4 + j];
            if (n < 0) continue;
            if (n >= count) throw Error(TP_ERROR_TETGEN, "TetGen returned a bad neighbour index");
            const int slot = slot_not_shared(cell, &out.tetrahedronlist[n * corners]);
            if (slot < 0) throw Error(TP_ERROR_TETGEN, "TetGen returned neighbours that share no facet");
            mesh.neighbours[size_t(t)][size_t(slot)] = uint32_t(n);
        }
    }
    return mesh;
}

}  // namespace tetprobe
