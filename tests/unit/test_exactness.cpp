// Exactness of format 3's run time (issue 7), judged against an exact referee that reads only the
// loaded store (exactness_support.h: TetGen's exact orient3d and long double barycentrics on the
// stored float32 positions):
// 1. a query at a probe weighs that probe exactly 1 and every other exactly 0 (rotated lattices of
//    several sizes and rotations, a 1/16 lattice at 1e6, a 1 cm cluster in a 1 km set, random
//    clouds; cold, with chained hints; both layouts), and interpolates to its SH bit for bit;
// 2. the cell found holds the query exactly, and the weights are the exact barycentrics within 1e-6
//    (exactly 0 where the query lies on the facet), on random points and on points exactly on edges;
//    a query answered by an outer cell is held by no inner cell;
// 3. the answers do not depend on the order the probes were given in (SH bit for bit, the same input
//    probes with the same weights), inside and outside the hull;
// 4. the fast and the compact layouts answer with the same cell and probes, weights within 1e-6;
// 5. a walk from any cell ends in a cell that holds the point, without the exhaustive fallback.
#include "exactness_support.h"
#include "probe_families.h"

#include "core/store.h"
#include "core/store_format.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace tetprobe;
using exactness::Built;
using families::ProbeSet;

namespace {

// Debug and sanitizer builds run fewer sets and queries so that the file stays within seconds.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__) || !defined(NDEBUG)
constexpr int kScale = 8;
#else
constexpr int kScale = 1;
#endif

const uint32_t kLayouts[] = {0u, TP_BUILD_COMPACT};
const char* layout_name(uint32_t flags) { return (flags & TP_BUILD_COMPACT) ? "compact" : "fast"; }

// Collects failures and reports the first few (one Catch assertion per property and set: millions
// of CHECKs would dominate the run time).
struct Failures {
    size_t count = 0, checked = 0;
    std::vector<std::string> first;
    void add(const std::string& message) {
        if (count++ < 6) first.push_back(message);
    }
    std::string report() const {
        std::ostringstream out;
        out << count << " failures of " << checked << " checks";
        for (const auto& m : first) out << "\n  " << m;
        return out.str();
    }
};

#define REQUIRE_NO_FAILURES(failures) \
    do {                              \
        INFO((failures).report());    \
        CHECK((failures).count == 0); \
    } while (0)

std::vector<float> random_sh(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<float> sh(27 * count);
    for (float& x : sh) x = u(rng);
    return sh;
}

// ---- 1. exactness at probes

std::vector<ProbeSet> probe_exactness_sets() {
    std::vector<ProbeSet> sets;
    const std::vector<int> sizes = kScale == 1 ? std::vector<int>{4, 5, 6, 8, 10, 12} : std::vector<int>{4, 8, 12};
    const int rotations = kScale == 1 ? 4 : 1;
    for (int n : sizes)
        for (int r = 0; r < rotations; ++r) sets.push_back(families::rotated_lattice(n, 1000u * n + r));
    sets.push_back(exactness::offset_lattice(8, 1.0 / 16, 1e6));
    sets.push_back(exactness::offset_lattice(6, 1.0 / 16, -1e6));
    // Rotated at 1e6: the float grid there is 1/16, so the rotated lattice is rounded to it.
    sets.push_back(families::rotated_lattice(8, 77, 1e6));
    sets.push_back(families::cluster_in_a_level(300, 0.01, 1));
    if (kScale == 1) sets.push_back(families::cluster_in_a_level(300, 0.01, 2));
    sets.push_back(exactness::named(families::random_cloud(500, 11), "random cloud 500"));
    sets.push_back(exactness::named(families::random_cloud(400, 12, 10, 1e5), "random cloud 400 at 1e5"));
    sets.push_back(exactness::named(families::lattice(8, 8, 8, 1, 1e-7, 3), "lattice 8^3 jittered by float ulps"));
    return sets;
}

// Queries every input probe at its own float position (order: input order or a shuffle; hints:
// cold or chained from the previous query) and checks weight 1 there, exactly 0 elsewhere, the
// probe's own SH bit for bit, an inner cell, no fallback.
void check_exact_at_probes(const Built& b, const ProbeSet& set, bool chained, bool shuffled, Failures& failures) {
    const Store& store = *b.store;
    std::vector<size_t> order(set.count());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    if (shuffled) std::shuffle(order.begin(), order.end(), std::mt19937(uint32_t(set.count())));
    int32_t hint = -1;
    for (size_t i : order) {
        const float* world = &set.positions[3 * i];
        const uint32_t stored = store.input_to_stored(uint32_t(i));
        if (store.probe_source(stored) != i) continue;  // merged into another probe (exact duplicates only)
        ++failures.checked;
        const Location loc = store.locate(world, chained ? hint : -1);
        hint = loc.cell;
        float at = 0, elsewhere = 0;
        for (int k = 0; k < 4; ++k) {
            if (loc.probes[k] == stored)
                at += loc.weights[k];
            else
                elsewhere = std::max(elsewhere, std::fabs(loc.weights[k]));
        }
        float sh[27], expected[27];
        int32_t sh_hint = chained ? hint : -1;
        const Status status = store.interpolate(world, &sh_hint, sh);
        store.probe_sh(stored, expected);
        const bool sh_exact = status == Status::ok && std::memcmp(sh, expected, sizeof sh) == 0;
        if (loc.status != Status::ok || loc.kind != CellKind::inner || loc.fallback || at != 1.0f || elsewhere != 0.0f ||
            !sh_exact) {
            std::ostringstream out;
            out.precision(9);
            out << "input probe " << i << " (stored " << stored << ") at " << exactness::describe_point(world)
                << (chained ? " chained" : " cold") << ": weight there " << at << ", largest elsewhere " << elsewhere
                << ", SH " << (sh_exact ? "exact" : "differs") << "; " << exactness::describe(loc);
            failures.add(out.str());
        }
    }
}

TEST_CASE("a query at a probe weighs that probe exactly 1 and the others exactly 0", "[exact]") {
    for (const ProbeSet& set : probe_exactness_sets()) {
        const std::vector<float> sh = random_sh(set.count(), 5);
        for (uint32_t flags : kLayouts) {
            const Built b = exactness::build(set, flags, 0.0, &sh);
            for (int mode = 0; mode < 3; ++mode) {
                const bool chained = mode != 0, shuffled = mode == 2;
                Failures failures;
                check_exact_at_probes(b, set, chained, shuffled, failures);
                INFO(set.name << ", " << layout_name(flags) << " layout, "
                              << (mode == 0 ? "cold" : mode == 1 ? "hints chained in input order"
                                                                 : "hints chained in a shuffled order"));
                CHECK(failures.checked >= set.count() * 9 / 10);
                REQUIRE_NO_FAILURES(failures);
            }
        }
    }
}

// ---- 2. weights equal an exact-arithmetic reference

std::vector<ProbeSet> reference_sets() {
    std::vector<ProbeSet> sets;
    sets.push_back(exactness::named(families::random_cloud(400, 21), "random cloud 400"));
    sets.push_back(exactness::named(families::lattice(6, 6, 6), "lattice 6^3"));
    sets.push_back(exactness::named(families::lattice(6, 6, 6, 1, 1e-7, 4), "lattice 6^3 jittered by float ulps"));
    sets.push_back(exactness::named(families::lattice(7, 7, 7, 1, 1e-3, 5), "lattice 7^3 jittered by 1e-3"));
    sets.push_back(families::rotated_lattice(6, 31));
    sets.push_back(families::rotated_lattice(8, 32));
    sets.push_back(exactness::offset_lattice(6, 1.0 / 16, 1e6));
    sets.push_back(families::cluster_in_a_level(300, 0.01, 7));
    if (kScale == 1) {
        sets.push_back(families::rotated_lattice(10, 33));
        sets.push_back(exactness::named(families::slab(8, 0.05), "slab 8x8x3 squashed"));
    }
    return sets;
}

// Query points in local coordinates: random in the bounds (and a margin), every edge midpoint and
// face centroid of a sample of inner cells (midpoints of floats are exact in double, and exactly on
// the edge wherever float holds them: everywhere on the axis-aligned lattices).
std::vector<std::array<double, 3>> reference_queries(const Store& store, int random_count, int cell_sample,
                                                     uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<std::array<double, 3>> points;
    const StoreHeader& h = store.header();
    std::uniform_real_distribution<double> u(-0.05, 1.05);
    for (int i = 0; i < random_count; ++i) {
        std::array<double, 3> p;
        for (int a = 0; a < 3; ++a) p[a] = h.bounds_min[a] + u(rng) * (double(h.bounds_max[a]) - h.bounds_min[a]);
        points.push_back(p);
    }
    std::uniform_int_distribution<uint32_t> pick(0, h.inner_cell_count - 1);
    for (int i = 0; i < cell_sample; ++i) {
        const float* P[4];
        uint32_t v[4];
        exactness::cell_positions(store, pick(rng), P, v);
        for (int j = 0; j < 4; ++j)
            for (int k = j + 1; k < 4; ++k) {
                std::array<double, 3> p;
                for (int a = 0; a < 3; ++a) p[a] = 0.5 * (double(P[j][a]) + double(P[k][a]));
                points.push_back(p);
            }
        for (int skip = 0; skip < 4; ++skip) {
            std::array<double, 3> p{0, 0, 0};
            for (int k = 0; k < 4; ++k)
                if (k != skip)
                    for (int a = 0; a < 3; ++a) p[a] += double(P[k][a]) / 3;
            points.push_back(p);
        }
    }
    return points;
}

// Checks one located query against the referee; returns false (with a message) on a failure.
bool check_against_reference(const Store& store, const float world[3], const Location& loc, std::string* message) {
    float q[3];
    exactness::local_of(store, world, q);
    std::ostringstream out;
    out.precision(9);
    out << "query " << exactness::describe_point(world) << " (local " << exactness::describe_point(q) << "): ";
    if (loc.status != Status::ok) {
        out << "status " << int(loc.status);
        *message = out.str();
        return false;
    }
    if (loc.kind == CellKind::outer) {
        if (exactness::any_inner_cell_holds(store, q)) {
            out << "answered by an outer cell, but an inner cell holds it; " << exactness::describe(loc);
            *message = out.str();
            return false;
        }
        return true;
    }
    if (loc.fallback || !exactness::cell_holds(store, uint32_t(loc.cell), q)) {
        out << "the inner cell found does not hold it exactly (or fell back); " << exactness::describe(loc);
        *message = out.str();
        return false;
    }
    long double ref[4];
    exactness::reference_weights(store, uint32_t(loc.cell), q, ref);
    uint32_t vertices[4], neighbours[4];
    store.cell(uint32_t(loc.cell), vertices, neighbours);
    double worst = 0, sum = 0;
    bool zero_exact = true, in_range = true;
    for (int k = 0; k < 4; ++k) {
        float w = 0;
        for (int j = 0; j < 4; ++j)
            if (loc.probes[j] == vertices[k]) w += loc.weights[j];
        worst = std::max(worst, double(std::fabs((long double)w - ref[k])));
        if (ref[k] == 0 && w != 0) zero_exact = false;
        if (!(w >= 0 && w <= 1)) in_range = false;
        sum += w;
    }
    if (worst > 1e-6 || !zero_exact || !in_range || std::fabs(sum - 1) > 1e-6) {
        out << "weights differ from the exact barycentrics by " << worst << (zero_exact ? "" : " (a zero is not exact)")
            << (in_range ? "" : " (outside [0, 1])") << ", sum " << sum << "; reference";
        for (int k = 0; k < 4; ++k) out << " " << vertices[k] << ":" << double(ref[k]);
        out << "; " << exactness::describe(loc);
        *message = out.str();
        return false;
    }
    return true;
}

TEST_CASE("the cell found holds the query exactly and the weights are its exact barycentrics", "[exact]") {
    for (const ProbeSet& set : reference_sets()) {
        for (uint32_t flags : kLayouts) {
            const Built b = exactness::build(set, flags);
            const Store& store = *b.store;
            REQUIRE(store.header().dimension == 3);
            const auto points = reference_queries(store, 1500 / kScale, 200 / kScale, 17);
            Failures failures;
            int outer_checked = 0;
            int32_t hint = -1;
            for (size_t i = 0; i < points.size(); ++i) {
                float world[3];
                exactness::world_of(store, points[i].data(), world);
                for (int chained = 0; chained < 2; ++chained) {
                    const Location loc = store.locate(world, chained ? hint : -1);
                    if (chained) hint = loc.cell;
                    if (loc.kind == CellKind::outer && loc.status == Status::ok && outer_checked++ > 60 / kScale)
                        continue;  // the O(cells) check that no inner cell holds it, for a sample
                    ++failures.checked;
                    std::string message;
                    if (!check_against_reference(store, world, loc, &message))
                        failures.add(std::string(chained ? "chained: " : "cold: ") + message);
                }
            }
            INFO(set.name << ", " << layout_name(flags) << " layout");
            REQUIRE_NO_FAILURES(failures);
        }
    }
}

// ---- 3. order independence

struct Answer {
    Status status;
    float sh[27];
    std::map<uint32_t, float> weights;  // original input index -> weight (zeros dropped)
};

// Query points: half in the bounds, half out to 3x the extent around the centre.
std::vector<std::array<float, 3>> world_queries(const ProbeSet& set, int count, uint32_t seed) {
    float lo[3] = {set.positions[0], set.positions[1], set.positions[2]}, hi[3] = {lo[0], lo[1], lo[2]};
    for (size_t i = 0; i < set.count(); ++i)
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], set.positions[3 * i + a]);
            hi[a] = std::max(hi[a], set.positions[3 * i + a]);
        }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> inside(0, 1), outside(-1.5, 1.5);
    std::vector<std::array<float, 3>> points;
    for (int i = 0; i < count; ++i) {
        std::array<float, 3> p;
        for (int a = 0; a < 3; ++a) {
            const double centre = 0.5 * (double(lo[a]) + hi[a]), extent = double(hi[a]) - lo[a];
            p[a] = float(i % 2 == 0 ? lo[a] + inside(rng) * extent : centre + outside(rng) * extent);
        }
        points.push_back(p);
    }
    return points;
}

