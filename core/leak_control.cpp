#include "core/leak_control.h"

#include "core/error.h"
#include "core/leak_plane.h"

#include <algorithm>
#include <string>

namespace tetprobe {

namespace {

const LeakPlane* planes(const Store::Impl& s) { return reinterpret_cast<const LeakPlane*>(s.leak_planes.get()); }

// Exact side of `point` against one side's wall plane of blocked edge i.
int side_of(const Store::Impl& s, uint32_t i, int side, const float point[3]) {
    const LeakPlane& p = planes(s)[2 * size_t(i) + size_t(side)];
    return leak_plane_side(p, point);
}

// The index of the blocked pair (a, b), a < b, in leak_edges, or -1 when they see each other.
int64_t blocked_edge(const Store::Impl& s, uint32_t a, uint32_t b) {
    const uint32_t end = s.leak_offsets[a + 1];
    for (uint32_t i = s.leak_offsets[a]; i < end; ++i) {
        const uint32_t partner = s.leak_edges[i].partner;
        if (partner == b) return i;
        if (partner > b) break;  // increasing within a list
    }
    return -1;
}

template <class Index>
void mark_cells(Store::Impl& s) {
    const auto* records = static_cast<const CellRecord<Index>*>(s.cells);
    uint8_t* blocked = s.leak_cells.get();
    for (uint32_t c = 0; c < s.cell_count; ++c) {
        uint32_t probes[4];
        int used = 0;
        for (int k = 0; k < 4; ++k) {
            const uint32_t v = records[c].vertices[k];
            if (v < s.probe_count) probes[used++] = v;  // reserved values (outer, none) are above any probe
        }
        blocked[c] = 0;
        for (int i = 0; i < used; ++i)
            for (int j = i + 1; j < used; ++j)
                if (probes[i] != probes[j] &&
                    blocked_edge(s, std::min(probes[i], probes[j]), std::max(probes[i], probes[j])) >= 0)
                    blocked[c] = 1;
    }
}

}  // namespace

void mark_blocked_cells(Store::Impl& s) {
    s.leak_cells = aligned_bytes(s.cell_count);
    if (s.index32)
        mark_cells<uint32_t>(s);
    else
        mark_cells<uint16_t>(s);
}

void decode_leak_planes(Store::Impl& s) {
    const uint32_t edges = s.leak_offsets[s.probe_count];
    s.leak_planes = aligned_bytes(std::max<size_t>(1, 2 * size_t(edges) * sizeof(LeakPlane)));
    LeakPlane* out = reinterpret_cast<LeakPlane*>(s.leak_planes.get());
    for (uint32_t i = 0; i < edges; ++i)
        for (int side = 0; side < 2; ++side) {
            const LeakEdge& e = s.leak_edges[i];
            const int16_t code[2] = {e.normal[side][0], e.normal[side][1]};
            LeakPlane& p = out[2 * size_t(i) + size_t(side)];
            leak_plane_normal(code, p.normal);
            p.offset = e.offset[side];
        }
}

void check_leak_planes(const Store::Impl& s) {
    for (uint32_t a = 0; a < s.probe_count; ++a) {
        for (uint32_t i = s.leak_offsets[a]; i < s.leak_offsets[a + 1]; ++i) {
            const LeakEdge& e = s.leak_edges[i];
            const float* pa = s.positions + 3 * size_t(a);
            const float* pb = s.positions + 3 * size_t(e.partner);
            if (side_of(s, i, 0, pa) <= 0 || side_of(s, i, 0, pb) >= 0 || side_of(s, i, 1, pb) <= 0 ||
                side_of(s, i, 1, pa) >= 0)
                throw Error(Status::invalid_blob, "invalid store blob: leak_edges[" + std::to_string(i) +
                                                      "] has a wall plane that does not separate probes " +
                                                      std::to_string(a) + " and " + std::to_string(e.partner));
        }
    }
}

void weigh_by_visibility(const Store::Impl& s, const float local[3], Location& loc) {
    if (loc.cell < 0 || !s.leak_cells.get()[loc.cell]) return;
    // Per slot: the share of the query's weight held by the partners its probe is hidden from, each over
    // where its wall crosses their edge.
    double hidden[4] = {0, 0, 0, 0};
    bool blocked = false;
    for (int i = 0; i < 4; ++i) {
        for (int j = i + 1; j < 4; ++j) {
            const uint32_t pi = loc.probes[i], pj = loc.probes[j];
            if (pi == pj) continue;  // unused slots repeat slot 0
            const int low = pi < pj ? i : j, high = pi < pj ? j : i;
            const int64_t edge = blocked_edge(s, loc.probes[low], loc.probes[high]);
            if (edge < 0) continue;
            blocked = true;
            const int slots[2] = {low, high};
            for (int side = 0; side < 2; ++side) {
                if (side_of(s, uint32_t(edge), side, local) > 0) continue;  // in front
                // Behind this probe's wall: hidden by the partner's weight over where the wall crosses.
                const double reach = s.leak_edges[edge].reach[side];
                const double share = double(loc.weights[slots[1 - side]]) * 65535.0 / reach;
                if (share > 0) hidden[slots[side]] += share;
            }
        }
    }
    if (!blocked) return;
    double total = 0;
    for (int k = 0; k < 4; ++k) total += loc.weights[k];
    if (!(total > 0)) return;  // weights of a validated store sum to 1; kept for safety
    double scaled[4], scaled_total = 0;
    for (int k = 0; k < 4; ++k) {
        const double visible = hidden[k] < 1 ? 1 - hidden[k] : 0.0;
        scaled[k] = double(loc.weights[k]) * (visible + kLeakFloor);
        scaled_total += scaled[k];
    }
    // Divided last, so that a query at a probe (one scaled weight equal to the total) gets exactly 1.
    for (int k = 0; k < 4; ++k) loc.weights[k] = float(scaled[k] * total / scaled_total);
}

}  // namespace tetprobe
