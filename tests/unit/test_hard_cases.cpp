// The hard-case families of issues 3 and 7, built by the builder and queried through the run-time
// store: exactness at probes (weight exactly 1 wherever the probe is stored where it was given: exact
// predicates on the stored floats), linear precision inside the hull, continuity (C0) across every
// face crossed by dense random segments (inside, across the hull, between outer cells), the walk
// against the slow reference and (3D) against TetGen's exact orient3d, extrapolation along hull rays,
// the half-precision store, and 32-bit indices. Each family prints one WARN line: the README's table.
#include "exact_referee.h"
#include "probe_families.h"
#include "reference_interpolator.h"
#include "store_structure.h"

#include "bake/store_builder.h"
#include "core/store.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using reference::Vec;
using tetprobe::StoreData;

namespace {

// Under AddressSanitizer everything runs several times slower: keep the sample counts modest there.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kSlow = 1;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr int kSlow = 1;
#else
constexpr int kSlow = 0;
#endif
#else
constexpr int kSlow = 0;
#endif

struct Built {
    StoreData data;
    std::unique_ptr<tetprobe::Store> store;
    std::vector<double> values;  // per stored probe: the scalar field blended in the checks (red L00)
    reference::Frame frame;
    double diagonal = 0;
};

// Builds a family with a random scalar per input probe stored as its red L00 coefficient.
Built build_family(const families::ProbeSet& set, uint32_t seed, uint32_t flags = 0, double allowed_folds = 0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<float> sh(27 * set.count(), 0.0f);
    for (size_t i = 0; i < set.count(); ++i) sh[27 * i] = u(rng);
    tetprobe::BuildSettings settings;
    settings.flags = flags;
    Built b;
    b.data = tetprobe::build_store_data(set.positions.data(), 12, sh.data(), 108, set.count(), settings);
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(b.data);
    b.store = tetprobe::Store::load(blob.data(), blob.size());
    for (uint32_t j = 0; j < b.data.probe_count(); ++j) b.values.push_back(b.data.sh[27 * size_t(j)]);
    b.frame = reference::frame_of(b.data);
    structure::check_all(b.data, seed, allowed_folds);
    b.diagonal = reference::set_diagonal(b.data);
    return b;
}

std::map<uint32_t, double> weights_of(const tetprobe::Location& loc) {
    std::map<uint32_t, double> w;
    for (int k = 0; k < 4; ++k)
        if (loc.weights[k] != 0) w[loc.probes[k]] += loc.weights[k];
    return w;
}

double largest_difference(const std::map<uint32_t, double>& a, const std::map<uint32_t, double>& b) {
    double worst = 0;
    for (const auto& x : a) {
        auto it = b.find(x.first);
        worst = std::max(worst, std::fabs(x.second - (it == b.end() ? 0.0 : it->second)));
    }
    for (const auto& x : b)
        if (!a.count(x.first)) worst = std::max(worst, std::fabs(x.second));
    return worst;
}

// The float world position of local point p, and the local point that float position really is.
struct Query {
    float world[3];
    Vec local;
};
Query query_at(const StoreData& d, const Vec& p) {
    Query q;
    for (int a = 0; a < 3; ++a) q.world[a] = float(d.origin[a] + p[a]);
    q.local = reference::local_point(d, q.world);
    return q;
}

double blend(const Built& b, const std::map<uint32_t, double>& w) {
    double v = 0;
    for (const auto& x : w) v += x.second * b.values[x.first];
    return v;
}

struct Measured {
    double probe_error = 0;        // 1 - weight of the probe at its own position (moved or merged probes)
    size_t probes_checked = 0;     // input probes queried at their own position
    size_t probes_stored_as_given = 0;  // ... whose survivor is stored exactly there
    size_t probes_not_exact = 0;   // ... of those, answered with a weight other than exactly 1
    double linear_error = 0;       // |sum w P - p| / diagonal inside the hull
    double c0_jump = 0;            // largest |value_A(x) - value_B(x)| of two adjacent cells at their facet,
                                   // over inner-inner and inner-outer facets (the hull)
    double c0_jump_outer = 0;      // the same between two outer cells
    double c0_jump_walk = 0;       // the same seen by the walk (float): values on both sides of the crossing
    double walk_vs_reference = 0;  // largest weight difference
    double ray_error = 0;          // 1 - weight of a hull probe along its ray
    size_t crossings = 0;
    size_t skipped_crossings = 0;
    size_t unbracketed = 0;        // crossings whose facet the double check could not pin down
    size_t fallbacks = 0;
    size_t queries = 0;
    size_t exact_checked = 0;       // 3D inner answers put to the exact referee
    size_t exact_misses = 0;        // ... whose cell does not hold the point exactly
    double exact_miss_depth = 0;    // the deepest miss (most negative barycentric, double)
    size_t probes = 0;             // stored probes
};

// Every probe located at its own (world, float) position: where its survivor is stored exactly at
// that float local position (not merged from elsewhere, not moved onto a fitted plane or line), the
// decision is made on the very same floats and the weight is exactly 1 (others exactly 0); elsewhere
// the error is measured.
void check_exact_at_probes(const Built& b, const families::ProbeSet& set, Measured& m, size_t limit) {
    const size_t step = std::max<size_t>(1, set.count() / limit);
    int32_t hint = -1;
    for (size_t i = 0; i < set.count(); i += step) {
        const uint32_t stored = b.data.input_remap[i];
        const bool as_given = reference::local_point(b.data, &set.positions[3 * i]) == reference::position(b.data, stored);
        ++m.probes_checked;
        m.probes_stored_as_given += as_given;
        for (int32_t start : {int32_t(-1), hint}) {
            const tetprobe::Location loc = b.store->locate(&set.positions[3 * i], start);
            ++m.queries;
            m.fallbacks += loc.fallback;
            REQUIRE(loc.status == tetprobe::Status::ok);
            const auto w = weights_of(loc);
            const double own = w.count(stored) ? w.at(stored) : 0.0;
            if (as_given) {
                if (!(own == 1.0 && w.size() == 1)) {
                    ++m.probes_not_exact;
                    UNSCOPED_INFO("probe " << i << " (stored " << stored << ") from hint " << start << ": cell " << loc.cell
                                           << " weight " << own << " of " << w.size() << " probes");
                }
            } else {
                m.probe_error = std::max(m.probe_error, 1 - own);
            }
            hint = loc.cell;
        }
        // The half store returns the probe's own (rounded) SH there (a merged or moved probe is
        // interpolated at its own place: measured above).
        if (!as_given) continue;
        float sh[27], own[27];
        b.store->interpolate(&set.positions[3 * i], nullptr, sh);
        b.store->probe_sh(stored, own);
        if (sh[0] != Approx(own[0]).margin(2e-3)) {  // say where the walk went before failing
            const tetprobe::Location cold = b.store->locate(&set.positions[3 * i], -1);
            INFO("probe " << i << " (stored " << stored << "): cold walk to cell " << cold.cell << " kind " << int(cold.kind)
                          << " weights " << cold.weights[0] << " " << cold.weights[1] << " " << cold.weights[2] << " "
                          << cold.weights[3] << " probes " << cold.probes[0] << " " << cold.probes[1] << " "
                          << cold.probes[2] << " " << cold.probes[3]);
            REQUIRE(sh[0] == Approx(own[0]).margin(2e-3));
        }
    }
}

// Random points inside random inner cells: the weights reproduce the position (linear precision).
void check_linear_precision(const Built& b, std::mt19937& rng, Measured& m, int samples) {
    const StoreData& d = b.data;
    std::uniform_int_distribution<uint32_t> pick(0, d.inner_cell_count - 1);
    std::uniform_real_distribution<double> u(0, 1);
    int32_t hint = -1;
    for (int s = 0; s < samples; ++s) {
        const uint32_t c = pick(rng);
        double lambda[4], sum = 0;
        for (uint32_t k = 0; k <= d.dimension; ++k) sum += (lambda[k] = u(rng));
        Vec p = Vec::Zero();
        for (uint32_t k = 0; k <= d.dimension; ++k) p += lambda[k] / sum * reference::position(d, d.cell_vertices[4 * c + k]);
        const Query q = query_at(d, p);
        const tetprobe::Location loc = b.store->locate(q.world, hint);
        hint = loc.cell;
        ++m.queries;
        m.fallbacks += loc.fallback;
        REQUIRE(loc.status == tetprobe::Status::ok);
        // Float rounding of the query (1/16 unit at 1e6) can move a point of a hull cell outside.
        if (loc.kind == tetprobe::CellKind::outer) continue;
        Vec blended = Vec::Zero();
        double total = 0;
        for (const auto& x : weights_of(loc)) {
            REQUIRE(x.second >= 0);
            REQUIRE(x.second <= 1);
            blended += x.second * reference::position(d, x.first);
            total += x.second;
        }
        REQUIRE(total == Approx(1).margin(1e-5));
        // In the store's frame: a flat set ignores the dropped axis, a line every coordinate but its own.
        const double error = (b.frame.project(blended) - b.frame.project(q.local)).norm() / std::max(b.diagonal, 1e-30);
        m.linear_error = std::max(m.linear_error, error);
    }
}

// A random point in the bounds grown by `grow` times the diagonal.
Vec random_point(const Built& b, std::mt19937& rng, double grow) {
    std::uniform_real_distribution<double> u(0, 1);
    Vec p;
    for (int a = 0; a < 3; ++a) {
        const double lo = b.data.bounds_min[a] - grow * b.diagonal, hi = b.data.bounds_max[a] + grow * b.diagonal;
        p[a] = lo + (hi - lo) * u(rng);
    }
    return p;
}

// Dense random segments through and around the set. Wherever the walk changes cell, the crossing is
// bisected and both cells' interpolants (reference, double) are compared at the same point.
void check_continuity(const Built& b, std::mt19937& rng, Measured& m, int segments, int samples) {
    const StoreData& d = b.data;
    for (int s = 0; s < segments; ++s) {
        const Vec a = random_point(b, rng, 0.5), z = random_point(b, rng, 0.5);
        auto at = [&](double t) { return query_at(d, a + t * (z - a)); };
        Query previous_q = at(0);
        tetprobe::Location previous = b.store->locate(previous_q.world, -1);
        double previous_t = 0;
        for (int i = 1; i <= samples; ++i) {
            const double t = double(i) / samples;
            Query q = at(t);
            tetprobe::Location loc = b.store->locate(q.world, previous.cell);
            ++m.queries;
            m.fallbacks += loc.fallback;
            if (loc.cell != previous.cell) {
                // Bisect to the crossing, keeping one end in each cell.
                double lo = previous_t, hi = t;
                tetprobe::Location lo_loc = previous, hi_loc = loc;
                Query lo_q = previous_q, hi_q = q;
                for (int k = 0; k < 40; ++k) {
                    const double mid = 0.5 * (lo + hi);
                    const Query mq = at(mid);
                    if (std::equal(mq.world, mq.world + 3, lo_q.world) || std::equal(mq.world, mq.world + 3, hi_q.world)) break;
                    const tetprobe::Location ml = b.store->locate(mq.world, lo_loc.cell);
                    if (ml.cell == lo_loc.cell) {
                        lo = mid, lo_loc = ml, lo_q = mq;
                    } else {
                        hi = mid, hi_loc = ml, hi_q = mq;
                    }
                }
                if (lo_loc.cell != hi_loc.cell && lo_loc.status == tetprobe::Status::ok &&
                    hi_loc.status == tetprobe::Status::ok) {
                    ++m.crossings;
                    m.c0_jump_walk =
                        std::max(m.c0_jump_walk, std::fabs(blend(b, weights_of(lo_loc)) - blend(b, weights_of(hi_loc))));
                    const uint32_t ca = uint32_t(lo_loc.cell), cb = uint32_t(hi_loc.cell);
                    bool adjacent = false;
                    for (int k = 0; k < 4; ++k) adjacent = adjacent || d.cell_neighbours[4 * size_t(ca) + k] == cb;
                    if (!adjacent) {
                        ++m.skipped_crossings;  // the float walk stepped over a cell thinner than a float step
                    } else {
                        // The shared facet, found in double by bisection on the sign of the weight of the
                        // probe of A that B lacks (or, from an outer cell to its inner cell, of the
                        // probe of B that A lacks) around the walk's crossing.
                        uint32_t slot = 0;
                        while (d.cell_neighbours[4 * size_t(ca) + slot] != cb) ++slot;
                        const uint32_t own = d.cell_vertices[4 * size_t(ca) + slot];
                        uint32_t other = 0;
                        while (d.cell_neighbours[4 * size_t(cb) + other] != ca) ++other;
                        const uint32_t theirs = d.cell_vertices[4 * size_t(cb) + other];
                        auto on_a_side = [&](const Vec& x) {
                            if (own != tetprobe::kOuter32) {
                                const auto w = reference::cell_answer(d, b.frame, ca, x).weights;
                                return w.count(own) && w.at(own) >= 0;
                            }
                            const auto w = reference::cell_answer(d, b.frame, cb, x).weights;
                            return !(w.count(theirs) && w.at(theirs) > 0);
                        };
                        // The walk decides on float queries, the facet is found in double: widen the
                        // bracket until it straddles the facet.
                        const Vec step = (z - a).normalized();
                        Vec inside = lo_q.local, beyond = hi_q.local;
                        bool bracketed = false;
                        for (double widen = 1e-9 * b.diagonal; widen < 1e-2 * b.diagonal && !bracketed; widen *= 4) {
                            inside = lo_q.local - widen * step, beyond = hi_q.local + widen * step;
                            bracketed = on_a_side(inside) && !on_a_side(beyond);
                        }
                        if (!bracketed) {
                            ++m.unbracketed;
                            inside = beyond = 0.5 * (lo_q.local + hi_q.local);
                        }
                        for (int k = 0; k < 60 && bracketed && (beyond - inside).norm() > 1e-14 * b.diagonal; ++k) {
                            const Vec mid = 0.5 * (inside + beyond);
                            if (on_a_side(mid))
                                inside = mid;
                            else
                                beyond = mid;
                        }
                        // An outer cell holds only points strictly beyond its facet: judge it a hair outside.
                        const Vec hair = 1e-12 * b.diagonal * step;
                        reference::Answer va = reference::cell_answer(d, b.frame, ca, inside);
                        reference::Answer vb = reference::cell_answer(d, b.frame, cb, beyond);
                        if (!std::isfinite(va.score) && ca >= d.inner_cell_count) va = reference::cell_answer(d, b.frame, ca, inside - hair);
                        if (!std::isfinite(vb.score) && cb >= d.inner_cell_count) vb = reference::cell_answer(d, b.frame, cb, beyond + hair);
                        if (!std::isfinite(va.score) || !std::isfinite(vb.score)) ++m.unbracketed;
                        if (std::isfinite(va.score) && std::isfinite(vb.score)) {
                            const double jump = std::fabs(va.blend(b.values) - vb.blend(b.values));
                            double& worst = (va.outer && vb.outer) ? m.c0_jump_outer : m.c0_jump;
                            worst = std::max(worst, jump);
                        }
                    }
                }
            }
            previous = loc;
            previous_q = q;
            previous_t = t;
        }
    }
}

// The exact referee for one answer of a 3D store: the walk's inner cell holds the point exactly
// (TetGen's orient3d on the stored floats and the float local query). A miss is counted, with its
// depth (most negative barycentric, in double) for the report.
void referee(const StoreData& d, const tetprobe::Location& loc, const Query& q, Measured& m) {
    if (d.dimension != 3 || loc.kind != tetprobe::CellKind::inner) return;
    ++m.exact_checked;
    if (exact::cell_holds(d, uint32_t(loc.cell), q.local)) return;
    ++m.exact_misses;
    double w[4];
    reference::inner_barycentrics(d, reference::frame_of(d), uint32_t(loc.cell), q.local, w);
    m.exact_miss_depth = std::max(m.exact_miss_depth, -std::min({w[0], w[1], w[2], w[3]}));
    UNSCOPED_INFO("exact referee: cell " << loc.cell << " does not hold local point " << q.local.transpose());
}

// The walk (from no hint and from a far hint) against the brute-force reference.
void check_walk_against_reference(const Built& b, std::mt19937& rng, Measured& m, int samples) {
    const StoreData& d = b.data;
    std::uniform_real_distribution<double> u(0, 1);
    for (int s = 0; s < samples; ++s) {
        Vec p = random_point(b, rng, s % 3 == 0 ? 1.0 : 0.1);
        if (s % 17 == 0) p *= 1e9 / std::max(p.norm(), 1e-30);  // far outside
        const Query q = query_at(d, p);
        const reference::Answer truth = reference::locate(d, q.local);
        for (int32_t hint : {int32_t(-1), int32_t(d.cell_count() - 1)}) {
            const tetprobe::Location loc = b.store->locate(q.world, hint);
            ++m.queries;
            m.fallbacks += loc.fallback;
            if (truth.outside) {
                REQUIRE(loc.status == tetprobe::Status::outside);
                continue;
            }
            REQUIRE(loc.status == tetprobe::Status::ok);
            const double difference = largest_difference(weights_of(loc), truth.weights);
            INFO("point " << q.local.transpose() << " cell " << loc.cell << " reference cell " << truth.cell);
            m.walk_vs_reference = std::max(m.walk_vs_reference, difference);
            referee(d, loc, q, m);
        }
    }
}

// The walk (hint carried, as a moving object's) against the exact referee, at random points in
// and around the set and at points on probes, edges and faces of random cells.
void check_walk_exactly(const Built& b, std::mt19937& rng, Measured& m, int samples) {
    const StoreData& d = b.data;
    if (d.dimension != 3) return;
    std::uniform_int_distribution<uint32_t> pick(0, d.inner_cell_count - 1);
    std::uniform_real_distribution<double> u(0, 1);
    int32_t hint = -1;
    for (int s = 0; s < samples; ++s) {
        Vec p;
        if (s % 4 == 0) {
            p = random_point(b, rng, 0.05);
        } else {
            // On a vertex (s % 4 == 1), an edge (2) or a face (3) of a random inner cell.
            const uint32_t c = pick(rng);
            double w[3] = {1, 0, 0};
            if (s % 4 >= 2) w[0] = u(rng), w[1] = 1 - w[0];
            if (s % 4 == 3) w[2] = u(rng) * w[1], w[1] -= w[2];
            p = Vec::Zero();
            for (uint32_t k = 0; k < 3; ++k) p += w[k] * reference::position(d, reference::vertex(d, c, k));
        }
        const Query q = query_at(d, p);
        const tetprobe::Location loc = b.store->locate(q.world, hint);
        if (loc.status == tetprobe::Status::outside && d.cell_count() == d.inner_cell_count) continue;
        REQUIRE(loc.status == tetprobe::Status::ok);
        hint = loc.cell;
        referee(d, loc, q, m);
    }
}

// Beyond the hull, along a hull probe's ray, the answer is that probe alone.
void check_rays(const Built& b, Measured& m, size_t limit, double reach) {
    const StoreData& d = b.data;
    if (d.cell_count() == d.inner_cell_count) return;
    size_t done = 0;
    for (uint32_t j = 0; j < d.probe_count() && done < limit; ++j) {
        const Vec n = reference::normal(d, j);
        if (n.isZero()) continue;
        ++done;
        for (double s : {0.25, 3.0, 1e3}) {
            if (s > reach) break;
            const Vec on_ray = reference::position(d, j) + s * b.diagonal * n;
            const Query q = query_at(d, on_ray);
            // Far from the origin the float query cannot sit on the ray (1/16 unit steps at 1e6).
            if ((q.local - on_ray).norm() > 1e-6 * s * b.diagonal + 1e-6 * b.diagonal) continue;
            const tetprobe::Location loc = b.store->locate(q.world, -1);
            ++m.queries;
            REQUIRE(loc.status == tetprobe::Status::ok);
            REQUIRE(loc.kind == tetprobe::CellKind::outer);
            const auto w = weights_of(loc);
            const double error = 1 - (w.count(j) ? w.at(j) : 0.0);
            if ((error > 1e-4 && m.ray_error <= 1e-4) || (error > 0.5 && m.ray_error <= 0.5)) {  // say where the first (and first big) miss went
                const reference::Answer r = reference::locate(d, q.local);
                const reference::Answer own = reference::cell_answer(d, b.frame, uint32_t(loc.cell), q.local);
                WARN("first ray miss: probe " << j << " at " << s << " diagonals: cell " << loc.cell << " t " << loc.t
                                              << " fallback " << loc.fallback << "; reference: cell " << r.cell << " t " << r.t
                                              << " score " << r.score << " weight of the probe "
                                              << (r.weights.count(j) ? r.weights.at(j) : 0.0)
                                              << "; the reference in the walk's cell: score " << own.score << " t " << own.t);
            }
            m.ray_error = std::max(m.ray_error, error);
        }
    }
}

struct Bounds {
    // Decisions are exact and weights are orientations over their sum (double, then float): linear
    // and walk errors are float roundings of the weights (~1e-7); probes moved onto a fitted plane or
    // merged are answered by interpolation at their own place (probe); the reference decides
    // continuity in double, where a shared facet agrees to rounding.
    double probe = 1e-4, linear = 1e-4, c0 = 1e-6, c0_outer = 1e-6, c0_walk = 1e-3, walk = 1e-3, ray = 1e-4;
    double allowed_fold_fraction = 0;  // of the outer cells, those that may turn over within 1e5 diagonals
    double ray_reach = 1e3;            // diagonals out to which a hull probe's ray is checked
};

// The claims every family shares: probes stored as given are exact (3D families: every probe but
// merged ones), the exact referee agrees with every 3D inner answer.
void check_claims(const families::ProbeSet& set, const Built& b, const Measured& m, const Bounds& bounds) {
    CHECK(m.probes_not_exact == 0);
    if (b.data.dimension == 3 && set.count() == b.data.probe_count()) CHECK(m.probes_stored_as_given == m.probes_checked);
    CHECK(m.probe_error <= bounds.probe);
    CHECK(m.linear_error <= bounds.linear);
    CHECK(m.exact_misses == 0);
}

std::string exactness(const Measured& m) {
    std::ostringstream out;
    out << "exact at " << m.probes_stored_as_given - m.probes_not_exact << "/" << m.probes_stored_as_given
        << " probes stored as given";
    if (m.probes_checked > m.probes_stored_as_given)
        out << ", " << m.probes_checked - m.probes_stored_as_given << " moved or merged within " << m.probe_error;
    return out.str();
}

Measured run_family(const families::ProbeSet& set, uint32_t seed, const Bounds& bounds, int effort = 1,
                    uint32_t flags = 0) {
    const Built b = build_family(set, seed, flags, bounds.allowed_fold_fraction);
    std::mt19937 rng(seed);
    Measured m;
    m.probes = b.data.probe_count();
    // Sample counts: the slow reference dominates; the sanitizer build runs a fraction of them.
    check_exact_at_probes(b, set, m, size_t((kSlow ? 30 : 300) * effort));
    if (b.data.dimension > 0) check_linear_precision(b, rng, m, (kSlow ? 30 : 300) * effort);
    check_continuity(b, rng, m, (kSlow ? 2 : 12) * effort, kSlow ? 40 : 150);
    check_walk_against_reference(b, rng, m, (kSlow ? 4 : 60) * effort);
    check_walk_exactly(b, rng, m, (kSlow ? 200 : 3000) * effort);
    check_rays(b, m, size_t((kSlow ? 6 : 60) * effort), bounds.ray_reach);
    WARN(set.name << ": probes " << b.data.probe_count() << "/" << set.count() << ", dimension " << b.data.dimension
                  << ", cells " << b.data.inner_cell_count << "+" << (b.data.cell_count() - b.data.inner_cell_count)
                  << " | " << exactness(m) << ", linear error " << m.linear_error << ", C0 jump "
                  << m.c0_jump << ", between outer cells " << m.c0_jump_outer << " (walk " << m.c0_jump_walk << ", " << m.crossings << " crossings, " << m.skipped_crossings << " not adjacent, " << m.unbracketed << " not bracketed), walk vs reference "
                  << m.walk_vs_reference << ", ray error " << m.ray_error << ", fallbacks " << m.fallbacks << "/"
                  << m.queries << ", exact referee: " << m.exact_checked - m.exact_misses << "/" << m.exact_checked
                  << " inner answers hold their point exactly" << (m.exact_misses ? ", the rest miss by " : "")
                  << (m.exact_misses ? std::to_string(m.exact_miss_depth) : std::string()));
    check_claims(set, b, m, bounds);
    CHECK(m.c0_jump <= bounds.c0);
    CHECK(m.c0_jump_outer <= bounds.c0_outer);
    CHECK(m.c0_jump_walk <= bounds.c0_walk);
    CHECK(m.walk_vs_reference <= bounds.walk);
    CHECK(m.ray_error <= bounds.ray);
    return m;
}

}  // namespace

