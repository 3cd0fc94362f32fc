// The Bowyer-Watson tetrahedralization of delaunay3d.cpp, included there once per kernel set (the
// AVX2 one inside a region compiled for that target, so that its kernels inline), like
// walk_clear.inl: TP_TETRAHEDRALIZATION names the class, TP_SPHERE_KERNEL the in-sphere filter
// (insphere_kernels.h), TP_ORIENT_KERNEL the orientations of a cell with a point
// (tetrahedron_orientations.h). The filters only decide faster: every sign is exact either way.
class TP_TETRAHEDRALIZATION {
public:
    TP_TETRAHEDRALIZATION(const float* positions, uint32_t count, uint64_t max_cells)
        : positions_(positions), count_(count), max_cells_(max_cells < (uint64_t(1) << 30) ? max_cells : uint64_t(1) << 30) {
        // Each point padded to 16 bytes, as the kernels read it.
        padded_.assign(size_t(count) * 4 + 4, 0.0f);
        for (size_t i = 0; i < count; ++i) std::copy_n(positions + 3 * i, 3, &padded_[4 * i]);
    }

    SimplexMesh run(const std::vector<uint32_t>& order) {
        if (count_ < 4) throw Error(Status::degenerate, "a tetrahedralization needs at least 4 probes");
        if (order.size() != count_) throw Error(Status::invalid_argument, "the insertion order names every point once");
        start(order);
        for (uint32_t i : order)
            if (!initial_[i]) insert(i);
        return extract();
    }

private:
    struct Boundary {
        uint32_t cell, facet, outside;  // cavity cell, its facet on the boundary, the link across it
    };
    struct Filed {
        uint32_t facet, reverse;  // a new facet and where its reverse half-edge is filed
    };
    // The direct table: for cavities of at most kDirectVertices boundary vertices (p numbered too).
    static constexpr uint32_t kDirectVertices = 255, kStride = 256;

    const float* point(uint32_t v) const { return positions_ + size_t(v) * 3; }
    const float* padded(uint32_t v) const { return padded_.data() + size_t(v) * 4; }

    uint32_t new_cell() {
        if (!free_.empty()) {
            const uint32_t t = free_.back();
            free_.pop_back();
            tets_[t].mark = 0;
            return t;
        }
        if (tets_.size() >= max_cells_) over_budget();
        return tets_.append();
    }

    // Out of line, so that new_cell stays small enough to inline into the insertion.
    [[noreturn]] __attribute__((noinline, cold)) void over_budget() const {
        throw Error(Status::invalid_argument, "more than " + std::to_string(max_cells_) + " cells at once");
    }

    void link(uint32_t t, uint32_t k, uint32_t u, uint32_t j) {
        tets_[t].n[k] = u * 4 + j;
        tets_[u].n[j] = t * 4 + k;
    }

    bool same_point(uint32_t a, uint32_t b) const {
        const float *p = point(a), *q = point(b);
        return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
    }

    [[noreturn]] void duplicate(uint32_t a, uint32_t b) const {
        throw Error(Status::invalid_argument, "probes " + std::to_string(std::min(a, b)) + " and " +
                                                  std::to_string(std::max(a, b)) + " are at the same position");
    }

