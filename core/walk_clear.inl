// The lean walk over tetrahedra, included by walk.cpp once per instruction set (the AVX2 one inside
// a region compiled for that target, so that its kernel inlines): TP_WALK_CLEAR_NAME is the function's
// name, TP_WALK_CLEAR_KERNEL the orientation kernel of one cell (tetrahedron_orientations.h), and
// TP_WALK_TARGET the function's target attribute.
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