TEST_CASE("hard cases: random cloud", "[hard]") { run_family(families::random_cloud(200, 1), 1, {}); }

TEST_CASE("hard cases: small random cloud", "[hard]") { run_family(families::random_cloud(60, 2, 0.5), 2, {}); }

TEST_CASE("hard cases: lattices 2^3 and 3^3", "[hard]") {
    for (int n : {2, 3}) run_family(families::lattice(n, n, n), uint32_t(n), {});
}

TEST_CASE("hard cases: lattices 5^3 to 10^3", "[hard]") {
    run_family(families::lattice(5, 5, 5), 5, {});
    if (!kSlow) {
        run_family(families::lattice(8, 8, 8), 8, {});
        run_family(families::lattice(10, 10, 10), 10, {});
    }
}

TEST_CASE("hard cases: lattice 20^3 (8000 probes; 10^3 under the sanitizers)", "[hard]") {
    // Under the sanitizers the build and the structure checks of 20^3 cost seconds: the big lattice
    // runs in the normal build only.
    const int n = kSlow ? 10 : 20;
    const families::ProbeSet set = families::lattice(n, n, n, 0.5);
    const Built b = build_family(set, 20);
    Measured m;
    check_exact_at_probes(b, set, m, kSlow ? 50 : 400);
    std::mt19937 rng(20);
    check_linear_precision(b, rng, m, kSlow ? 50 : 400);
    check_walk_exactly(b, rng, m, kSlow ? 200 : 2000);
    WARN("lattice " << n << "^3: cells " << b.data.inner_cell_count << "+" << (b.data.cell_count() - b.data.inner_cell_count)
                    << ", " << exactness(m) << ", linear error " << m.linear_error << ", exact referee "
                    << m.exact_checked - m.exact_misses << "/" << m.exact_checked);
    check_claims(set, b, m, {});
}

