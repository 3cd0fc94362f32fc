// The lean walk over tetrahedra, included by locate.cpp once per orientation kernel (the AVX2
// one inside a region compiled for that target, so that its kernel inlines): TP_WALK_CLEAR_NAME is
// the function's name, TP_WALK_CLEAR_KERNEL the kernel (tetrahedron_orientations.h).
//
// The common case, kept lean: the walk over tetrahedra while the filter decides. A cell whose four
// orientations are all certainly positive holds the query (weights D / sum D); a cell with a
// certainly negative one is left across the most negative (any facet the query is strictly beyond
// is a valid visibility step). Returns true with loc filled when answered; false with *cell where
// the general walk must take over (an uncertain sign, the hull, an outer cell, or the step cap).
template <class Index>
__attribute__((noinline)) bool TP_WALK_CLEAR_NAME(const Cells<Index>& cells, uint32_t* cell, const float q[3],
                                                  uint32_t* steps,
                                  uint32_t step_cap, Location& loc) {
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
            loc.cell = int32_t(c);
            loc.steps = *steps;
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

// Several queries' first tests at once: their start cells' orientations computed back to back, so
// that the processor overlaps their independent load and arithmetic chains; a query whose start cell
// holds it clearly is answered here, the others walk on their own (walk<Index>).
template <class Index>
__attribute__((noinline)) void TP_LOCATE_GROUP_NAME(const Cells<Index>& cells, size_t count, const float (*q)[3],
                                                    const int32_t* hints, Location* out) {
    const Store::Impl& s = cells.s;
    Orientations o[kMaxGroup];
    const CellRecord<Index>* records[kMaxGroup];
    for (size_t i = 0; i < count; ++i) {
        records[i] = nullptr;
        if (hints[i] < 0 || uint32_t(hints[i]) >= s.inner_cell_count) continue;
        const CellRecord<Index>& r = cells.records[hints[i]];
        const float* const P[4] = {cells.position(r.vertices[0]), cells.position(r.vertices[1]),
                                   cells.position(r.vertices[2]), cells.position(r.vertices[3])};
        o[i] = TP_WALK_CLEAR_KERNEL::of(P, q[i]);
        records[i] = &r;
    }
    for (size_t i = 0; i < count; ++i) {
        const double* D = o[i].D;
        const double bound = o[i].bound;
        if (records[i] && (D[0] > bound) & (D[1] > bound) & (D[2] > bound) & (D[3] > bound)) {
            const double scale = 1.0 / (D[0] + D[1] + D[2] + D[3]);
            Location& loc = out[i];
            loc = Location();
            loc.cell = hints[i];
            for (int k = 0; k < 4; ++k) {
                loc.probes[k] = records[i]->vertices[k];
                loc.weights[k] = float(D[k] * scale);
            }
        } else {
            out[i] = walk<Index>(s, q[i], hints[i]);
        }
    }
}
