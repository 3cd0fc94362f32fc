#include "core/leak_control.h"

#include <algorithm>

namespace tetprobe {

namespace {

// The ramp of the blocked pair (a, b), a < b, or null when they see each other.
const LeakEdge* blocked_edge(const Store::Impl& s, uint32_t a, uint32_t b) {
    const uint32_t end = s.leak_offsets[a + 1];
    for (uint32_t i = s.leak_offsets[a]; i < end; ++i) {
        const uint32_t partner = s.leak_edges[i].partner;
        if (partner == b) return &s.leak_edges[i];
        if (partner > b) break;  // increasing within a list
    }
    return nullptr;
}

double smoothstep(double x) {
    x = x < 0 ? 0 : (x > 1 ? 1 : x);
    return x * x * (3 - 2 * x);
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
                    blocked_edge(s, std::min(probes[i], probes[j]), std::max(probes[i], probes[j])))
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

void weigh_by_visibility(const Store::Impl& s, Location& loc) {
    if (loc.cell < 0 || !s.leak_cells.get()[loc.cell]) return;
    // Per slot: the weight of its blocked partners in the cell, and their ramps (oriented away from
    // the slot's probe) summed with those weights.
    double behind[4] = {0, 0, 0, 0}, ramp_start[4] = {0, 0, 0, 0}, ramp_end[4] = {0, 0, 0, 0};
    bool blocked = false;
    for (int i = 0; i < 4; ++i) {
        for (int j = i + 1; j < 4; ++j) {
            const uint32_t pi = loc.probes[i], pj = loc.probes[j];
            if (pi == pj) continue;  // unused slots repeat slot 0
            const int low = pi < pj ? i : j, high = pi < pj ? j : i;
            const LeakEdge* edge = blocked_edge(s, loc.probes[low], loc.probes[high]);
            if (!edge) continue;
            blocked = true;
            const double w_low = loc.weights[low], w_high = loc.weights[high];
            behind[low] += w_high;
            ramp_start[low] += w_high * edge->start;
            ramp_end[low] += w_high * edge->end;
            behind[high] += w_low;
            ramp_start[high] += w_low * (1.0 - edge->end);
            ramp_end[high] += w_low * (1.0 - edge->start);
        }
    }
    if (!blocked) return;
    double total = 0;
    for (int k = 0; k < 4; ++k) total += loc.weights[k];
    if (!(total > 0)) return;  // weights of a validated store sum to 1; kept for safety
    double scaled[4], scaled_total = 0;
    for (int k = 0; k < 4; ++k) {
        double visible = 1;
        if (behind[k] > 0) {
            // How far the query has gone towards the probes this one cannot see (0 at this probe, 1 at
            // them), against the weighted ramp: past it, the query is on their side of the wall.
            const double t = behind[k] / total;
            const double start = ramp_start[k] / behind[k], end = ramp_end[k] / behind[k];
            // Every ramp is wider than zero, but their average may round to none: a step then.
            const double x = end > start ? (t - start) / (end - start) : (t > start ? 1.0 : 0.0);
            visible = 1.0 - smoothstep(x);
        }
        scaled[k] = double(loc.weights[k]) * (visible + kLeakFloor);
        scaled_total += scaled[k];
    }
    // Divided last, so that a query at a probe (one scaled weight equal to the total) gets exactly 1.
    for (int k = 0; k < 4; ++k) loc.weights[k] = float(scaled[k] * total / scaled_total);
}

}  // namespace tetprobe