TEST_CASE("hard cases: lattice with 2 eps jitter", "[hard]") {
    // Nearly cospherical cells everywhere: slivers inside, nearly coplanar faces on the hull.
    // The interpolant is continuous (the double-precision C0 check holds), but a sliver between two
    // nearly cospherical cubes turns one diagonal's interpolation into the other's within a float
    // step, so values seen by the float walk on either side of it differ by up to ~0.1.
    // Measured 0.25 since format 3's builder (its canonical probe order gives TetGen other slivers);
    // 0.09 before. The exact referee confirms every answer and the double C0 check holds.
    Bounds slivers;
    slivers.c0_walk = 0.3;
    slivers.ray = 0.02;  // flat sides, one normal each: see the rotated lattices
    // As on the rotated lattices, a sliver facet from an edge probe into a side (three nearly
    // collinear probes) can turn over right outside the hull: whether it does depends on the
    // rounding of the averaged normals (measured: 1 of the 96 outer cells for about half of the
    // facet orders the normals could be summed in; hull normals now follow the stored cell order).
    slivers.allowed_fold_fraction = 0.03;
    run_family(families::lattice(kSlow ? 4 : 6, kSlow ? 4 : 6, kSlow ? 4 : 6, 1, 2.4e-7), 3, slivers);
}