    // The first four points of the order spanning a tetrahedron, as one cell and four at infinity.
    void start(const std::vector<uint32_t>& order) {
        tets_.reserve(size_t(count_) * 7 + 16);
        initial_.assign(count_, 0);
        local_.assign(size_t(count_) + 1, Local{0, 0});
        pairs_.assign(size_t(kStride) * kStride, 0);
        const uint32_t a = order[0], b = order[1];
        uint32_t c = kInfinite, d = kInfinite;
        if (same_point(a, b)) duplicate(a, b);
        size_t at = 2;
        for (; at < count_ && c == kInfinite; ++at) {
            const uint32_t i = order[at];
            const float *p = point(a), *q = point(b), *r = point(i);
            const float pxy[2] = {p[0], p[1]}, qxy[2] = {q[0], q[1]}, rxy[2] = {r[0], r[1]};
            const float pyz[2] = {p[1], p[2]}, qyz[2] = {q[1], q[2]}, ryz[2] = {r[1], r[2]};
            const float pzx[2] = {p[2], p[0]}, qzx[2] = {q[2], q[0]}, rzx[2] = {r[2], r[0]};
            if (orient2d(pxy, qxy, rxy) != 0 || orient2d(pyz, qyz, ryz) != 0 || orient2d(pzx, qzx, rzx) != 0) c = i;
        }
        for (; at < count_ && d == kInfinite; ++at)
            if (orient3d(point(a), point(b), point(c), point(order[at])) != 0) d = order[at];
        if (d == kInfinite) throw Error(Status::degenerate, "the probes span no volume (all coplanar)");
        initial_[a] = initial_[b] = initial_[c] = initial_[d] = 1;
        uint32_t v[4] = {a, b, c, d};
        if (orient3d(point(a), point(b), point(c), point(d)) < 0) std::swap(v[0], v[1]);
        const uint32_t first = new_cell();
        std::copy(v, v + 4, tets_[first].v);
        uint32_t ghost[4];
        for (uint32_t k = 0; k < 4; ++k) {
            ghost[k] = new_cell();
            Tet& g = tets_[ghost[k]];
            for (int j = 0; j < 3; ++j) g.v[j] = v[kFacet[k][j]];
            g.v[3] = kInfinite;
            link(first, k, ghost[k], 3);
        }
        // The cells at infinity meet across the hull edges: match their facets by vertex sets.
        for (uint32_t k = 0; k < 4; ++k)
            for (uint32_t j = 0; j < 3; ++j)
                for (uint32_t l = k + 1; l < 4; ++l)
                    for (uint32_t m = 0; m < 3; ++m)
                        if (same_facet(ghost[k], j, ghost[l], m)) link(ghost[k], j, ghost[l], m);
        last_ = first;
    }

    bool same_facet(uint32_t t, uint32_t j, uint32_t u, uint32_t m) const {
        uint32_t x[3], y[3];
        for (int i = 0, a = 0, b = 0; i < 4; ++i) {
            if (i != int(j)) x[a++] = tets_[t].v[i];
            if (i != int(m)) y[b++] = tets_[u].v[i];
        }
        std::sort(x, x + 3);
        std::sort(y, y + 3);
        return x[0] == y[0] && x[1] == y[1] && x[2] == y[2];
    }

    // A cell holding point p (or, outside the hull, a cell at infinity whose hull facet p sees), by
    // a visibility walk from the last insertion: step across any facet with p strictly beyond it.
    // Exact signs make the walk end on a Delaunay tessellation; a step cap guards against anything
    // else with a search of every cell.
    uint32_t locate(uint32_t p) {
        const float* q = point(p);
        uint32_t t = last_, from = 4, rotation = 0;
        const size_t cap = 4 * tets_.size() + 64;
        for (size_t steps = 0; steps < cap; ++steps) {
            const Tet& cell = tets_[t];
            if (cell.v[3] == kInfinite) return t;  // entered across a hull facet p sees
            // The next cell is one of the four neighbours: fetch them while the kernel runs.
            TP_UNROLL_FULLY
            for (uint32_t k = 0; k < 4; ++k) __builtin_prefetch(&tets_[cell.n[k] >> 2]);
            const float* const P[4] = {padded(cell.v[0]), padded(cell.v[1]), padded(cell.v[2]), padded(cell.v[3])};
            const Orientations o = TP_ORIENT_KERNEL::of(P, padded(p));
            uint32_t exit = 4;
            rotation = (rotation + 1) & 3;
            for (uint32_t j = 0; j < 4 && exit == 4; ++j) {
                const uint32_t k = (j + rotation) & 3;
                if (k == from || o.D[k] > o.bound) continue;
                if (o.D[k] < -o.bound) {
                    exit = k;
                    break;
                }
                const float* y[4] = {point(cell.v[0]), point(cell.v[1]), point(cell.v[2]), point(cell.v[3])};
                y[k] = q;
                if (orient3d_exact_fast(y[0], y[1], y[2], y[3]) < 0) exit = k;
            }
            if (exit == 4) return t;
            from = cell.n[exit] & 3;
            t = cell.n[exit] >> 2;
        }
        return locate_by_search(p);
    }

