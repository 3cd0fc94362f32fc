// The lane walk: eight queries walk at once, structure of arrays (lane_orientations.h), each lane taking
// the same steps as the lean walk (walk_clear.inl) would for its query, so that it ends in the same cell
// with the same weights, bit for bit, or hands the general walk the same cell and step count. Included by
// walk.cpp once per instruction set after walk_clear.inl, with the same macros and TP_LANE_KERNEL the lane
// orientation kernel.
//
// Each round computes the orientations of every lane's current cell together (gathered from the lanes'
// records, one vector per coordinate); then, lane by lane, a held query is blended and its lane takes the
// next query, a query the filter proves beyond a facet steps across it and stays, and any other goes to the
// general walk. The lanes' loads are independent, so the CPU overlaps them (the lean walk's are one
// dependent chain per query).
//
// Feed, what the lanes walk (a batch's queries in order):
//   bool next(int lane, const float** q, int32_t* hint): the lane's next query and its hint, false at the end;
//   void held(int lane, uint32_t cell, const uint8_t* const records[4], const float weights[4]): its answer
//     from the lean walk (records: the four probes' SH records; cell: the next hint);
//   void general(int lane, const Location& loc): its answer from the general walk.
template <class Index, class Feed>
TP_WALK_TARGET inline __attribute__((always_inline)) void TP_WALK_ISA(walk_lanes)(const Store::Impl& s, Feed& feed) {
    const Cells<Index> cells(s);
    const uint32_t inner = s.inner_cell_count;
    const uint32_t step_cap = walk_step_cap(s);
    const float* q[kLanes];
    uint32_t cell[kLanes], steps[kLanes];
    // The lane's next query that starts in an inner cell (those that do not are the general walk's at once,
    // as the lean walk hands them over without a step).
    auto start = [&](int lane) {
        const float* p;
        int32_t hint;
        while (feed.next(lane, &p, &hint)) {
            const uint32_t c = start_of(cells, p, hint);
            if (c < inner) {
                const CellRecord<Index>& r = cells.records[c];
                for (int k = 0; k < 4; ++k) __builtin_prefetch(s.sh + size_t(r.vertices[k]) * s.sh_stride);
                q[lane] = p;
                cell[lane] = c;
                steps[lane] = 0;
                return true;
            }
            Location loc;
            walk_general<Index, 3, TP_WALK_AVX2>(s, p, c, 0, loc);
            feed.general(lane, loc);
        }
        return false;
    };
    unsigned live = 0;
    for (int lane = 0; lane < kLanes; ++lane)
        if (start(lane)) live |= 1u << lane;
    LaneBlock b;
    while (live) {
        const float* P[kLanes][4];
        const float* Q[kLanes];
        const int any = __builtin_ctz(live);
        for (int lane = 0; lane < kLanes; ++lane) {
            const int l = (live >> lane) & 1 ? lane : any;  // an idle lane repeats a walking one
            const CellRecord<Index>& r = cells.records[cell[l]];
            for (int k = 0; k < 4; ++k) P[lane][k] = cells.position(r.vertices[k]);
            Q[lane] = q[l];
        }
        TP_LANE_KERNEL::of(P, Q, b);
        for (unsigned m = live; m; m &= m - 1) {
            const int lane = __builtin_ctz(m);
            const uint32_t c = cell[lane];
            const CellRecord<Index>& r = cells.records[c];
            if ((b.held >> lane) & 1) {
                const uint8_t* const records[4] = {
                    s.sh + size_t(r.vertices[0]) * s.sh_stride, s.sh + size_t(r.vertices[1]) * s.sh_stride,
                    s.sh + size_t(r.vertices[2]) * s.sh_stride, s.sh + size_t(r.vertices[3]) * s.sh_stride};
                feed.held(lane, c, records, b.weights[lane]);
            } else {
                int exit = 0;
                for (int k = 1; k < 4; ++k) exit = b.D[k][lane] < b.D[exit][lane] ? k : exit;
                const uint32_t next = r.neighbours[exit];
                uint32_t at = c;
                if ((b.D[exit][lane] < -b.bound[lane]) && next != none_index<Index>()) {  // a step, as the lean walk's
                    at = next;
                    ++steps[lane];
                    if (next < inner && steps[lane] <= step_cap) {
                        cell[lane] = next;
                        __builtin_prefetch(&cells.records[next]);
                        continue;
                    }
                }
                Location loc;
                walk_general<Index, 3, TP_WALK_AVX2>(s, q[lane], at, steps[lane], loc);
                feed.general(lane, loc);
            }
            if (!start(lane)) live &= ~(1u << lane);
        }
    }
}

// A batch's feed: its queries in order, one lane after the other taking the next, each query's loads asked
// for ahead as the loop does (prefetch_ahead).
template <class Index>
struct TP_WALK_ISA(BatchFeed) {
    const Store::Impl& s;
    size_t count;
    const float (*q)[3];
    int32_t* hints;
    float* const* out_sh;
    Status* status;
    size_t taken = 0;
    size_t query[kLanes] = {};
    TP_WALK_TARGET bool next(int lane, const float** p, int32_t* hint) {
        if (taken == count) return false;
        const size_t i = taken++;
        prefetch_ahead(Cells<Index>(s), i, count, hints);
        query[lane] = i;
        *p = q[i];
        *hint = hints[i];
        return true;
    }
    TP_WALK_TARGET void held(int lane, uint32_t cell, const uint8_t* const records[4], const float weights[4]) {
        const size_t i = query[lane];
        hints[i] = int32_t(cell);
        status[i] = Status::ok;
        s.blend_sh(records, weights, out_sh[i]);
    }
    TP_WALK_TARGET void general(int lane, const Location& loc) {
        const size_t i = query[lane];
        hints[i] = loc.cell;
        status[i] = answer_sh(s, loc, out_sh[i], nullptr);
    }
};

template <class Index>
TP_WALK_TARGET void TP_WALK_ISA(interpolate_batch_lanes)(const Store::Impl& s, size_t count, const float (*q)[3],
                                                         int32_t* hints, float* const* out_sh, Status* status) {
    prefetch_first(Cells<Index>(s), count, hints);
    TP_WALK_ISA(BatchFeed)<Index> feed{s, count, q, hints, out_sh, status};
    TP_WALK_ISA(walk_lanes)<Index>(s, feed);
}