TEST_CASE("hard cases: slab squashed to 1e-3", "[hard]") {
    run_family(families::slab(kSlow ? 5 : 8, 1e-3), 4, {});
}

TEST_CASE("hard cases: plane", "[hard]") { run_family(families::plane(80, 5), 5, {}); }

TEST_CASE("hard cases: tilted plane with rounded coordinates", "[hard]") {
    // The probes sit up to 0.5 mm off the fitted plane: they are stored on it, and queries are decided
    // in the two stored coordinates other than axis (not extruded along the plane normal any more).
    // KNOWN FAILURE (reported, not loosened): a query at a moved probe's given position lands up to
    // ~0.8 x its move away from the stored probe in those coordinates, so the probe weighs 0.98, not
    // 1 +- 1e-4 (measured 0.018). Moving probes onto the plane along the dropped axis instead of along
    // the plane normal would keep them exact there (builder).
    run_family(families::tilted_plane_rounded(120, 6), 6, {});
}

TEST_CASE("hard cases: racetrack", "[hard]") { run_family(families::racetrack(48), 7, {}); }

TEST_CASE("hard cases: line, and 1, 2, 3 probes", "[hard]") {
    run_family(families::line(12), 8, {});
    families::ProbeSet one{"1 probe", {}}, two{"2 probes", {}}, three{"3 probes", {}}, corridor{"3 in a corridor", {}};
    one.add(4, 5, 6);
    two.add(0, 0, 0), two.add(1, 2, 2);
    three.add(0, 0, 0), three.add(4, 0, 0), three.add(1, 3, 0);
    corridor.add(0, 1, 0), corridor.add(10, 1, 0), corridor.add(20, 1, 0);
    for (const auto* set : {&one, &two, &three, &corridor}) run_family(*set, 9, {});

    // One probe: the same answer everywhere; two probes: constant beyond the ends.
    const Built b1 = build_family(one, 9);
    for (float x : {-1e9f, 0.f, 4.f, 3e5f}) {
        const float p[3] = {x, x, -x};
        const tetprobe::Location loc = b1.store->locate(p, -1);
        REQUIRE(loc.status == tetprobe::Status::ok);
        REQUIRE(loc.weights[0] == 1.0f);
        REQUIRE(loc.probes[0] == 0);
    }
    const Built b2 = build_family(two, 9);
    for (float s : {-100.f, -1.f, 2.f, 1e6f}) {
        const float p[3] = {s, 2 * s, 2 * s};
        const tetprobe::Location loc = b2.store->locate(p, -1);
        const auto w = weights_of(loc);
        REQUIRE(w.size() == 1);
        REQUIRE(w.begin()->first == b2.data.input_remap[s < 0 ? 0 : 1]);
    }
}