    uint32_t locate_by_search(uint32_t p) const {
        const float* q = point(p);
        uint32_t seen_from_outside = kInfinite;
        for (uint32_t t = 0; t < tets_.size(); ++t) {
            const Tet& cell = tets_[t];
            if (cell.v[0] == kDead) continue;
            if (cell.v[3] == kInfinite) {
                if (seen_from_outside == kInfinite && orient3d(point(cell.v[0]), point(cell.v[1]), point(cell.v[2]), q) > 0)
                    seen_from_outside = t;
                continue;
            }
            bool inside = true;
            for (uint32_t k = 0; k < 4 && inside; ++k) {
                const float* y[4] = {point(cell.v[0]), point(cell.v[1]), point(cell.v[2]), point(cell.v[3])};
                y[k] = q;
                inside = orient3d(y[0], y[1], y[2], y[3]) >= 0;
            }
            if (inside) return t;
        }
        if (seen_from_outside == kInfinite) throw Error(Status::internal, "point location failed");
        return seen_from_outside;
    }

    // Decides cell t's conflict with point p (inside its circumsphere under the perturbation; for a
    // cell at infinity: p beyond its hull facet, or in its plane and the inner cell behind it in
    // conflict), marks it for this insertion and queues it in the cavity when in conflict.
    bool classify(uint32_t t, uint32_t p) {
        const Tet& cell = tets_[t];
        bool conflict;
        if (__builtin_expect(cell.v[3] != kInfinite, 1)) {
            const float* const P[5] = {padded(cell.v[0]), padded(cell.v[1]), padded(cell.v[2]), padded(cell.v[3]), padded(p)};
            int sign;
            conflict = TP_SPHERE_KERNEL::filter(P, &sign) ? sign > 0 : inside_exactly(t, p);
        } else {
            conflict = beyond_hull_facet(t, p);
        }
        tets_[t].mark = stamp_ << 1 | (conflict ? 0u : 1u);
        if (conflict) {
            room_for_one_more(cavity_, cavity_size_);
            cavity_[cavity_size_++] = t;
        }
        return conflict;
    }

    // The cavity and boundary lists are arrays with a count, so that the search appends to them
    // without a branch on the decision (written always, counted when it applies).
    template <class T>
    static void room_for_one_more(std::vector<T>& list, size_t size) {
        if (__builtin_expect(size == list.size(), 0)) list.resize(std::max<size_t>(64, 2 * list.size()));
    }

    // The rare cases, out of the hot path: the exact in-sphere sign with the tie rule, and the test
    // of a cell at infinity.
    __attribute__((noinline)) bool inside_exactly(uint32_t t, uint32_t p) {
        const Tet& cell = tets_[t];
        const float* const points[5] = {point(cell.v[0]), point(cell.v[1]), point(cell.v[2]), point(cell.v[3]), point(p)};
        int sign = insphere_exact(points[0], points[1], points[2], points[3], points[4]);
        if (sign == 0) {
            const uint32_t indices[5] = {cell.v[0], cell.v[1], cell.v[2], cell.v[3], p};
            sign = insphere_tie(points, indices);
        }
        return sign > 0;
    }

    __attribute__((noinline)) bool beyond_hull_facet(uint32_t t, uint32_t p) {
        const Tet& cell = tets_[t];
        const int side = orient3d_fast(point(cell.v[0]), point(cell.v[1]), point(cell.v[2]), point(p));
        return side > 0 || (side == 0 && in_conflict(cell.n[3] >> 2, p));
    }

    bool in_conflict(uint32_t t, uint32_t p) {
        const uint32_t state = tets_[t].mark;
        return (state >> 1) == stamp_ ? (state & 1u) == 0 : classify(t, p);
    }

