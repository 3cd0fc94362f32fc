// The walk: its answer equals a brute-force search over all cells (the slow reference in
// reference_interpolator.h, from positions and normals only) on hand-built stores and on built
// stores of every probe-set family; hints never change the answer; threads agree with a serial run;
// stores without extrapolation report Status::outside; a misled walk ends in the exhaustive search.
#include "hand_built_stores.h"
#include "probe_families.h"
#include "reference_interpolator.h"

#include "store_structure.h"

#include "bake/store_builder.h"
#include "core/orientation.h"
#include "core/plane_projection.h"
#include "core/store.h"
#include "core/store_data.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace tetprobe;

namespace {

// Debug and sanitizer builds run fewer queries so that each case stays within seconds.
#if defined(__SANITIZE_ADDRESS__) || !defined(NDEBUG)
constexpr int kQueryScale = 15;
#else
constexpr int kQueryScale = 1;
#endif

struct Query {
    float world[3];
    reference::Vec local;  // exactly the float world position minus the origin, in double
};

// The float world position nearest the target, and the float local point the run time decides with.
Query make_query(const StoreData& d, const reference::Vec& local_target) {
    Query q;
    for (int k = 0; k < 3; ++k) q.world[k] = float(d.origin[k] + local_target[k]);
    q.local = reference::local_point(d, q.world);
    return q;
}

// Whether stored probe `stored` sits exactly where input position `world` lands in the local frame
// (not moved onto a fitted plane or line, not merged into a probe elsewhere): then a query there is
// decided on the very same floats, and exact predicates make its weight exactly 1.
bool at_stored_position(const StoreData& d, const float world[3], uint32_t stored) {
    const reference::Vec local = reference::local_point(d, world);
    return local == reference::position(d, stored);
}

std::map<uint32_t, double> weight_map(const Location& loc) {
    std::map<uint32_t, double> m;
    for (int k = 0; k < 4; ++k)
        if (loc.weights[k] != 0) m[loc.probes[k]] += loc.weights[k];
    return m;
}

double weight_difference(const std::map<uint32_t, double>& a, const std::map<uint32_t, double>& b) {
    double worst = 0;
    for (const auto& e : a) {
        const auto it = b.find(e.first);
        worst = std::fmax(worst, std::fabs(e.second - (it == b.end() ? 0.0 : it->second)));
    }
    for (const auto& e : b)
        if (!a.count(e.first)) worst = std::fmax(worst, std::fabs(e.second));
    return worst;
}

std::string describe(const std::map<uint32_t, double>& weights) {
    std::ostringstream out;
    for (const auto& w : weights) out << w.first << ":" << w.second << " ";
    return out.str();
}

// Query points: inside and around the bounds, plus far away in every direction.
std::vector<reference::Vec> query_points(const StoreData& d, int count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.5, 1.5);
    std::normal_distribution<double> g;
    reference::Vec lo(d.bounds_min[0], d.bounds_min[1], d.bounds_min[2]);
    reference::Vec hi(d.bounds_max[0], d.bounds_max[1], d.bounds_max[2]);
    const double diagonal = std::fmax((hi - lo).norm(), 1e-30);
    std::vector<reference::Vec> points;
    for (int i = 0; i < count; ++i) {
        reference::Vec p;
        if (i % 10 == 9) {
            p = reference::Vec(g(rng), g(rng), g(rng)).normalized() * diagonal * 50.0 + 0.5 * (lo + hi);
        } else {
            for (int k = 0; k < 3; ++k) p[k] = lo[k] + u(rng) * (hi[k] - lo[k] + (hi[k] > lo[k] ? 0 : diagonal));
        }
        points.push_back(p);
    }
    return points;
}

struct Built {
    StoreData data;
    std::unique_ptr<Store> store;
};

Built build(const std::vector<float>& positions, uint32_t flags = 0) {
    BuildSettings settings;
    settings.flags = flags;
    Built b;
    b.data = build_store_data(positions.data(), 12, nullptr, 108, positions.size() / 3, settings);
    const std::vector<uint8_t> blob = write_store_blob(b.data);
    b.store = Store::load(blob.data(), blob.size());
    return b;
}

Built load(const StoreData& data) {
    Built b;
    b.data = data;
    const std::vector<uint8_t> blob = write_store_blob(data);
    b.store = Store::load(blob.data(), blob.size());
    return b;
}