// Answers for the queries, cold (chained = false) or with hints chained through the list;
// original[j] is the original index of input probe j of this build.
std::vector<Answer> answers(const Store& store, const std::vector<std::array<float, 3>>& points,
                            const std::vector<uint32_t>& original, bool chained) {
    std::vector<Answer> out(points.size());
    int32_t hint = -1, sh_hint = -1;
    for (size_t i = 0; i < points.size(); ++i) {
        Answer& a = out[i];
        const Location loc = store.locate(points[i].data(), chained ? hint : -1);
        hint = loc.cell;
        int32_t h = chained ? sh_hint : -1;
        a.status = store.interpolate(points[i].data(), &h, a.sh);
        sh_hint = h;
        for (int k = 0; k < 4; ++k)
            if (loc.weights[k] != 0) a.weights[original[store.probe_source(loc.probes[k])]] += loc.weights[k];
    }
    return out;
}

std::string describe_answer(const Answer& a) {
    std::ostringstream out;
    out.precision(9);
    out << "status " << int(a.status) << ", sh[0] " << a.sh[0] << ", weights";
    for (const auto& w : a.weights) out << " " << w.first << ":" << w.second;
    return out.str();
}

TEST_CASE("the answers do not depend on the order the probes are given in", "[exact]") {
    const ProbeSet sets[] = {exactness::named(families::random_cloud(300, 41), "random cloud 300"),
                             families::rotated_lattice(7, 42)};
    for (const ProbeSet& set : sets) {
        const size_t n = set.count();
        const std::vector<float> sh = random_sh(n, 43);
        const auto points = world_queries(set, 2000 / kScale, 44);
        std::vector<uint32_t> identity(n);
        for (size_t i = 0; i < n; ++i) identity[i] = uint32_t(i);
        const Built base = exactness::build(set, 0, kDefaultMergeTolerance, &sh);
        REQUIRE(base.store->header().probe_count == n);
        std::vector<std::vector<uint32_t>> permutations;
        permutations.push_back(std::vector<uint32_t>(identity.rbegin(), identity.rend()));
        for (uint32_t seed = 1; seed <= 3; ++seed) {
            std::vector<uint32_t> p = identity;
            std::shuffle(p.begin(), p.end(), std::mt19937(seed));
            permutations.push_back(p);
        }
        for (int chained = 0; chained < 2; ++chained) {
            const std::vector<Answer> expected = answers(*base.store, points, identity, chained != 0);
            for (size_t pi = 0; pi < permutations.size(); ++pi) {
                const std::vector<uint32_t>& perm = permutations[pi];  // input j of the copy is probe perm[j]
                ProbeSet copy{set.name, {}};
                std::vector<float> copy_sh;
                for (uint32_t j : perm) {
                    copy.positions.insert(copy.positions.end(), &set.positions[3 * j], &set.positions[3 * j + 3]);
                    copy_sh.insert(copy_sh.end(), &sh[27 * size_t(j)], &sh[27 * size_t(j) + 27]);
                }
                const Built b = exactness::build(copy, 0, kDefaultMergeTolerance, &copy_sh);
                const std::vector<Answer> got = answers(*b.store, points, perm, chained != 0);
                Failures failures;
                for (size_t i = 0; i < points.size(); ++i) {
                    ++failures.checked;
                    const bool same = got[i].status == expected[i].status &&
                                      std::memcmp(got[i].sh, expected[i].sh, sizeof got[i].sh) == 0 &&
                                      got[i].weights == expected[i].weights;
                    if (!same)
                        failures.add("query " + exactness::describe_point(points[i].data()) + ": given order " +
                                     describe_answer(expected[i]) + "; permuted " + describe_answer(got[i]));
                }
                INFO(set.name << ", permutation " << (pi == 0 ? "reversed" : "random #" + std::to_string(pi))
                              << (chained ? ", hints chained" : ", cold"));
                REQUIRE_NO_FAILURES(failures);
            }
        }
    }
}