TEST_CASE("hard cases: duplicates and near-duplicates", "[hard]") {
    families::ProbeSet set = families::random_cloud(80, 10);
    const size_t base = set.count();
    std::mt19937 rng(10);
    std::uniform_int_distribution<size_t> pick(0, base - 1);
    for (int i = 0; i < 40; ++i) {
        const size_t j = pick(rng);
        const float dx = i % 2 ? 1e-6f : 0.0f;  // 3e-8 of the diagonal: within the merge tolerance
        set.add(set.positions[3 * j] + dx, set.positions[3 * j + 1], set.positions[3 * j + 2]);
    }
    const Measured m = run_family(set, 10, {});
    REQUIRE(m.probes == base);
    // The survivors and the exact duplicates are exact; the 20 probes 1e-6 away are interpolated.
    // (The sanitizer build checks a sample of the probes.)
    REQUIRE(m.probes_not_exact == 0);
    if (!kSlow) REQUIRE(m.probes_stored_as_given >= base);
    REQUIRE(m.probe_error <= 1e-4);
}

TEST_CASE("hard cases: offset 1e3 from the origin", "[hard]") {
    run_family(families::random_cloud(150, 11, 10, 1e3), 11, {});
}

TEST_CASE("hard cases: offset 1e6 from the origin", "[hard]") {
    // At 1e6 a float has 1/16 unit steps: the probes sit on that grid, the queries too, so two
    // neighbouring query positions are 1/16 apart and their values differ accordingly.
    Bounds coarse;
    coarse.c0_walk = 0.1;
    run_family(families::random_cloud(150, 12, 10, 1e6), 12, coarse);
}