// Walk (cold, and from the previous query's cell) against the reference at every query point.
// Near the probes the walk never needs its fallback; far away (tens of diagonals) neighbouring outer
// cells' sweeps may disagree and the exhaustive search may decide, still matching the reference.
void require_walk_matches_reference(const Built& b, const std::vector<reference::Vec>& points, double tolerance) {
    int32_t hint = -1;
    double worst = 0;
    int far_fallbacks = 0;
    const reference::Vec centre = 0.5 * (reference::Vec(b.data.bounds_min[0], b.data.bounds_min[1], b.data.bounds_min[2]) +
                                         reference::Vec(b.data.bounds_max[0], b.data.bounds_max[1], b.data.bounds_max[2]));
    const double diagonal = reference::set_diagonal(b.data);
    for (const reference::Vec& target : points) {
        const bool far = (target - centre).norm() > 3 * diagonal;
        const Query q = make_query(b.data, target);
        const reference::Answer expected = reference::locate(b.data, q.local);
        for (int32_t start : {int32_t(-1), hint}) {
            const Location loc = b.store->locate(q.world, start);
            INFO(std::setprecision(17) << "query local (" << q.local.x() << ", " << q.local.y() << ", " << q.local.z()
                                       << ") world (" << q.world[0] << ", " << q.world[1] << ", " << q.world[2]
                                       << ") origin (" << b.data.origin[0] << ", " << b.data.origin[1] << ", "
                                       << b.data.origin[2] << ") start " << start);
            if (expected.outside) {
                REQUIRE(loc.status == Status::outside);
                continue;
            }
            REQUIRE(loc.status == Status::ok);
            if (far)
                far_fallbacks += loc.fallback;
            else
                REQUIRE(!loc.fallback);
            const double difference = weight_difference(weight_map(loc), expected.weights);
            INFO("walk: cell " << loc.cell << " kind " << int(loc.kind) << " t " << loc.t << " weights " << describe(weight_map(loc))
                               << "; reference: cell " << expected.cell << " t " << expected.t << " weights "
                               << describe(expected.weights));
            worst = std::fmax(worst, difference);
            REQUIRE(difference <= tolerance);
            // A point clearly inside one cell must be found in that very cell.
            if (expected.score > 1e-3) REQUIRE(uint32_t(loc.cell) == expected.cell);
            hint = loc.cell;
        }
    }
    INFO("largest weight difference " << worst << ", far queries decided by the fallback " << far_fallbacks);
    SUCCEED();
}

}  // namespace

TEST_CASE("walk = brute force: hand-built tetrahedron, line and point", "[locate]") {
    const std::array<hand_built::Vec, 4> corners = {hand_built::Vec(0.1, -0.2, 0.05), hand_built::Vec(1.3, 0.1, -0.1),
                                                    hand_built::Vec(0.2, 1.1, 0.3), hand_built::Vec(0.4, 0.3, 1.2)};
    for (bool extrapolate : {false, true}) {
        const Built tet = load(hand_built::tetrahedron_store(corners, extrapolate));
        require_walk_matches_reference(tet, query_points(tet.data, 400 / kQueryScale + 20, 1), 1e-4);
        const Built line = load(hand_built::line_store({-2, 0, 0.5, 3, 7}, extrapolate));
        require_walk_matches_reference(line, query_points(line.data, 200 / kQueryScale + 10, 2), 1e-5);
    }
    const Built point = load(hand_built::point_store());
    for (const reference::Vec& p : query_points(point.data, 50, 3)) {
        const Query q = make_query(point.data, p);
        const Location loc = point.store->locate(q.world, -1);
        REQUIRE(loc.status == Status::ok);
        REQUIRE(loc.probes[0] == 0);
        REQUIRE(loc.weights[0] == 1.0f);
    }
}

void require_walk_matches_reference(const std::vector<families::ProbeSet>& sets) {
    for (const families::ProbeSet& set : sets) {
        for (uint32_t flags : {0u, uint32_t(kFlagNoExtrapolation)}) {
            INFO(set.name << " with " << set.count() << " probes, flags " << flags);
            const Built b = build(set.positions, flags);
            require_walk_matches_reference(b, query_points(b.data, 150 / kQueryScale, 7), 2e-4);
        }
    }
}