// ---- 4. fast and compact layouts agree

TEST_CASE("the fast and compact layouts give the same cell and probes, and the same weights within 1e-6", "[exact]") {
    std::vector<ProbeSet> sets = {exactness::named(families::random_cloud(500, 51), "random cloud 500"),
                                  families::rotated_lattice(8, 52), families::cluster_in_a_level(300, 0.01, 53),
                                  exactness::offset_lattice(6, 1.0 / 16, 1e6)};
    if (kScale == 1)
        sets.push_back(exactness::named(families::dense_room_in_a_level(54), "dense room in a level"));
    for (const ProbeSet& set : sets) {
        const Built fast = exactness::build(set, 0, kDefaultMergeTolerance);
        const Built compact = exactness::build(set, TP_BUILD_COMPACT, kDefaultMergeTolerance);
        REQUIRE(compact.store->header().layout == kLayoutCompact);
        REQUIRE(fast.store->header().layout == kLayoutFast);
        REQUIRE(fast.store->header().cell_count == compact.store->header().cell_count);
        const auto points = world_queries(set, 3000 / kScale, 55);
        Failures failures;
        for (int chained = 0; chained < 2; ++chained) {
            int32_t hint_fast = -1, hint_compact = -1;
            for (const auto& p : points) {
                const Location a = fast.store->locate(p.data(), chained ? hint_fast : -1);
                const Location b = compact.store->locate(p.data(), chained ? hint_compact : -1);
                hint_fast = a.cell;
                hint_compact = b.cell;
                ++failures.checked;
                bool same = a.status == b.status && a.cell == b.cell && a.kind == b.kind;
                double worst = 0;
                for (int k = 0; k < 4; ++k) {
                    same &= fast.store->probe_source(a.probes[k]) == compact.store->probe_source(b.probes[k]);
                    worst = std::max(worst, double(std::fabs(a.weights[k] - b.weights[k])));
                }
                if (!same || worst > 1e-6)
                    failures.add(std::string(chained ? "chained" : "cold") + " query " +
                                 exactness::describe_point(p.data()) + ": fast " + exactness::describe(a) +
                                 "; compact " + exactness::describe(b));
            }
        }
        INFO(set.name);
        REQUIRE_NO_FAILURES(failures);
    }
}