    void insert(uint32_t p) {
        const uint32_t seed = locate(p);
        const Tet& found = tets_[seed];
        if (found.v[3] != kInfinite)
            for (uint32_t k = 0; k < 4; ++k)
                if (same_point(found.v[k], p)) duplicate(found.v[k], p);

        // The cavity: every cell in conflict, connected to the seed (which holds p, or sees it from
        // outside the hull, so it is in conflict without any tie), searched breadth first with the
        // cavity list as the queue; the facets to cells not in conflict bound it.
        ++stamp_;
        cavity_size_ = boundary_size_ = 0;
        tets_[seed].mark = stamp_ << 1;
        room_for_one_more(cavity_, 0);
        cavity_[cavity_size_++] = seed;
        // A cavity cell's four neighbours are filtered together (filter4), decided ones included: the
        // tests overlap instead of waiting on each other. A cell at infinity reads the zero point
        // after the last (its filter is ignored), and a filter that cannot tell, or a cell decided
        // meanwhile, goes through in_conflict as before, so every decision stays exact. Whether a
        // neighbour is in conflict is a coin toss, so its cell is queued and its facet filed without
        // a branch on it.
        const float* const e = padded(p);
        for (size_t i = 0; i < cavity_size_; ++i) {
            const uint32_t c = cavity_[i];
            uint32_t across[4];
            const float* corners[4][4];
            TP_UNROLL_FULLY
            for (uint32_t k = 0; k < 4; ++k) {
                across[k] = tets_[c].n[k];
                const Tet& u = tets_[across[k] >> 2];
                corners[k][0] = padded(u.v[0]);
                corners[k][1] = padded(u.v[1]);
                corners[k][2] = padded(u.v[2]);
                corners[k][3] = padded(u.v[3] == kInfinite ? count_ : u.v[3]);
            }
            unsigned inside, outside;
            TP_SPHERE_KERNEL::filter4(corners, e, &inside, &outside);
            TP_UNROLL_FULLY
            for (uint32_t k = 0; k < 4; ++k) {
                const uint32_t t = across[k] >> 2;
                Tet& u = tets_[t];
                const uint32_t mark = u.mark, marked = uint32_t((mark >> 1) == stamp_);
                const uint32_t filtered = ((inside | outside) >> k & 1u) & uint32_t(u.v[3] != kInfinite);
                uint32_t conflict;
                if (__builtin_expect(marked | filtered, 1)) {
                    conflict = marked ? (mark & 1u) ^ 1u : (inside >> k) & 1u;
                    u.mark = stamp_ << 1 | (conflict ^ 1u);  // unchanged when already marked
                    room_for_one_more(cavity_, cavity_size_);
                    cavity_[cavity_size_] = t;
                    cavity_size_ += conflict & (marked ^ 1u);
                } else {
                    conflict = classify(t, p);
                }
                room_for_one_more(boundary_, boundary_size_);
                boundary_[boundary_size_] = Boundary{c, k, across[k]};
                boundary_size_ += conflict ^ 1u;
            }
        }

        // One new cell per boundary facet: the cavity cell's vertices with the point in the slot of
        // the vertex the facet faces away from (so it keeps the cavity cell's orientation). New cells
        // meet across the boundary's edges: each new facet is filed under its half-edge and meets the
        // facet filed under the reverse (the boundary is a closed surface wound alike throughout),
        // in a table indexed by the boundary vertices' local numbers (EdgeLinks' hashing only for a
        // cavity with very many vertices, as a cospherical set can make). The cavity's cells are
        // freed last, so new cells reuse the previous insertion's.
        // A closed triangulated sphere with F facets has F / 2 + 2 vertices.
        const bool direct = boundary_size_ / 2 + 2 <= kDirectVertices;
        if (!direct) edges_.start(boundary_size_ * 3);
        if (filed_.size() < boundary_size_ * 3) filed_.resize(boundary_size_ * 3);
        uint32_t numbered = 0, filed = 0, finite = kInfinite;
        for (size_t at = 0; at < boundary_size_; ++at) {
            const Boundary& b = boundary_[at];
            const uint32_t t = new_cell();
            Tet& cell = tets_[t];
            // Through a local: std::copy within tets_ may overlap as far as the compiler knows, and
            // became a call to memmove (about 1.5% of a rebuild).
            uint32_t corners[4];
            std::memcpy(corners, tets_[b.cell].v, sizeof corners);
            std::memcpy(cell.v, corners, sizeof corners);
            cell.v[b.facet] = p;
            cell.n[b.facet] = b.outside;
            tets_[b.outside >> 2].n[b.outside & 3] = t * 4 + b.facet;
            if (direct) {
                uint32_t number[4];
                TP_UNROLL_FULLY
                for (uint32_t k = 0; k < 4; ++k) {
                    const uint32_t v = cell.v[k], at = v == kInfinite ? count_ : v;
                    Local& local = local_[at];
                    if (local.stamp != stamp_) local = Local{stamp_, numbered++};
                    number[k] = local.number;  // p's own number is never read
                }
                TP_UNROLL_FULLY
                for (const FacetEdge& e : kFacetEdges[b.facet]) {
                    const uint32_t from = number[e.end0], to = number[e.end1], facet = t * 4 + e.facet;
                    pairs_[from * kStride + to] = facet;
                    filed_[filed++] = Filed{facet, to * kStride + from};
                }
            } else {
                for (const FacetEdge& e : kFacetEdges[b.facet]) edges_.add(cell.v[e.end0], cell.v[e.end1], t * 4 + e.facet);
            }
            if (finite == kInfinite && cell.v[3] != kInfinite) finite = t;
        }
        if (direct) {
            for (uint32_t i = 0; i < filed; ++i) tets_[filed_[i].facet >> 2].n[filed_[i].facet & 3] = pairs_[filed_[i].reverse];
        } else {
            edges_.finish([&](uint32_t x, uint32_t y) { tets_[x >> 2].n[x & 3] = y; });
        }
        for (size_t at = 0; at < cavity_size_; ++at) {
            tets_[cavity_[at]].v[0] = kDead;
            free_.push_back(cavity_[at]);
        }
        if (finite != kInfinite) last_ = finite;
    }