TEST_CASE("walk = brute force on built stores: random, lattices, slab", "[locate]") {
    require_walk_matches_reference({
        families::random_cloud(120, 5),
        families::lattice(4, 4, 3),                       // cospherical: Delaunay ties everywhere
        families::lattice(4, 4, 4, 1.0, 2.4e-7, 9),       // lattice plus a few ulps of jitter
        families::slab(5, 1e-3),
    });
}

TEST_CASE("walk = brute force on built stores: planes, line, race track, 1 to 3 probes", "[locate]") {
    require_walk_matches_reference({
        families::plane(40, 4),
        families::tilted_plane_rounded(40, 6),
        families::line(7),
        families::racetrack(24),
        families::random_cloud(1, 21),
        families::random_cloud(2, 22),
        families::random_cloud(3, 23),
    });
}

TEST_CASE("walk = brute force on built stores: far from the origin, tiny and huge", "[locate]") {
    require_walk_matches_reference({
        families::random_cloud(60, 8, 10, 1e3),           // a kilometre from the origin
        families::random_cloud(60, 9, 10, 1e6),           // a thousand kilometres
        families::random_cloud(60, 10, 1e-4),             // tiny
        families::random_cloud(60, 11, 1e5),              // huge
    });
}

TEST_CASE("every input probe is exact and linear fields are reproduced inside the hull", "[locate]") {
    for (const families::ProbeSet& set : {families::random_cloud(200, 31), families::plane(50, 32), families::line(9)}) {
        const Built b = build(set.positions);
        int32_t hint = -1;
        size_t exact = 0;
        for (size_t i = 0; i < set.count(); ++i) {
            const Location loc = b.store->locate(&set.positions[3 * i], hint);
            REQUIRE(loc.status == Status::ok);
            const uint32_t survivor = b.store->input_to_stored(uint32_t(i));
            INFO(set.name << " probe " << i << " (stored " << survivor << "): weights " << describe(weight_map(loc)));
            // Exact predicates on the stored floats: weight exactly 1 where the probe is stored as given.
            if (at_stored_position(b.data, &set.positions[3 * i], survivor)) {
                ++exact;
                REQUIRE(weight_map(loc)[survivor] == 1.0);
                REQUIRE(weight_map(loc).size() == 1);
            } else {
                REQUIRE(weight_map(loc)[survivor] == Approx(1.0).margin(1e-5));
            }
            hint = loc.cell;
        }
        // These sets are exactly representable (a cloud, a plane at z = 2, a line with binary steps):
        // nothing is moved.
        REQUIRE(exact == set.count());
        // sum_k w_k P_k = p at points inside the hull (the weights are barycentric coordinates), in the
        // store's frame (a flat set ignores the dropped axis, a line every coordinate but its axis).
        const reference::Frame frame = reference::frame_of(b.data);
        for (const reference::Vec& target : query_points(b.data, 300 / (2 * kQueryScale), 33)) {
            const Query q = make_query(b.data, target);
            const reference::Answer expected = reference::locate(b.data, q.local);
            if (expected.outer || expected.outside) continue;
            const Location loc = b.store->locate(q.world, -1);
            REQUIRE(loc.kind == CellKind::inner);
            reference::Vec blended = reference::Vec::Zero();
            float sum = 0;
            for (int k = 0; k < 4; ++k) {
                REQUIRE(loc.weights[k] >= 0.0f);
                REQUIRE(loc.weights[k] <= 1.0f);
                sum += loc.weights[k];
                blended += double(loc.weights[k]) * reference::position(b.data, loc.probes[k]);
            }
            REQUIRE(sum == Approx(1.0f).margin(1e-6));
            const reference::Vec residual = frame.project(blended) - frame.project(q.local);
            const double diagonal = reference::set_diagonal(b.data);
            REQUIRE(residual.norm() <= 1e-5 * diagonal);
        }
    }
}

TEST_CASE("hints never change the answer", "[locate]") {
    const Built b = build(families::random_cloud(150, 41).positions);
    std::mt19937 rng(42);
    std::uniform_int_distribution<int32_t> any_cell(-3, int32_t(b.data.cell_count()) + 3);
    for (const reference::Vec& target : query_points(b.data, 200, 43)) {
        const Query q = make_query(b.data, target);
        const Location cold = b.store->locate(q.world, -1);
        for (int trial = 0; trial < 5; ++trial) {
            const Location warm = b.store->locate(q.world, any_cell(rng));
            REQUIRE(warm.status == cold.status);
            REQUIRE(weight_difference(weight_map(warm), weight_map(cold)) <= 1e-4);
        }
    }
}