// ---- 5. a walk from any cell

TEST_CASE("a walk started from any cell ends in a cell that holds the point, without falling back", "[exact]") {
    std::vector<ProbeSet> sets = {exactness::named(families::random_cloud(250, 61), "random cloud 250"),
                                  families::rotated_lattice(6, 62),
                                  exactness::named(families::lattice(5, 5, 5), "lattice 5^3"),
                                  exactness::offset_lattice(5, 1.0 / 16, 1e6)};
    if (kScale == 1) sets.push_back(families::cluster_in_a_level(300, 0.01, 63));
    for (const ProbeSet& set : sets) {
        for (uint32_t flags : kLayouts) {
            const Built b = exactness::build(set, flags);
            const Store& store = *b.store;
            const uint32_t cells = store.header().cell_count, inner = store.header().inner_cell_count;
            std::mt19937 rng(64);
            std::uniform_int_distribution<uint32_t> pick(0, inner - 1);
            std::uniform_real_distribution<double> u(0, 1);
            // Points inside the hull: random points of random cells, edge midpoints, probes themselves.
            std::vector<std::array<float, 3>> points;
            const int wanted = (kScale == 1 ? 300 : 40) * (cells > 4000 ? 1 : 2) / 2;
            for (int attempt = 0; int(points.size()) < wanted && attempt < 4 * wanted; ++attempt) {
                const float* P[4];
                uint32_t v[4];
                exactness::cell_positions(store, pick(rng), P, v);
                double w[4], sum = 0, local[3] = {0, 0, 0};
                const int kind = attempt % 3;
                for (int k = 0; k < 4; ++k) sum += w[k] = kind == 0 ? u(rng) : (kind == 1 ? (k < 2 ? 1 : 0) : (k == 0));
                for (int k = 0; k < 4; ++k)
                    for (int a = 0; a < 3; ++a) local[a] += w[k] / sum * double(P[k][a]);
                std::array<float, 3> world;
                exactness::world_of(store, local, world.data());
                float q[3];
                exactness::local_of(store, world.data(), q);
                if (exactness::any_inner_cell_holds(store, q)) points.push_back(world);
            }
            REQUIRE(int(points.size()) == wanted);
            Failures failures;
            for (const auto& p : points) {
                float q[3];
                exactness::local_of(store, p.data(), q);
                const Location cold = store.locate(p.data(), -1);
                const auto cold_weights = exactness::weight_map(cold);
                for (uint32_t hint = 0; hint < cells; ++hint) {
                    const Location loc = store.locate(p.data(), int32_t(hint));
                    ++failures.checked;
                    bool ok = loc.status == Status::ok && loc.kind == CellKind::inner && !loc.fallback &&
                              exactness::cell_holds(store, uint32_t(loc.cell), q);
                    // The same answer as a cold query (another cell only when the point is on their
                    // shared boundary, with the same nonzero weights up to rounding).
                    const auto weights = exactness::weight_map(loc);
                    for (const auto& w : weights) {
                        const auto it = cold_weights.find(w.first);
                        ok &= std::fabs(w.second - (it == cold_weights.end() ? 0.0f : it->second)) <= 1e-6f;
                    }
                    for (const auto& w : cold_weights)
                        if (!weights.count(w.first)) ok &= std::fabs(w.second) <= 1e-6f;
                    if (!ok)
                        failures.add("query " + exactness::describe_point(p.data()) + " from cell " +
                                     std::to_string(hint) + ": " + exactness::describe(loc) + "; cold " +
                                     exactness::describe(cold));
                }
            }
            INFO(set.name << ", " << layout_name(flags) << " layout, " << cells << " cells");
            REQUIRE_NO_FAILURES(failures);
        }
    }
}

}  // namespace