TEST_CASE("hard cases: a dense room far from the centre of a kilometre-wide level", "[hard]") {
    // Cells of half a metre 400 m from the origin of the local frame: float rows relative to the
    // origin lost ~1e-4 there (a query at a probe could land in a neighbouring sliver); rows
    // relative to a cell vertex keep float precision.
    run_family(families::dense_room_in_a_level(21), 21, {});
}

TEST_CASE("hard cases: scale 1e-4", "[hard]") { run_family(families::random_cloud(150, 13, 1e-4), 13, {}); }

TEST_CASE("hard cases: scale 1e5", "[hard]") { run_family(families::random_cloud(150, 14, 1e5), 14, {}); }

TEST_CASE("hard cases: stores without extrapolation answer outside with tetprobe::Status::outside", "[hard]") {
    run_family(families::random_cloud(100, 15), 15, {}, 1, tetprobe::kFlagNoExtrapolation);
    run_family(families::plane(40, 16), 16, {}, 1, tetprobe::kFlagNoExtrapolation);
    run_family(families::line(6), 17, {}, 1, tetprobe::kFlagNoExtrapolation);
}

TEST_CASE("hard cases: more than 65535 cells switch the blob to 32-bit indices", "[hard]") {
    // 11,000 probes make ~66,500 cells. Under the sanitizers building them takes long, so there the
    // 32-bit path runs on a small set forced to 32 bits.
    const families::ProbeSet set = kSlow ? families::random_cloud(300, 18) : families::random_cloud(11000, 18);
    const Built b = build_family(set, 18, kSlow ? tetprobe::kFlagIndex32 : 0u);
    if (!kSlow) REQUIRE(b.data.cell_count() > 65535);
    REQUIRE((b.store->header().flags & tetprobe::kFlagIndex32) != 0);
    Measured m;
    check_exact_at_probes(b, set, m, 200);
    std::mt19937 rng(18);
    check_linear_precision(b, rng, m, 200);
    check_walk_exactly(b, rng, m, 500);
    check_claims(set, b, m, {});
    // A smaller set stays at 16 bits.
    const Built small = build_family(families::random_cloud(500, 19), 19);
    REQUIRE((small.store->header().flags & tetprobe::kFlagIndex32) == 0);
}