TEST_CASE("many threads querying one store get the serial results", "[locate][threads]") {
    const Built b = build(families::random_cloud(300, 51).positions);
    const std::vector<reference::Vec> targets = query_points(b.data, 2000, 52);
    std::vector<Query> queries;
    for (const auto& t : targets) queries.push_back(make_query(b.data, t));
    auto run = [&](std::vector<float>& out) {
        out.assign(queries.size() * 27, 0.0f);
        int32_t hint = -1;
        for (size_t i = 0; i < queries.size(); ++i) b.store->interpolate(queries[i].world, &hint, &out[27 * i]);
    };
    std::vector<float> serial;
    run(serial);
    const int thread_count = 8;
    std::vector<std::vector<float>> results(thread_count);
    std::vector<std::thread> threads;
    for (int t = 0; t < thread_count; ++t) threads.emplace_back([&, t] { run(results[t]); });
    for (auto& t : threads) t.join();
    for (const auto& r : results) REQUIRE(std::memcmp(r.data(), serial.data(), serial.size() * sizeof(float)) == 0);
}

TEST_CASE("without extrapolation, points beyond the hull are Status::outside and points on it are inside", "[locate]") {
    const std::array<hand_built::Vec, 4> corners = {hand_built::Vec(0, 0, 0), hand_built::Vec(1, 0, 0),
                                                    hand_built::Vec(0, 1, 0), hand_built::Vec(0, 0, 1)};
    const Built b = load(hand_built::tetrahedron_store(corners, false));
    // Decided exactly on the floats: float(1/3) is above 1/3, so three of them sum beyond the face
    // x + y + z = 1 (by 3e-8), and that point is outside; (0.25, 0.25, 0.5) is on the face.
    const float third = 1.0f / 3;
    REQUIRE(double(third) * 3 > 1.0);
    const float outside[][3] = {{-0.01f, 0.2f, 0.2f}, {0.5f, 0.5f, 0.5f}, {0.2f, 0.2f, -1e9f}, {1e9f, 1e9f, 1e9f},
                                {third, third, third}};
    for (const auto& p : outside) {
        REQUIRE(b.store->locate(p, -1).status == Status::outside);
        int32_t hint = 0;
        float sh[27];
        REQUIRE(b.store->interpolate(p, &hint, sh) == Status::outside);
        for (float x : sh) REQUIRE(x == 0.0f);
    }
    const float on_hull[][3] = {{0, 0.2f, 0.2f}, {1, 0, 0}, {0.5f, 0.5f, 0}, {0.25f, 0.25f, 0.5f}, {0.125f, 0.375f, 0.5f}};
    for (const auto& p : on_hull) {
        INFO(p[0] << ", " << p[1] << ", " << p[2]);
        REQUIRE(b.store->locate(p, -1).status == Status::ok);
    }
}

