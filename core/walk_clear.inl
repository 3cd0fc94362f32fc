// The lean walk over tetrahedra and the query kernels of 3-dimensional stores built on it, included by
// walk.cpp once per instruction set (the AVX2 one inside a region compiled for that target, so that its
// orientation kernel inlines): TP_WALK_ISA(name) names a function for that instruction set,
// TP_WALK_CLEAR_KERNEL is the orientation kernel of one cell (tetrahedron_orientations.h), TP_WALK_AVX2
// the general walk's instruction set and TP_WALK_TARGET the functions' target attribute.
//
// The common case, kept lean: the walk over tetrahedra while the filter decides. A cell whose four
// orientations are all certainly positive holds the query (weights D / sum D); a cell with a
// certainly negative one is left across the most negative (any facet the query is strictly beyond
// is a valid visibility step). Returns true with *cell the cell that holds the query and weights its
// weights (its record's vertices are the probes); false with *cell where the general walk must take
// over (an uncertain sign, the hull, an outer cell, or the step cap). Inlined into each query kernel
// (walk.cpp), so that nothing of it goes through memory on the way to the caller's answer.
template <class Index>
TP_WALK_TARGET inline __attribute__((always_inline)) bool TP_WALK_ISA(walk_clear)(const Cells<Index>& cells, uint32_t* cell,
                                                                               const float q[3], uint32_t* steps,
                                                                               uint32_t step_cap, float weights[4]) {
    const uint32_t inner = cells.s.inner_cell_count;
    uint32_t c = *cell;
    if (c < inner) {
        // The start cell is usually the answer: ask for its probes' SH while the orientations compute.
        const CellRecord<Index>& r = cells.records[c];
        for (int k = 0; k < 4; ++k) __builtin_prefetch(cells.s.sh + size_t(r.vertices[k]) * cells.s.sh_stride);
    }
    bool stepped = false;
    while (c < inner && *steps <= step_cap) {
        const CellRecord<Index>& r = cells.records[c];
        // A walk that has stepped once often steps again: ask for the neighbours' records while the
        // orientations compute, so that the next cell's is on its way when the exit is known. (Not in
        // the start cell, which usually holds the query: there the four requests cost more than they save.)
        if (stepped)
            for (int k = 0; k < 4; ++k) {
                const uint32_t n = r.neighbours[k];
                __builtin_prefetch(&cells.records[n == none_index<Index>() ? c : n]);  // no pointer out of the array
            }
        stepped = true;
        const float* const P[4] = {cells.position(r.vertices[0]), cells.position(r.vertices[1]),
                                   cells.position(r.vertices[2]), cells.position(r.vertices[3])};
        const Orientations o = TP_WALK_CLEAR_KERNEL::of(P, q);
        const double* D = o.D;
        if (TP_WALK_CLEAR_KERNEL::all_above_bound(o)) {
            const double scale = 1.0 / (D[0] + D[1] + D[2] + D[3]);
            for (int k = 0; k < 4; ++k) weights[k] = float(D[k] * scale);
            *cell = c;
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

// The query kernels (locate_kernel.h) of a 3-dimensional store: the lean walk, the general walk where
// it stops. The loop batch asks for each query's dependent loads ahead: its hint's cell record
// kRecordAhead queries before it runs, then (the record has arrived) that cell's vertex positions
// kPositionsAhead before; the lean walk asks for the SH of its start cell itself. The queries are
// independent, so the CPU overlaps them out of order. The lane batch (walk_lanes.inl) walks eight at
// once in structure of arrays; TP_BATCH_KERNEL chooses (locate_kernel.h).
template <class Index>
TP_WALK_TARGET void TP_WALK_ISA(locate)(const Store::Impl& s, const float q[3], int32_t hint, Location& loc) {
    const Cells<Index> cells(s);
    uint32_t cell = start_of(cells, q, hint), steps = 0;
    float weights[4];
    if (TP_WALK_ISA(walk_clear)(cells, &cell, q, &steps, walk_step_cap(s), weights)) {
        const CellRecord<Index>& r = cells.records[cell];
        loc.status = Status::ok;
        loc.cell = int32_t(cell);
        loc.kind = CellKind::inner;
        loc.steps = steps;
        loc.fallback = false;
        loc.searched = 0;
        loc.t = 0;
        for (int k = 0; k < 4; ++k) {
            loc.probes[k] = r.vertices[k];
            loc.weights[k] = weights[k];
        }
        return;
    }
    walk_general<Index, 3, TP_WALK_AVX2>(s, q, cell, steps, loc);
}

template <class Index>
TP_WALK_TARGET void TP_WALK_ISA(locate_batch)(const Store::Impl& s, size_t count, const float (*q)[3], const int32_t* hints,
                                              Location* out) {
    const Cells<Index> cells(s);
    prefetch_first(cells, count, hints);
    for (size_t i = 0; i < count; ++i) {
        prefetch_ahead(cells, i, count, hints);
        TP_WALK_ISA(locate)<Index>(s, q[i], hints[i], out[i]);
    }
}

// The lean walk's answer blended straight into out_sh (no Location: nothing of the answer goes through
// memory on its way to the blend); the general walk's through the front end's answer_sh.
template <class Index>
TP_WALK_TARGET inline __attribute__((always_inline)) Status TP_WALK_ISA(interpolate_inline)(const Store::Impl& s,
                                                                                          const float q[3],
                                                                                          int32_t* hint, float out_sh[27]) {
    const Cells<Index> cells(s);
    uint32_t cell = start_of(cells, q, *hint), steps = 0;
    float weights[4];
    if (TP_WALK_ISA(walk_clear)(cells, &cell, q, &steps, walk_step_cap(s), weights)) {
        const CellRecord<Index>& r = cells.records[cell];
        const uint8_t* const records[4] = {s.sh + size_t(r.vertices[0]) * s.sh_stride, s.sh + size_t(r.vertices[1]) * s.sh_stride,
                                           s.sh + size_t(r.vertices[2]) * s.sh_stride, s.sh + size_t(r.vertices[3]) * s.sh_stride};
        *hint = int32_t(cell);
        s.blend_sh(records, weights, out_sh);
        return Status::ok;
    }
    Location loc;
    walk_general<Index, 3, TP_WALK_AVX2>(s, q, cell, steps, loc);
    *hint = loc.cell;
    return answer_sh(s, loc, out_sh, nullptr);
}

template <class Index>
TP_WALK_TARGET Status TP_WALK_ISA(interpolate)(const Store::Impl& s, const float q[3], int32_t* hint, float out_sh[27]) {
    return TP_WALK_ISA(interpolate_inline)<Index>(s, q, hint, out_sh);
}

template <class Index>
TP_WALK_TARGET void TP_WALK_ISA(interpolate_batch)(const Store::Impl& s, size_t count, const float (*q)[3], int32_t* hints,
                                                   float* const* out_sh, Status* status) {
    const Cells<Index> cells(s);
    prefetch_first(cells, count, hints);
    for (size_t i = 0; i < count; ++i) {
        prefetch_ahead(cells, i, count, hints);
        status[i] = TP_WALK_ISA(interpolate_inline)<Index>(s, q[i], &hints[i], out_sh[i]);
    }
}