    SimplexMesh extract() const {
        std::vector<uint32_t> index(tets_.size(), kNone32);
        uint32_t cells = 0;
        for (uint32_t t = 0; t < tets_.size(); ++t)
            if (tets_[t].v[0] != kDead && tets_[t].v[3] != kInfinite) index[t] = cells++;
        SimplexMesh mesh;
        mesh.dimension = 3;
        mesh.vertices.resize(cells);
        mesh.neighbours.resize(cells);
        for (uint32_t t = 0; t < tets_.size(); ++t) {
            if (index[t] == kNone32) continue;
            CellSlots& v = mesh.vertices[index[t]];
            CellSlots& n = mesh.neighbours[index[t]];
            TP_UNROLL_FULLY
            for (uint32_t k = 0; k < 4; ++k) {
                v[k] = tets_[t].v[k];
                n[k] = index[tets_[t].n[k] >> 2];
            }
            canonicalise_cell(v, n, 3, 1);  // every cell is built positively oriented
        }
        return mesh;
    }

    const float* positions_;
    uint32_t count_;
    uint64_t max_cells_;  // live cells (those outside the hull included) at any time

    CellPool tets_;
    std::vector<uint32_t> free_;
    std::vector<char> initial_;
    std::vector<float> padded_;  // 4 floats per point
    std::vector<uint32_t> cavity_;  // the first cavity_size_ in use
    std::vector<Boundary> boundary_;  // the first boundary_size_ in use
    size_t cavity_size_ = 0, boundary_size_ = 0;
    struct Local {
        uint32_t stamp, number;  // the insertion that numbered the point, its number on the boundary
    };
    std::vector<Local> local_;  // per point, and one for infinity
    std::vector<uint32_t> pairs_;                // facet per (half-edge's local numbers)
    std::vector<Filed> filed_;
    EdgeLinks edges_;
    uint32_t stamp_ = 0, last_ = 0;
};