TEST_CASE("outer cells: continuous across the hull and equal to the hull probe along its ray", "[locate]") {
    const Built b = build(families::random_cloud(80, 61).positions);
    // Along each hull probe's ray the weight stays 1 on that probe.
    for (uint32_t probe = 0; probe < b.data.probe_count(); ++probe) {
        const reference::Vec n = reference::normal(b.data, probe);
        if (n.norm() == 0) continue;
        for (double t : {0.0, 0.5, 3.0, 100.0}) {
            const Query q = make_query(b.data, reference::position(b.data, probe) + t * n);
            const Location loc = b.store->locate(q.world, -1);
            REQUIRE(loc.status == Status::ok);
            REQUIRE(weight_map(loc)[probe] == Approx(1.0).margin(2e-4));
        }
    }
    // Random segments from inside to far outside: weights may change fast in thin cells, so every
    // large change between samples is narrowed by bisection; a continuous field's change vanishes
    // with the interval, a jump would stay.
    std::mt19937 rng(62);
    std::normal_distribution<double> g;
    const double diagonal = reference::set_diagonal(b.data);
    auto weights_at = [&](const reference::Vec& p) {
        const Query q = make_query(b.data, p);
        const Location loc = b.store->locate(q.world, -1);
        REQUIRE(loc.status == Status::ok);
        return weight_map(loc);
    };
    double largest_jump = 0;
    int narrowed = 0;
    for (int segment = 0; segment < 40; ++segment) {
        const reference::Vec a(g(rng), g(rng), g(rng));
        const reference::Vec e = reference::Vec(g(rng), g(rng), g(rng)).normalized() * diagonal * 2;
        const int steps = 200;
        std::map<uint32_t, double> previous = weights_at(a);
        for (int i = 1; i <= steps; ++i) {
            const std::map<uint32_t, double> current = weights_at(a + e * (double(i) / steps));
            if (weight_difference(current, previous) > 0.05) {
                ++narrowed;
                reference::Vec lo = a + e * (double(i - 1) / steps), hi = a + e * (double(i) / steps);
                std::map<uint32_t, double> w_lo = previous, w_hi = current;
                for (int k = 0; k < 30; ++k) {
                    const reference::Vec mid = 0.5 * (lo + hi);
                    const std::map<uint32_t, double> w_mid = weights_at(mid);
                    if (weight_difference(w_mid, w_lo) > weight_difference(w_mid, w_hi))
                        hi = mid, w_hi = w_mid;
                    else
                        lo = mid, w_lo = w_mid;
                }
                largest_jump = std::fmax(largest_jump, weight_difference(w_lo, w_hi));
            }
            previous = current;
        }
    }
    INFO("largest weight change left after narrowing " << narrowed << " fast changes to 2^-30 of a step: "
                                                         << largest_jump);
    REQUIRE(largest_jump < 1e-3);
}

namespace {

// Flips the edge between flat inner cell c and its neighbour across slot i when the quadrilateral is
// strictly convex (both new triangles positively oriented, exactly); returns whether it flipped.
// Cells keep their indices; the neighbours of both and the back links around them are updated.
bool flip_edge(StoreData& d, uint32_t c, uint32_t i) {
    const uint32_t n = d.cell_neighbours[4 * size_t(c) + i];
    if (n == kNone32 || n >= d.inner_cell_count) return false;
    uint32_t j = 0;
    while (j < 3 && d.cell_neighbours[4 * size_t(n) + j] != c) ++j;
    REQUIRE(j < 3);
    uint32_t* cv = &d.cell_vertices[4 * size_t(c)];
    uint32_t* nv = &d.cell_vertices[4 * size_t(n)];
    uint32_t* cn = &d.cell_neighbours[4 * size_t(c)];
    uint32_t* nn = &d.cell_neighbours[4 * size_t(n)];
    const uint32_t a = cv[i], x = cv[(i + 1) % 3], y = cv[(i + 2) % 3], f = nv[j];
    // n = (f, y, x) up to rotation: its neighbour across the edge f-x is opposite y, across f-y opposite x.
    uint32_t nx = kNone32, ny = kNone32;
    for (uint32_t k = 0; k < 3; ++k) {
        if (nv[k] == y) nx = nn[k];
        if (nv[k] == x) ny = nn[k];
    }
    const uint32_t cy = cn[(i + 1) % 3], cx = cn[(i + 2) % 3];  // across a-y, across a-x
    const uint32_t first[4] = {a, x, f, 0}, second[4] = {a, f, y, 0};
    if (structure::frame_orientation(d, first) <= 0 || structure::frame_orientation(d, second) <= 0) return false;
    const uint32_t new_c[4] = {a, x, f, kNone32}, new_c_links[4] = {nx, n, cx, kNone32};
    const uint32_t new_n[4] = {a, f, y, kNone32}, new_n_links[4] = {ny, cy, c, kNone32};
    std::copy(new_c, new_c + 4, cv);
    std::copy(new_c_links, new_c_links + 4, cn);
    std::copy(new_n, new_n + 4, nv);
    std::copy(new_n_links, new_n_links + 4, nn);
    auto relink = [&](uint32_t cell, uint32_t from, uint32_t to) {
        if (cell == kNone32) return;
        for (uint32_t k = 0; k < 3; ++k)
            if (d.cell_neighbours[4 * size_t(cell) + k] == from) d.cell_neighbours[4 * size_t(cell) + k] = to;
    };
    relink(nx, n, c);
    relink(cy, c, n);
    return true;
}

}  // namespace

