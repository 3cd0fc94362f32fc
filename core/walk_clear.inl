// The lean walks over tetrahedra, included by walk.cpp once per instruction set (the AVX2 one inside
// a region compiled for that target, so that its kernels inline): TP_WALK_CLEAR_NAME and
// TP_LOCATE_BATCH_NAME are the functions' names, TP_WALK_CLEAR_KERNEL the orientation kernel of one
// cell, TP_LANE_KERNEL that of four queries' cells at once (tetrahedron_orientations.h), and
// TP_WALK_AVX2 the general walk's instruction set, TP_WALK_TARGET the functions' target attribute.
//
// The common case, kept lean: the walk over tetrahedra while the filter decides. A cell whose four
// orientations are all certainly positive holds the query (weights D / sum D); a cell with a
// certainly negative one is left across the most negative (any facet the query is strictly beyond
// is a valid visibility step). Returns true with loc filled when answered; false with *cell where
// the general walk must take over (an uncertain sign, the hull, an outer cell, or the step cap).
template <class Index>
TP_WALK_TARGET __attribute__((noinline)) bool TP_WALK_CLEAR_NAME(const Cells<Index>& cells, uint32_t* cell, const float q[3],
                                                  uint32_t* steps, uint32_t step_cap, Location& loc) {
    const uint32_t inner = cells.s.inner_cell_count;
    uint32_t c = *cell;
    if (c < inner) {
        // The start cell is usually the answer: ask for its probes' SH while the orientations compute.
        const CellRecord<Index>& r = cells.records[c];
        for (int k = 0; k < 4; ++k) __builtin_prefetch(cells.s.sh + size_t(r.vertices[k]) * cells.s.sh_stride);
    }
    while (c < inner && *steps <= step_cap) {
        const CellRecord<Index>& r = cells.records[c];
        const float* const P[4] = {cells.position(r.vertices[0]), cells.position(r.vertices[1]),
                                   cells.position(r.vertices[2]), cells.position(r.vertices[3])};
        const Orientations o = TP_WALK_CLEAR_KERNEL::of(P, q);
        const double* D = o.D;
        if ((D[0] > o.bound) & (D[1] > o.bound) & (D[2] > o.bound) & (D[3] > o.bound)) {
            const double scale = 1.0 / (D[0] + D[1] + D[2] + D[3]);
            loc.status = Status::ok;
            loc.cell = int32_t(c);
            loc.kind = CellKind::inner;
            loc.steps = *steps;
            loc.fallback = false;
            loc.searched = 0;
            loc.t = 0;
            for (int k = 0; k < 4; ++k) {
                loc.probes[k] = r.vertices[k];
                loc.weights[k] = float(D[k] * scale);
            }
            return true;
        }
        int exit = 0;
        for (int k = 1; k < 4; ++k) exit = D[k] < D[exit] ? k : exit;
        const uint32_t next = r.neighbours[exit];
        if (!(D[exit] < -o.bound) || next == none_index<Index>()) break;
        c = next;
        ++*steps;
    }
    *cell = c;
    return false;
}