TEST_CASE("hard cases: rotated lattices, several sizes and rotations", "[hard]") {
    // A lattice under a random rotation: its float coordinates are no longer on a grid, every cube's
    // four-point faces are nearly (not exactly) coplanar and its eight corners nearly cospherical, so
    // a float decision picks among slivers; exact predicates answer each probe with itself.
    // Like the jittered lattice, every cube's nearly cospherical corners make slivers: the
    // interpolant is continuous (C0 in double), but across a sliver thinner than a float step the
    // values the float walk sees on either side differ by the ramp across it (measured 0.18-0.40).
    Bounds slivers;
    slivers.c0_walk = 0.5;
    // The sides of the hull are flat only up to float rounding: each side's probes share one normal
    // (bake/hull.cpp), so far out a moved facet stays the size of the facet, and a query 1000
    // diagonals out, rounded to float, sits a float step (1e-3 of a cell there) off the probe's ray,
    // which the weights show (the slow reference agrees, measured up to 0.009).
    slivers.ray = 0.02;
    // A few sliver facets along the rounded edges between two sides (nearly collinear probes whose
    // normals belong to different sides) turn over right outside the hull: a known limit (README);
    // their neighbours answer where they overlap (core/outer_cells.cpp, choose_outer). Measured: 3 of
    // the 12^3 lattice's 132 outer cells.
    slivers.allowed_fold_fraction = 0.03;
    // Out there, the sweeps of a side's shared normal and of its edge probes' averaged normals cross:
    // one probe of the 12^3 lattice lies in a neighbour's cell 3 diagonals out along its own ray (the
    // slow reference agrees; 1000 diagonals out for rotation 2). Rays are claimed to 0.25 diagonals
    // here: a known limit (README).
    slivers.ray_reach = 0.25;
    for (const int n : {4, 7, kSlow ? 7 : 12})
        for (const uint32_t rotation : {1u, 2u}) run_family(families::rotated_lattice(n, rotation), 30 + rotation, slivers);
}