TEST_CASE("a walk on a valid but non-Delaunay tessellation, from far hints, still ends in the cell that holds the point",
          "[locate]") {
    // Format 3 has no matrices to be inconsistent; what a loaded store can still get wrong is its
    // tessellation: a valid one (every cell positively oriented, neighbours consistent: the loader
    // checks exactly that) that is not Delaunay, where a visibility walk may circle (Edelsbrunner's
    // acyclicity needs Delaunay). Random convex edge flips of a built flat store make such a
    // tessellation; every walk must still end in a cell that holds the point exactly (the step cap
    // hands a circling walk to the exhaustive search).
    families::ProbeSet set = families::plane(60, 71);
    for (int corner = 0; corner < 4; ++corner) set.add(corner & 1 ? 10 : 0, corner & 2 ? 10 : 0, 2.0);
    BuildSettings settings;
    settings.flags = kFlagNoExtrapolation;
    StoreData d = build_store_data(set.positions.data(), 12, nullptr, 108, set.count(), settings);
    REQUIRE(d.dimension == 2);
    std::mt19937 rng(72);
    std::uniform_int_distribution<uint32_t> pick_cell(0, d.inner_cell_count - 1), pick_slot(0, 2);
    size_t flips = 0;
    for (int attempt = 0; attempt < 40 * int(d.inner_cell_count); ++attempt) flips += flip_edge(d, pick_cell(rng), pick_slot(rng));
    REQUIRE(flips > d.inner_cell_count);
    structure::check_layout_and_links(d);
    structure::check_inner_orientation(d);
    const Built b = load(d);
    std::uniform_int_distribution<int32_t> any_cell(0, int32_t(d.cell_count()) - 1);
    std::uniform_real_distribution<double> u(0, 10);
    size_t fallbacks = 0, queries = 0;
    for (int i = 0; i < 3000 / kQueryScale; ++i) {
        const reference::Vec world(u(rng), u(rng), i % 5 == 0 ? 2.0 : u(rng));  // off the plane too
        const reference::Vec target = world - reference::Vec(d.origin[0], d.origin[1], d.origin[2]);
        const Query q = make_query(d, target);
        const Location exhaustive = b.store->locate_exhaustive(q.world, Store::Cells::all);
        INFO("query world " << q.world[0] << ", " << q.world[1] << ", " << q.world[2] << " local " << q.local.transpose()
                            << " axis " << d.axis << " origin " << d.origin[0] << ", " << d.origin[1] << ", " << d.origin[2]);
        REQUIRE(exhaustive.status == Status::ok);
        for (int32_t hint : {int32_t(-1), any_cell(rng), any_cell(rng)}) {
            const Location loc = b.store->locate(q.world, hint);
            ++queries;
            fallbacks += loc.fallback;
            INFO("query local " << q.local.transpose() << " hint " << hint << " cell " << loc.cell);
            REQUIRE(loc.status == Status::ok);
            REQUIRE(loc.kind == CellKind::inner);
            // The cell holds the point exactly: no orientation of the query with its edges is negative.
            float uv[3][2], quv[2];
            float local[3] = {float(q.local.x()), float(q.local.y()), float(q.local.z())};
            project_to_plane(local, d.axis, quv);
            for (int k = 0; k < 3; ++k) project_to_plane(&d.positions[3 * size_t(d.cell_vertices[4 * size_t(loc.cell) + k])], d.axis, uv[k]);
            for (int k = 0; k < 3; ++k) REQUIRE(orient2d(uv[(k + 1) % 3], uv[(k + 2) % 3], quv) >= 0);
            // And it gives the exhaustive search's weights (the same cell, or a shared edge or vertex).
            REQUIRE(weight_difference(weight_map(loc), weight_map(exhaustive)) <= 1e-6);
        }
    }
    WARN("non-Delaunay tessellation (" << flips << " flips of " << d.inner_cell_count << " cells): " << fallbacks << " of "
                                       << queries << " walks handed over to the exhaustive search");
    // Outside the square, a store without extrapolation still says so, from any hint.
    const float beyond[3] = {float(d.origin[0] + 5), float(d.origin[1] - 20), float(d.origin[2])};
    for (int32_t hint : {int32_t(-1), 0, int32_t(d.cell_count()) - 1}) REQUIRE(b.store->locate(beyond, hint).status == Status::outside);
}

