#include "core/leak_control.h"

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

}  // namespace

void weigh_by_visibility(const Store::Impl& s, Location& loc) {
    double factor[4] = {1, 1, 1, 1};
    bool blocked = false;
    for (int i = 0; i < 4; ++i) {
        for (int j = i + 1; j < 4; ++j) {
            const uint32_t pi = loc.probes[i], pj = loc.probes[j];
            if (pi == pj) continue;  // unused slots repeat slot 0
            const bool i_low = pi < pj;
            const LeakEdge* edge = blocked_edge(s, i_low ? pi : pj, i_low ? pj : pi);
            if (!edge) continue;
            blocked = true;
            const int low = i_low ? i : j, high = i_low ? j : i;
            const double wa = loc.weights[low], wb = loc.weights[high];
            // Where the query projects onto the edge, 0 at the low probe (0 when both weights vanish:
            // their product with any factor is 0 then).
            const double t = wa + wb > 0 ? wb / (wa + wb) : 0.0;
            const double high_visible = smoothstep((t - edge->start) / (double(edge->end) - edge->start));
            factor[high] *= high_visible;
            factor[low] *= 1.0 - high_visible;
        }
    }
    if (!blocked) return;
    double scaled[4], total = 0, scaled_total = 0;
    for (int k = 0; k < 4; ++k) {
        scaled[k] = double(loc.weights[k]) * (factor[k] + kLeakFloor);
        total += loc.weights[k];
        scaled_total += scaled[k];
    }
    if (!(scaled_total > 0)) return;  // weights of a validated store sum to 1; kept for safety
    // Divided last, so that a query at a probe (one scaled weight equal to the total) gets exactly 1.
    for (int k = 0; k < 4; ++k) loc.weights[k] = float(scaled[k] * total / scaled_total);
}

}  // namespace tetprobe