TEST_CASE("hard cases: a cluster 1e-5 of the extent wide inside a kilometre-wide set", "[hard]") {
    // The merge tolerance (1e-6 of the 1.7 km diagonal: 1.7 mm) is the cluster's own spacing (1 cm /
    // 300^(1/3) = 1.5 mm): about two thirds of the cluster merges, and a merged probe at its own place
    // is interpolated among neighbours as close as its survivor (error up to 1). Every survivor is
    // exact. A float step at 300 m (3e-5) is 2% of a cell there, hence the walk's steps of 0.005.
    Bounds cluster;
    cluster.probe = 1.0;
    cluster.c0_walk = 0.01;
    run_family(families::cluster_in_a_level(300, 1e-2, 41), 41, cluster);
    // Fewer probes (40: 10 still merge): every probe stored as given is exact.
    const Measured m = run_family(families::cluster_in_a_level(40, 1e-2, 42), 42, cluster);
    CHECK(m.probes_not_exact == 0);
}

TEST_CASE("hard cases: a rotated lattice 1e6 from the origin", "[hard]") {
    // At 1e6 a float steps by 1/16: neighbouring query positions differ by that much, so the values
    // seen by the walk on either side of a crossing differ accordingly (as for the cloud at 1e6).
    // Slivers as in every rotated lattice, plus the 1/16 steps.
    Bounds coarse;
    coarse.c0_walk = 0.5;
    coarse.ray = 0.02;  // as for every rotated lattice (above)
    run_family(families::rotated_lattice(6, 3, 1e6), 43, coarse);
}