namespace {

// Whether a local point is strictly beyond some hull facet of a 3D or flat store (the side away from
// the facet's inner cell), decided from the positions alone in double.
bool beyond_some_hull_facet(const StoreData& d, const reference::Vec& p) {
    const reference::Frame frame = reference::frame_of(d);
    for (uint32_t c = d.inner_cell_count; c < d.cell_count(); ++c) {
        const uint32_t base = d.cell_neighbours[4 * size_t(c) + d.dimension];
        std::vector<uint32_t> facet;
        for (uint32_t k = 0; k < d.dimension; ++k) facet.push_back(d.cell_vertices[4 * size_t(c) + k]);
        uint32_t apex = 0;
        for (uint32_t k = 0; k <= d.dimension; ++k) {
            const uint32_t v = d.cell_vertices[4 * size_t(base) + k];
            if (std::find(facet.begin(), facet.end(), v) == facet.end()) apex = v;
        }
        const reference::Vec p0 = frame.project(reference::position(d, facet[0]));
        const reference::Vec inside = frame.project(reference::position(d, apex)), q = frame.project(p);
        const reference::Vec e1 = frame.project(reference::position(d, facet[1])) - p0;
        const reference::Vec across = d.dimension == 3 ? reference::Vec(e1.cross(reference::position(d, facet[2]) - p0))
                                                       : reference::Vec(e1.y(), -e1.x(), 0.0);
        if (across.dot(q - p0) * across.dot(inside - p0) < 0) return true;
    }
    return false;
}

}  // namespace

TEST_CASE("walk fallback beyond the hull: the outer cells alone decide as all cells do", "[locate]") {
    // A lost walk for a point beyond a hull facet searches only the outer cells. That is sound when
    // no inner cell holds such a point (the hull is convex) and the best cell over all cells is an
    // outer one whenever any cell holds the point.
    families::ProbeSet box = families::random_cloud(300, 31);
    for (int corner = 0; corner < 8; ++corner) box.add(corner & 1 ? 10 : 0, corner & 2 ? 10 : 0, corner & 4 ? 10 : 0);
    box.add(5e-4, 1.05, 9.65);  // nearly on a face: skinny hull facets
    box.add(1.17, 6.5e-5, 6.07);
    const std::vector<families::ProbeSet> sets = {box, families::random_cloud(200, 32), families::lattice(4, 4, 4),
                                                  families::lattice(4, 4, 4, 1, 2.4e-7), families::plane(40, 33)};
    std::mt19937 rng(34);
    std::normal_distribution<double> g;
    int beyond = 0, outer_answers = 0;
    for (const families::ProbeSet& set : sets) {
        const Built b = build(set.positions);
        const reference::Vec lo(b.data.bounds_min[0], b.data.bounds_min[1], b.data.bounds_min[2]);
        const reference::Vec hi(b.data.bounds_max[0], b.data.bounds_max[1], b.data.bounds_max[2]);
        const reference::Vec centre = 0.5 * (lo + hi);
        const double diagonal = (hi - lo).norm();
        for (int i = 0; i < 600 / kQueryScale + 20; ++i) {
            reference::Vec direction(g(rng), g(rng), g(rng));
            if (b.data.dimension == 2) direction[b.data.axis] = 0;  // in the plane
            const double radius = diagonal * std::pow(10.0, std::uniform_real_distribution<double>(-0.4, 5.0)(rng));
            const Query q = make_query(b.data, centre + radius * direction.normalized());
            if (!beyond_some_hull_facet(b.data, q.local)) continue;
            ++beyond;
            INFO(set.name << " query " << q.world[0] << ", " << q.world[1] << ", " << q.world[2]);
            const Location all = b.store->locate_exhaustive(q.world, Store::Cells::all);
            const Location outer = b.store->locate_exhaustive(q.world, Store::Cells::outer);
            REQUIRE(outer.cell >= int32_t(b.data.inner_cell_count));
            if (all.kind == CellKind::inner) {
                // An inner cell can only win where no outer cell holds the point: it does not hold it either.
                const reference::Answer r = reference::locate(b.data, q.local);
                REQUIRE(r.score < 0);
                continue;
            }
            ++outer_answers;
            REQUIRE(outer.cell == all.cell);
            REQUIRE(weight_difference(weight_map(outer), weight_map(all)) == 0);
            // And the walk itself, from the centre's cell and from no hint, answers the same.
            // KNOWN FAILURE (reported, not fixed here): on the axis-aligned 4x4x4 lattice, at about 6e4
            // diagonals out (local -184952, 127061, 246413), two neighbouring outer cells both hold the
            // point (the slow reference agrees: cell 349 at t 338724 with smallest weight 0.046, cell 350
            // at t 343909 with 0.091): their sweeps overlap, the walk answers with the first it reaches,
            // the exhaustive search with the best; weights differ by 0.149.
            const Location walked = b.store->locate(q.world, -1);
            INFO("walk: cell " << walked.cell << " t " << walked.t << " fallback " << walked.fallback << " steps "
                               << walked.steps << " weights " << describe(weight_map(walked)) << "; exhaustive: cell "
                               << all.cell << " t " << all.t << " weights " << describe(weight_map(all))
                               << "; reference: cell " << reference::locate(b.data, q.local).cell << " weights "
                               << describe(reference::locate(b.data, q.local).weights) << "; the reference in the walk's cell: score "
                               << reference::cell_answer(b.data, reference::frame_of(b.data), uint32_t(walked.cell), q.local).score
                               << " t " << reference::cell_answer(b.data, reference::frame_of(b.data), uint32_t(walked.cell), q.local).t);
            REQUIRE(weight_difference(weight_map(walked), weight_map(all)) <= 1e-4);
        }
    }
    INFO(beyond << " points beyond the hull, " << outer_answers << " answered by an outer cell over all cells");
    REQUIRE(outer_answers > beyond * 9 / 10);
}

