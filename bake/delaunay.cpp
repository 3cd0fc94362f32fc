#include "bake/delaunay.h"

#include "bake/tetgen_guard.h"
#include "core/error.h"

#include <tetgen.h>

#include <cmath>
#include <memory>
#include <new>
#include <mutex>
#include <string>

namespace tetprobe {

namespace {

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

struct TetgenCall {
    const std::vector<Eigen::Vector3d>* points = nullptr;
    int rotation = 0;    // coordinates cycled this many times (an exact, orientation-keeping rotation)
    tetgenio* in = nullptr;
    tetgenio* out = nullptr;
    int error_code = 0;  // TetGen's int throw, if any
    bool out_of_memory = false;
};

// Allocates TetGen's input and output and runs it (inside the crash guard, so that what a crashed
// attempt allocated is all in one place).
void run_tetgen(void* context) {
    auto* call = static_cast<TetgenCall*>(context);
    try {
        const std::vector<Eigen::Vector3d>& points = *call->points;
        call->in = new tetgenio;
        call->out = new tetgenio;
        call->in->firstnumber = 0;
        call->in->numberofpoints = int(points.size());
        call->in->pointlist = new REAL[points.size() * 3];
        for (size_t i = 0; i < points.size(); ++i) {
            for (int a = 0; a < 3; ++a) call->in->pointlist[i * 3 + a] = points[i][(a + call->rotation) % 3];
        }
        // Q quiet, n neighbours, z zero-based, J keep every input point's number.
        tetrahedralize(const_cast<char*>("QnzJ"), call->in, call->out);
    } catch (int code) {
        call->error_code = code == 0 ? -1 : code;
    } catch (const std::bad_alloc&) {
        call->out_of_memory = true;  // nothing may unwind through the guard's handlers
    } catch (...) {
        call->error_code = -2;
    }
}

}  // namespace

SimplexMesh delaunay_tetrahedralize(const std::vector<Eigen::Vector3d>& points) {
    // Last line of defence: these inputs crash TetGen, so they must never reach it.
    if (points.size() < 4) throw Error(Status::internal, "tetrahedralization needs at least 4 points");
    for (const auto& p : points) {
        if (!p.allFinite()) throw Error(Status::internal, "non-finite point reached the tetrahedralization");
    }
    if (points.size() > size_t(INT32_MAX / 4)) throw Error(Status::invalid_argument, "too many points for TetGen");

    // TetGen sometimes dies on a set it handles fine with its axes cycled (an exact rotation that
    // keeps every tetrahedron's orientation), so a crash is contained and retried that way.
    TetgenCall call;
    bool survived = false;
    call.points = &points;
    for (int rotation = 0; rotation < 3 && !survived; ++rotation) {
        call.rotation = rotation;
        std::lock_guard<std::mutex> lock(tetgen_mutex());
        survived = call_guarded_against_crashes(&run_tetgen, &call);
        if (!survived) call.in = call.out = nullptr;  // leaked on purpose: TetGen died holding them
    }
    if (!survived) {
        throw Error(Status::tetgen, "TetGen crashed on this probe set (contained; tried 3 orientations)");
    }
    std::unique_ptr<tetgenio> in_owner(call.in), out_owner(call.out);
    if (call.out_of_memory) throw std::bad_alloc();
    if (call.error_code != 0) {
        throw Error(Status::tetgen, "TetGen failed with code " + std::to_string(call.error_code));
    }
    const tetgenio& out = *call.out;

    if (out.numberoftetrahedra <= 0 || !out.tetrahedronlist || !out.neighborlist || out.numberofcorners < 4) {
        throw Error(Status::tetgen, "TetGen returned no tetrahedra");
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
            if (v < 0 || size_t(v) >= points.size()) throw Error(Status::tetgen, "TetGen returned a bad vertex index");
            mesh.vertices[size_t(t)][size_t(k)] = uint32_t(v);
        }
    }
    // TetGen's own neighbour lists: each at the slot of the vertex it does not share, which is the
    // store's convention. TetGen 1.5 lists neighbour j opposite corner j, so the check is four
    // comparisons (the neighbour does not hold corner j); another order falls back to a search.
    for (int t = 0; t < count; ++t) {
        const int* cell = &out.tetrahedronlist[t * corners];
        for (int j = 0; j < 4; ++j) {
            const int n = out.neighborlist[t * 4 + j];
            if (n < 0) continue;
            if (n >= count) throw Error(Status::tetgen, "TetGen returned a bad neighbour index");
            const int* other = &out.tetrahedronlist[n * corners];
            const bool opposite_j = other[0] != cell[j] && other[1] != cell[j] && other[2] != cell[j] && other[3] != cell[j];
            const int slot = opposite_j ? j : slot_not_shared(cell, other);
            if (slot < 0) throw Error(Status::tetgen, "TetGen returned neighbours that share no facet");
            mesh.neighbours[size_t(t)][size_t(slot)] = uint32_t(n);
        }
    }
    return mesh;
}

}  // namespace tetprobe