// The batch walk: up to kLanes queries walk at once, each step computing the orientations of every
// walking query's cell together (four queries' cells per kernel call, structure of arrays), so the
// arithmetic runs side by side and the loads of different queries overlap. A query leaves its lane
// when it is answered or needs the general walk (the same cell and step count walk_clear would hand
// over), and the next query of the batch takes the lane. The same steps as walk_clear, with the same
// operations on the same values: the same cells and weights, bit for bit.
template <class Index>
TP_WALK_TARGET __attribute__((noinline)) void TP_LOCATE_BATCH_NAME(const Cells<Index>& cells, size_t count, const float (*q)[3],
                                                    const int32_t* hints, Location* out) {
    constexpr int kLanes = 8;
    const Store::Impl& s = cells.s;
    const uint32_t inner = s.inner_cell_count;
    const uint32_t step_cap = walk_step_cap(s);
    size_t next_query = 0;
    uint32_t lane_query[kLanes], lane_cell[kLanes], lane_steps[kLanes];
    // Starts the next query that begins in an inner cell in lane (the others walk on their own).
    auto start = [&](int lane) {
        while (next_query < count) {
            const size_t i = next_query++;
            const int32_t hint = hints[i];
            const uint32_t cell = (hint >= 0 && uint32_t(hint) < s.cell_count) ? uint32_t(hint) : cells.start_cell(q[i]);
            if (cell < inner) {
                const CellRecord<Index>& r = cells.records[cell];
                for (int k = 0; k < 4; ++k) __builtin_prefetch(s.sh + size_t(r.vertices[k]) * s.sh_stride);
                lane_query[lane] = uint32_t(i);
                lane_cell[lane] = cell;
                lane_steps[lane] = 0;
                return true;
            }
            walk_general<Index, 3, TP_WALK_AVX2>(s, q[i], cell, 0, out[i]);
        }
        return false;
    };
    int lanes = 0;
    while (lanes < kLanes && start(lanes)) ++lanes;
    while (lanes > 0) {
        LaneOrientations o[kLanes / 4];
        for (int group = 0; 4 * group < lanes; ++group) {
            const float* P[4][4];
            const float* Q[4];
            for (int l = 0; l < 4; ++l) {
                const int lane = 4 * group + l < lanes ? 4 * group + l : 4 * group;  // idle lanes repeat a walking one
                const CellRecord<Index>& r = cells.records[lane_cell[lane]];
                for (int k = 0; k < 4; ++k) P[l][k] = cells.position(r.vertices[k]);
                Q[l] = q[lane_query[lane]];
            }
            TP_LANE_KERNEL::of(P, Q, o[group]);
        }
        // Backwards, so that the last lane, moved into a finished one, has had its step.
        for (int lane = lanes - 1; lane >= 0; --lane) {
            const LaneOrientations& g = o[lane / 4];
            const int l = lane % 4;
            const double D[4] = {g.D[0][l], g.D[1][l], g.D[2][l], g.D[3][l]};
            const double bound = g.bound[l];
            const uint32_t c = lane_cell[lane];
            const size_t i = lane_query[lane];
            const CellRecord<Index>& r = cells.records[c];
            bool finished = true;
            if ((D[0] > bound) & (D[1] > bound) & (D[2] > bound) & (D[3] > bound)) {
                const double scale = 1.0 / (D[0] + D[1] + D[2] + D[3]);
                Location& loc = out[i];
                loc.status = Status::ok;
                loc.cell = int32_t(c);
                loc.kind = CellKind::inner;
                loc.steps = lane_steps[lane];
                loc.fallback = false;
                loc.searched = 0;
                loc.t = 0;
                for (int k = 0; k < 4; ++k) {
                    loc.probes[k] = r.vertices[k];
                    loc.weights[k] = float(D[k] * scale);
                }
            } else {
                int exit = 0;
                for (int k = 1; k < 4; ++k) exit = D[k] < D[exit] ? k : exit;
                const uint32_t next = r.neighbours[exit];
                if (!(D[exit] < -bound) || next == none_index<Index>()) {
                    walk_general<Index, 3, TP_WALK_AVX2>(s, q[i], c, lane_steps[lane], out[i]);
                } else {
                    const uint32_t steps = ++lane_steps[lane];
                    lane_cell[lane] = next;
                    if (next >= inner || steps > step_cap)
                        walk_general<Index, 3, TP_WALK_AVX2>(s, q[i], next, steps, out[i]);
                    else
                        finished = false;
                }
            }
            if (finished && !start(lane)) {
                --lanes;
                lane_query[lane] = lane_query[lanes];
                lane_cell[lane] = lane_cell[lanes];
                lane_steps[lane] = lane_steps[lanes];
            }
        }
    }
}