TEST_CASE("on forged blobs every query ends within its cap of examined cells, and says when it gave up", "[locate]") {
    // The loader proves every index, link and orientation, but not that a tessellation is Delaunay, so
    // a forged blob can send walks round in circles and every query into the exhaustive search. What one
    // query examines is capped: a walk of cells + 64 steps, then a search of 3 x outer cells + 4096.
    const StoreData valid = build(families::random_cloud(1500, 61).positions).data;
    const uint64_t outer = valid.cell_count() - valid.inner_cell_count, budget = 3 * outer + 4096;
    REQUIRE(valid.inner_cell_count > budget);  // a search of every inner cell does not fit
    std::mt19937 rng(62);
    std::uniform_real_distribution<double> u(-12, 12);
    SECTION("every tetrahedron flattened onto one plane: walks on it wander, searches find nothing, queries give up") {
        StoreData flat = valid;
        for (size_t p = 0; p < flat.probe_count(); ++p) flat.positions[3 * p + 2] = 0.0f;
        flat.bounds_min[2] = flat.bounds_max[2] = 0.0f;
        flat.origin[2] = 0.0;
        const Built b = load(flat);  // flat tetrahedra are valid (TetGen's slivers may be): it loads
        size_t gave_up = 0;
        for (int i = 0; i < 200 / kQueryScale + 4; ++i) {
            // On the plane every cell is flat for the query (it hands it on) and no hull facet has it beyond.
            const float p[3] = {float(u(rng)), float(u(rng)), i % 2 ? 0.0f : float(0.3 * u(rng))};
            for (int32_t hint : {-1, int32_t(rng() % flat.cell_count())}) {
                const Location loc = b.store->locate(p, hint);
                REQUIRE(loc.steps <= flat.cell_count() + 65);  // the walk's cap: cells + 64 steps past the start
                REQUIRE(loc.searched <= budget);
                if (loc.status == Status::invalid_blob) {
                    ++gave_up;
                    REQUIRE(loc.searched == budget);
                    REQUIRE(loc.cell == -1);
                    float sh[27];
                    REQUIRE(b.store->interpolate(p, nullptr, sh) == Status::invalid_blob);
                    for (float x : sh) REQUIRE(x == 0.0f);
                } else {
                    REQUIRE(loc.status == Status::ok);
                }
            }
        }
        CHECK(gave_up > 0);
    }
    SECTION("every hull normal turned inwards: each query beyond the hull searches the outer cells, within the cap") {
        StoreData inward = valid;
        for (float& n : inward.normals) n = -n;
        const Built b = load(inward);
        size_t searched = 0;
        for (int i = 0; i < 200 / kQueryScale + 4; ++i) {
            const float p[3] = {float(3 * u(rng)), float(3 * u(rng)), float(3 * u(rng))};
            const Location loc = b.store->locate(p, -1);
            REQUIRE(loc.status == Status::ok);
            REQUIRE(loc.searched <= budget);
            searched += loc.fallback;
        }
        CHECK(searched > 0);
    }
}
