// The store builder (bake/store_builder.h): structure of the StoreData it produces for every kind of
// probe set, merging, dimension handling, bad input, progress and cancellation, and tp_store_build.
#include "probe_families.h"
#include "reference_interpolator.h"
#include "store_structure.h"

#include "bake/delaunay.h"
#include "bake/hull_slivers.h"
#include "bake/probe_merge.h"
#include "bake/set_dimension.h"
#include "bake/start_grid.h"
#include "bake/store_builder.h"
#include "capi/tetprobe.h"
#include "core/error.h"
#include "core/store.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using tetprobe::BuildSettings;
using tetprobe::StoreData;

namespace {

StoreData build(const std::vector<float>& positions, uint32_t flags = 0, const std::vector<float>* sh = nullptr) {
    BuildSettings settings;
    settings.flags = flags;
    return tetprobe::build_store_data(positions.data(), 12, sh ? sh->data() : nullptr, 108, positions.size() / 3,
                                      settings);
}

// Status and message of a build that must fail.
std::pair<tp_status, std::string> build_error(const std::vector<float>& positions, const BuildSettings& settings = {},
                                              const std::vector<float>* sh = nullptr) {
    try {
        tetprobe::build_store_data(positions.data(), 12, sh ? sh->data() : nullptr, 108, positions.size() / 3, settings);
    } catch (const tetprobe::Error& e) {
        return {e.status(), e.what()};
    }
    return {TP_OK, ""};
}

}  // namespace

static void check_structure_of(const std::vector<families::ProbeSet>& sets) {
    for (const auto& set : sets) {
        for (uint32_t flags : {0u, uint32_t(TP_BUILD_NO_EXTRAPOLATION)}) {
            INFO(set.name << " flags " << flags);
            const StoreData d = build(set.positions, flags);
            structure::check_all(d);
        }
    }
}

TEST_CASE("builder: structure follows store_format.h for general sets", "[builder]") {
    check_structure_of({families::random_cloud(150, 1), families::lattice(2, 2, 2), families::lattice(4, 3, 5),
                        families::lattice(5, 5, 5, 1, 2.4e-7), families::slab(6, 1e-3)});
}

TEST_CASE("builder: structure follows store_format.h for flat sets and lines", "[builder]") {
    check_structure_of({families::plane(60, 2), families::tilted_plane_rounded(80, 3), families::line(7),
                        families::racetrack(40)});
}

TEST_CASE("builder: set dimension follows the shape", "[builder]") {
    CHECK(build(families::random_cloud(40, 2).positions).dimension == 3);
    CHECK(build(families::lattice(3, 3, 3).positions).dimension == 3);
    CHECK(build(families::slab(5, 1e-3).positions).dimension == 3);
    CHECK(build(families::slab(5, 1e-6).positions).dimension == 2);  // thinner than the flat tolerance
    CHECK(build(families::plane(30, 4).positions).dimension == 2);
    CHECK(build(families::tilted_plane_rounded(30, 5).positions).dimension == 2);
    CHECK(build(families::racetrack(20).positions).dimension == 2);
    CHECK(build(families::line(5).positions).dimension == 1);
    CHECK(build({1, 2, 3}).dimension == 0);
    CHECK(build({1, 2, 3, 1, 2, 3, 1, 2, 3}).dimension == 0);  // identical probes merge into one
}

TEST_CASE("builder: one probe is one inner cell and no outer cell", "[builder]") {
    const StoreData d = build({5, -2, 7});
    structure::check_all(d);
    REQUIRE(d.dimension == 0);
    REQUIRE(d.cell_count() == 1);
    REQUIRE(d.inner_cell_count == 1);
    REQUIRE(d.cell_vertices == std::vector<uint32_t>{0, tetprobe::kNone32, tetprobe::kNone32, tetprobe::kNone32});
    REQUIRE(d.origin[0] == 5);
    REQUIRE(d.origin[1] == -2);
    REQUIRE(d.origin[2] == 7);
    REQUIRE(d.positions == std::vector<float>{0, 0, 0});
}

TEST_CASE("builder: two probes and collinear probes make segments with two end cells", "[builder]") {
    SECTION("two probes") {
        const StoreData d = build({0, 0, 0, 2, 4, 4});
        structure::check_all(d);
        REQUIRE(d.dimension == 1);
        REQUIRE(d.inner_cell_count == 1);
        REQUIRE(d.cell_count() == 3);
        // The ends' rays point away from each other along the segment.
        const reference::Vec n0 = reference::normal(d, 0), n1 = reference::normal(d, 1);
        REQUIRE(n0.dot(reference::Vec(2, 4, 4).normalized()) == Approx(-1));
        REQUIRE(n1.dot(reference::Vec(2, 4, 4).normalized()) == Approx(1));
    }
    SECTION("collinear, unsorted input") {
        const std::vector<float> p = {3, 3, 3, 0, 0, 0, 1, 1, 1, 4, 4, 4, 2, 2, 2};
        const StoreData d = build(p);
        structure::check_all(d);
        REQUIRE(d.dimension == 1);
        REQUIRE(d.inner_cell_count == 4);
        REQUIRE(d.cell_count() == 6);
        // Segments join neighbours along the line: every segment is one unit of (1,1,1) long.
        for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
            const reference::Vec a = reference::position(d, d.cell_vertices[4 * c]);
            const reference::Vec b = reference::position(d, d.cell_vertices[4 * c + 1]);
            REQUIRE((a - b).norm() == Approx(std::sqrt(3.0)));
        }
    }
}

TEST_CASE("builder: flat sets are triangulated in their plane", "[builder]") {
    SECTION("three probes") {
        const StoreData d = build({0, 0, 0, 1, 0, 0, 0, 1, 0});
        structure::check_all(d);
        REQUIRE(d.dimension == 2);
        REQUIRE(d.inner_cell_count == 1);
        REQUIRE(d.cell_count() == 4);
    }
    SECTION("a square lattice gives two triangles per square and no cell off the plane") {
        const StoreData d = build(families::lattice(6, 5, 1).positions);
        structure::check_all(d);
        REQUIRE(d.dimension == 2);
        REQUIRE(d.inner_cell_count == 2 * 5 * 4);
        REQUIRE(d.cell_count() - d.inner_cell_count == 2 * (5 + 4));  // boundary edges
    }
}

TEST_CASE("builder: duplicates and near-duplicates merge into the first, with the mean SH", "[builder]") {
    families::ProbeSet set = families::random_cloud(30, 9);
    const size_t base = set.count();
    std::vector<float> sh(27 * base);
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = float(i % 97) * 0.01f;
    // Probe base + i copies probe 3 * i exactly, or 1e-8 of the diagonal away.
    for (size_t i = 0; i < 5; ++i) {
        const float* p = &set.positions[3 * (3 * i)];
        set.add(p[0] + (i % 2 ? 1e-7f * 40 : 0.f), p[1], p[2]);
        for (int c = 0; c < 27; ++c) sh.push_back(float(c));
    }
    const StoreData d = build(set.positions, 0, &sh);
    structure::check_all(d);
    REQUIRE(d.input_probe_count == base + 5);
    REQUIRE(d.probe_count() == base);
    for (size_t i = 0; i < 5; ++i) {
        const uint32_t survivor = d.input_remap[3 * i];
        REQUIRE(d.input_remap[base + i] == survivor);
        REQUIRE(d.probe_source[survivor] == 3 * i);
        for (int c = 0; c < 27; ++c) REQUIRE(d.sh[27 * survivor + c] == Approx((sh[27 * 3 * i + c] + float(c)) / 2));
    }
    // Probes that were not merged keep their SH and position.
    const uint32_t kept = d.input_remap[1];
    REQUIRE(d.probe_source[kept] == 1);
    for (int c = 0; c < 27; ++c) REQUIRE(d.sh[27 * kept + c] == sh[27 + c]);
    for (int a = 0; a < 3; ++a) REQUIRE(d.positions[3 * kept + a] + d.origin[a] == Approx(set.positions[3 + a]));
}

TEST_CASE("builder: probes closer than the merge tolerance merge, farther ones do not", "[builder]") {
    std::vector<float> p = families::lattice(3, 3, 3).positions;  // diagonal 2 sqrt(3)
    p.insert(p.end(), {1.0f + 1e-3f, 1, 1});                        // 2.9e-4 of the diagonal from (1,1,1)
    BuildSettings settings;
    settings.merge_tolerance = 1e-3;
    StoreData merged = tetprobe::build_store_data(p.data(), 12, nullptr, 108, p.size() / 3, settings);
    REQUIRE(merged.probe_count() == 27);
    REQUIRE(merged.input_remap[27] == merged.input_remap[13]);
    settings.merge_tolerance = 1e-4;
    StoreData kept = tetprobe::build_store_data(p.data(), 12, nullptr, 108, p.size() / 3, settings);
    REQUIRE(kept.probe_count() == 28);
    structure::check_all(kept);
}

TEST_CASE("builder: a flat set merges probes that differ only across its plane", "[builder]") {
    std::vector<float> p = families::lattice(4, 4, 1).positions;
    p.insert(p.end(), {1, 1, 1e-5f});  // above lattice probe (1,1,0): the same point of the plane
    const StoreData d = build(p);
    REQUIRE(d.dimension == 2);
    REQUIRE(d.probe_count() == 16);
    REQUIRE(d.input_remap[16] == d.input_remap[5]);
    structure::check_all(d);
}

TEST_CASE("builder: no extrapolation leaves hull facets without neighbours", "[builder]") {
    const StoreData d = build(families::random_cloud(50, 4).positions, TP_BUILD_NO_EXTRAPOLATION);
    REQUIRE(d.cell_count() == d.inner_cell_count);
    REQUIRE((d.flags & tetprobe::kFlagNoExtrapolation) != 0);
    size_t open = 0;
    for (uint32_t n : d.cell_neighbours) open += n == tetprobe::kNone32;
    REQUIRE(open > 0);
    structure::check_all(d);
}

TEST_CASE("builder: cell 0 is the inner cell nearest the probes' mean and the grid covers the set", "[builder]") {
    const StoreData d = build(families::random_cloud(150, 5, 4.0, 20.0).positions);
    reference::Vec mean = reference::Vec::Zero();
    for (uint32_t j = 0; j < d.probe_count(); ++j) mean += reference::position(d, j) / d.probe_count();
    auto centroid = [&](uint32_t c) {
        reference::Vec s = reference::Vec::Zero();
        for (uint32_t k = 0; k < 4; ++k) s += reference::position(d, d.cell_vertices[4 * c + k]) / 4;
        return s;
    };
    const double best = (centroid(0) - mean).norm();
    for (uint32_t c = 1; c < d.inner_cell_count; ++c) REQUIRE((centroid(c) - mean).norm() >= best - 1e-6);
    REQUIRE(d.grid[0] * d.grid[1] * d.grid[2] > 1);
    // Grid cells whose centre lies inside the hull name a cell that contains it.
    const reference::Frame frame = reference::frame_of(d);
    size_t inside = 0;
    for (uint32_t z = 0; z < d.grid[2]; ++z)
        for (uint32_t y = 0; y < d.grid[1]; ++y)
            for (uint32_t x = (y + z) % 3; x < d.grid[0]; x += 3) {  // a third of the grid suffices
                const uint32_t g[3] = {x, y, z};
                reference::Vec p;
                for (int a = 0; a < 3; ++a)
                    p[a] = d.bounds_min[a] + (g[a] + 0.5) * (d.bounds_max[a] - d.bounds_min[a]) / d.grid[a];
                // Inside the hull when some inner cell holds the centre with a margin.
                double best = -1;
                for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
                    double w[4];
                    reference::inner_barycentrics(d, frame, c, p, w);
                    best = std::max(best, std::min(std::min(w[0], w[1]), std::min(w[2], w[3])));
                }
                if (best < 1e-6) continue;
                ++inside;
                double w[4];
                reference::inner_barycentrics(d, frame, d.grid_cells[(z * d.grid[1] + y) * d.grid[0] + x], p, w);
                REQUIRE(std::min(std::min(w[0], w[1]), std::min(w[2], w[3])) >= -1e-9);
            }
    REQUIRE(inside > 0);
}

TEST_CASE("builder: origin is the centroid and positions are local", "[builder]") {
    const families::ProbeSet set = families::random_cloud(20, 6, 1.0, 1000.0);
    const StoreData d = build(set.positions);
    double centroid[3] = {0, 0, 0};
    for (size_t i = 0; i < set.count(); ++i)
        for (int a = 0; a < 3; ++a) centroid[a] += double(set.positions[3 * i + a]) / double(set.count());
    for (int a = 0; a < 3; ++a) REQUIRE(d.origin[a] == Approx(centroid[a]).epsilon(1e-12));
    for (uint32_t j = 0; j < d.probe_count(); ++j)
        for (int a = 0; a < 3; ++a)
            REQUIRE(double(d.positions[3 * j + a]) + d.origin[a] ==
                    Approx(double(set.positions[3 * d.probe_source[j] + a])).margin(1e-4));
}

TEST_CASE("builder: bad input is refused with a status naming the probe", "[builder]") {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    std::vector<float> p = families::random_cloud(10, 7).positions;

    auto with = [&](size_t index, float value) {
        std::vector<float> q = p;
        q[index] = value;
        return build_error(q);
    };
    auto e = with(3 * 4 + 1, nan);
    REQUIRE(e.first == TP_ERROR_INVALID_ARGUMENT);
    REQUIRE(e.second.find("probe 4") != std::string::npos);
    REQUIRE(e.second.find(" y ") != std::string::npos);
    e = with(3 * 9 + 2, -inf);
    REQUIRE(e.first == TP_ERROR_INVALID_ARGUMENT);
    REQUIRE(e.second.find("probe 9") != std::string::npos);
    REQUIRE(e.second.find(" z ") != std::string::npos);
    e = with(0, 3e31f);
    REQUIRE(e.first == TP_ERROR_INVALID_ARGUMENT);
    REQUIRE(e.second.find("probe 0") != std::string::npos);

    std::vector<float> sh(27 * 10, 0.5f);
    sh[27 * 6 + 13] = nan;
    e = build_error(p, {}, &sh);
    REQUIRE(e.first == TP_ERROR_INVALID_ARGUMENT);
    REQUIRE(e.second.find("probe 6") != std::string::npos);

    REQUIRE(build_error({}).first == TP_ERROR_DEGENERATE);
    // Distinct probes closer than 1e-9 units: refused; identical probes (one position) are fine.
    const auto tiny = build_error({1e-20f, 0, 0, 0, 3e-21f, 0, 0, 0, 1e-20f, 2e-21f, 2e-21f, 2e-21f});
    REQUIRE(tiny.first == TP_ERROR_DEGENERATE);
    REQUIRE(tiny.second.find("span") != std::string::npos);
    REQUIRE(build_error({0, 0, 0, 2e-9f, 0, 0}).first == TP_OK);
    REQUIRE(build_error({5, 5, 5, 5, 5, 5}).first == TP_OK);

    BuildSettings bad;
    bad.merge_tolerance = -1;
    REQUIRE(build_error(p, bad).first == TP_ERROR_INVALID_ARGUMENT);
    bad = BuildSettings();
    bad.flat_tolerance = std::nan("");
    REQUIRE(build_error(p, bad).first == TP_ERROR_INVALID_ARGUMENT);
    bad = BuildSettings();
    bad.flags = 0x80;
    REQUIRE(build_error(p, bad).first == TP_ERROR_INVALID_ARGUMENT);
}

namespace {

struct ProgressLog {
    std::vector<float> fractions;
    std::vector<std::string> stages;
    int cancel_at = -1;
};

int log_progress(void* user, float fraction, const char* stage) {
    auto* log = static_cast<ProgressLog*>(user);
    log->fractions.push_back(fraction);
    log->stages.push_back(stage);
    return int(log->fractions.size()) - 1 == log->cancel_at ? 1 : 0;
}

}  // namespace

TEST_CASE("builder: progress reaches 1 in order, and a non-zero return cancels", "[builder]") {
    const std::vector<float> p = families::random_cloud(40, 8).positions;
    ProgressLog log;
    BuildSettings settings;
    settings.progress = &log_progress;
    settings.progress_user = &log;
    tetprobe::build_store_data(p.data(), 12, nullptr, 108, p.size() / 3, settings);
    REQUIRE(log.fractions.size() >= 5);
    REQUIRE(log.fractions.front() == 0.0f);
    REQUIRE(log.fractions.back() == 1.0f);
    for (size_t i = 1; i < log.fractions.size(); ++i) REQUIRE(log.fractions[i] >= log.fractions[i - 1]);

    for (int at : {0, 2, int(log.fractions.size()) - 1}) {
        ProgressLog cancel;
        cancel.cancel_at = at;
        settings.progress_user = &cancel;
        auto e = build_error(p, settings);
        REQUIRE(e.first == TP_ERROR_CANCELLED);
        REQUIRE(e.second == "build cancelled");
        REQUIRE(cancel.fractions.size() == size_t(at) + 1);
    }
}

TEST_CASE("builder: strided positions and SH read the same as packed ones", "[builder]") {
    const families::ProbeSet set = families::random_cloud(25, 10);
    std::vector<float> sh(27 * set.count());
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = float(i) * 0.001f;
    const size_t ps = 5, ss = 31;  // floats per record
    std::vector<float> strided_p(ps * set.count(), -1.f), strided_sh(ss * set.count(), -1.f);
    for (size_t i = 0; i < set.count(); ++i) {
        std::memcpy(&strided_p[ps * i], &set.positions[3 * i], 12);
        std::memcpy(&strided_sh[ss * i], &sh[27 * i], 108);
    }
    BuildSettings settings;
    const StoreData a = tetprobe::build_store_data(set.positions.data(), 12, sh.data(), 108, set.count(), settings);
    const StoreData b =
        tetprobe::build_store_data(strided_p.data(), ps * 4, strided_sh.data(), ss * 4, set.count(), settings);
    REQUIRE(a.positions == b.positions);
    REQUIRE(a.sh == b.sh);
    REQUIRE(a.cell_vertices == b.cell_vertices);
    REQUIRE(a.inner_matrices == b.inner_matrices);
}

TEST_CASE("builder: the data writes a blob that loads and answers at the probes", "[builder]") {
    // (tp_store_build itself is this path behind the C boundary; the C harness covers its arguments.)
    const families::ProbeSet set = families::random_cloud(30, 11);
    for (uint32_t flags : {0u, uint32_t(TP_BUILD_INDEX32), uint32_t(TP_BUILD_NO_EXTRAPOLATION)}) {
        const StoreData d = build(set.positions, flags);
        const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
        const auto store = tetprobe::Store::load(blob.data(), blob.size());
        REQUIRE(store->header().probe_count == 30);
        REQUIRE(store->header().dimension == 3);
        REQUIRE(((store->header().flags & tetprobe::kFlagIndex32) != 0) == ((flags & TP_BUILD_INDEX32) != 0));
        for (uint32_t i = 0; i < 30; ++i) {
            const tetprobe::Location loc = store->locate(&set.positions[3 * i], -1);
            REQUIRE(loc.status == TP_OK);
            for (int k = 0; k < 4; ++k) {
                if (loc.probes[k] == d.input_remap[i]) REQUIRE(loc.weights[k] == Approx(1).margin(1e-5));
            }
        }
    }
}

TEST_CASE("builder: merging keeps the first probe of each group and leaves survivors apart", "[builder]") {
    std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0.5, 0, 0}, {1.0, 0, 0}, {0.9, 0, 0}, {0, 0, 0}, {3, 3, 3}};
    const tetprobe::ProbeMerge merge = tetprobe::merge_close_points(points, 0.6);
    // 0 survives; 0.5 joins 0; 1.0 survives (1.0 from 0); 0.9 joins 1.0 (0.9 from 0 is too far);
    // the duplicate of 0 joins 0; (3,3,3) survives.
    REQUIRE(merge.survivors == std::vector<uint32_t>{0, 2, 5});
    REQUIRE(merge.group_of == std::vector<uint32_t>{0, 0, 1, 1, 0, 2});
    const tetprobe::ProbeMerge exact = tetprobe::merge_close_points(points, 0.0);
    REQUIRE(exact.survivors == std::vector<uint32_t>{0, 1, 2, 3, 5});
    REQUIRE(exact.group_of[4] == 0);
}

TEST_CASE("builder: dimension detection compares thickness with the flat tolerance times the diagonal", "[builder]") {
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) points.emplace_back(i, j, (i * j) % 2 ? 1e-3 : 0.0);
    const double diagonal = std::sqrt(81.0 + 81.0 + 1e-6);
    REQUIRE(tetprobe::detect_set_dimension(points, diagonal, 1e-3).dimension == 2);
    REQUIRE(tetprobe::detect_set_dimension(points, diagonal, 1e-5).dimension == 3);
    // The caller's tolerance never goes below the float-rounding floor.
    std::vector<Eigen::Vector3d> thin = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1e-9}};
    REQUIRE(tetprobe::detect_set_dimension(thin, std::sqrt(2.0), 0.0).dimension == 2);
    std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2 + 1e-8}};
    const tetprobe::SetShape shape = tetprobe::detect_set_dimension(line, std::sqrt(12.0), 1e-4);
    REQUIRE(shape.dimension == 1);
    REQUIRE(std::fabs(shape.axes.col(0).dot(Eigen::Vector3d(1, 1, 1).normalized())) == Approx(1));
}

TEST_CASE("builder: start grid dimensions follow the extents within the cell budget", "[builder]") {
    uint32_t g[3];
    const float lo[3] = {0, 0, 0}, cube[3] = {10, 10, 10}, flat[3] = {20, 10, 0}, box[3] = {40, 10, 10};
    tetprobe::start_grid_dimensions(lo, cube, 4000, g);
    REQUIRE(g[0] == 10);
    REQUIRE(g[1] == 10);
    REQUIRE(g[2] == 10);
    tetprobe::start_grid_dimensions(lo, flat, 800, g);
    REQUIRE(g[2] == 1);
    REQUIRE(g[0] == 2 * g[1]);
    tetprobe::start_grid_dimensions(lo, box, 100000000, g);
    REQUIRE(size_t(g[0]) * g[1] * g[2] <= tetprobe::kMaxStartGridCells);
    REQUIRE(g[0] > 3 * g[1]);
    tetprobe::start_grid_dimensions(lo, lo, 1, g);
    REQUIRE(g[0] * g[1] * g[2] == 1);
}

TEST_CASE("builder: slivers on the hull are peeled and their probes keep a cell", "[builder]") {
    // A cube with corners a few ulps off (a "lattice plus eps" cell) and its centre: Delaunay leaves
    // flat cells between nearly coplanar corners on the hull.
    const std::vector<Eigen::Vector3d> p = {
        {-7.43751104e-07, 8.65114723e-07, 9.94369616e-07}, {-2.06838548e-07, -5.27822047e-07, 4.000001},
        {8.71078145e-07, 4.00000034, -2.24178519e-07},     {4.90963257e-08, 3.99999963, 4.00000069},
        {4.00000007, -5.4084556e-07, -1.13094212e-07},     {3.99999986, -8.55903814e-08, 4.00000083},
        {4.00000043, 4.00000056, 8.7825559e-07},           {4.00000004, 3.99999919, 4.00000061},
        {2, 2, 2}};
    const tetprobe::SetShape shape = tetprobe::detect_set_dimension(p, 7, 1e-4);
    REQUIRE(shape.dimension == 3);
    tetprobe::SimplexMesh mesh = tetprobe::delaunay_tetrahedralize(p);
    auto thin_hull_cells = [&] {
        size_t thin = 0;
        for (size_t c = 0; c < mesh.cell_count(); ++c) {
            bool hull = false;
            for (int k = 0; k < 4; ++k) hull = hull || mesh.neighbours[c][k] == tetprobe::kNone32;
            thin += hull && tetprobe::cell_thickness(mesh, c, p, shape) < tetprobe::kSliverThickness;
        }
        return thin;
    };
    const size_t before = thin_hull_cells(), cells = mesh.cell_count();
    REQUIRE(before > 0);
    const size_t peeled = tetprobe::peel_hull_slivers(mesh, p, shape);
    REQUIRE(peeled >= before);
    REQUIRE(mesh.cell_count() == cells - peeled);
    REQUIRE(thin_hull_cells() == 0);
    std::vector<int> used(p.size(), 0);
    for (size_t c = 0; c < mesh.cell_count(); ++c) {
        for (int k = 0; k < 4; ++k) {
            used[mesh.vertices[c][k]] = 1;
            const uint32_t n = mesh.neighbours[c][k];
            if (n == tetprobe::kNone32) continue;
            REQUIRE(n < mesh.cell_count());
            REQUIRE(std::count(mesh.neighbours[n].begin(), mesh.neighbours[n].end(), uint32_t(c)) == 1);
        }
    }
    REQUIRE(std::count(used.begin(), used.end(), 1) == int(p.size()));
}

TEST_CASE("builder: a set that crashes TetGen 1.5.0 is contained and retried", "[builder]") {
    // Found by fuzz_build: centred and rounded to float, these seven points make Debian's TetGen
    // 1.5.0 fail an assertion (abort). With its axes cycled TetGen handles them; the build must
    // succeed that way, and the process must live either way.
    const std::vector<float> positions = {0, 0, 3, 0, 0, 0, 0, 0, -1, -1, -1, 0, 1, 0, 0, 1, 1, 2, 2, 3, -3};
    const StoreData d = build(positions, 0);
    REQUIRE(d.dimension == 3);
    REQUIRE(d.probe_count() == 7);
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
    const auto store = tetprobe::Store::load(blob.data(), blob.size());
    for (uint32_t i = 0; i < 7; ++i) {
        const tetprobe::Location loc = store->locate(&positions[3 * i], -1);
        REQUIRE(loc.status == TP_OK);
        float own = 0;
        for (int k = 0; k < 4; ++k)
            if (loc.probes[k] == d.input_remap[i]) own += loc.weights[k];
        CHECK(own == Approx(1).margin(1e-5));
    }
}

TEST_CASE("builder: a flat set with collinear boundary probes keeps every probe", "[builder]") {
    // Found by fuzz_build: four probes on one straight stretch of the boundary. TetGen 1.5.0 left one
    // out of the flat triangulation for one apex (with clang's rounding), which merged it into a
    // neighbour 1.1 away; another apex keeps it.
    const std::vector<float> positions = {1000.f, 1000.f, 1000.f,  1000.37f, 1000.f, 1000.f,  1000.f, 1000.f, 999.63f,
                                          1001.48f, 1000.f, 1000.37f, 1000.f, 1000.f, 1000.37f, 1001.11f, 1000.f, 1000.f,
                                          1000.f, 1000.f, 1001.48f};
    const StoreData d = build(positions, 0);
    REQUIRE(d.dimension == 2);
    REQUIRE(d.probe_count() == 7);
}

namespace {

// Every input probe answers as its survivor alone, with the hint carried from query to query as a
// moving object would.
void require_exact_at_inputs(const StoreData& d, const std::vector<float>& positions) {
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
    const auto store = tetprobe::Store::load(blob.data(), blob.size());
    int32_t hint = -1;
    for (size_t i = 0; i < positions.size() / 3; ++i) {
        const tetprobe::Location loc = store->locate(&positions[3 * i], hint);
        REQUIRE(loc.status == TP_OK);
        hint = loc.cell;
        float own = 0;
        for (int k = 0; k < 4; ++k)
            if (loc.probes[k] == d.input_remap[i]) own += loc.weights[k];
        INFO("input probe " << i);
        REQUIRE(own == Approx(1).margin(1e-5));
    }
}

}  // namespace

TEST_CASE("builder: a flat set already on its plane keeps its coordinates and makes no slivers", "[builder]") {
    // Found by fuzz_build: probes on the plane y = 0, four of them on one straight stretch of the
    // boundary. Rotated into the plane's principal axes and rounded, the four were no longer
    // collinear; TetGen then built slivers along them, and the end probe was left in a sliver only,
    // which the run time never answers. Triangulated in the plane's own coordinates they stay
    // exactly collinear.
    SECTION("the fuzzer's set") {
        const std::vector<float> positions = {0, 0, 3, 4, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 1};
        const StoreData d = build(positions);
        REQUIRE(d.dimension == 2);
        REQUIRE(d.probe_count() == 5);
        REQUIRE(d.inner_cell_count == 3);  // a fan from (4, 0, 0) over the three boundary segments
        require_exact_at_inputs(d, positions);
    }
    SECTION("random small-integer sets on axis planes") {
        uint32_t state = 12345;
        auto next = [&state](int range) {
            state = state * 1664525u + 1013904223u;
            return int((state >> 8) % uint32_t(range)) - range / 2;
        };
        for (int trial = 0; trial < 300; ++trial) {
            std::vector<float> positions;
            const int count = 4 + trial % 12, kind = trial % 2;
            for (int i = 0; i < count; ++i) {
                const int a = next(9), b = next(9);
                switch (kind) {
                    case 0: positions.insert(positions.end(), {float(a), 2.5f, float(b)}); break;
                    case 1: positions.insert(positions.end(), {float(a), float(b), -7.0f}); break;
                    case 2: positions.insert(positions.end(), {float(a), float(b), float(a + b)}); break;
                    default: positions.insert(positions.end(), {float(2 * a - b), float(a), float(b)}); break;
                }
            }
            BuildSettings settings;
            StoreData d;
            try {
                d = tetprobe::build_store_data(positions.data(), 12, nullptr, 108, size_t(count), settings);
            } catch (const tetprobe::Error&) {
                continue;  // fewer than three distinct probes off one line: not this test's concern
            }
            if (d.dimension != 2) continue;
            INFO("trial " << trial << " kind " << kind);
            structure::check_all(d);
            // Stored exactly as given: the local position is the input minus the origin, rounded once.
            for (size_t i = 0; i < size_t(count); ++i) {
                const uint32_t s = d.input_remap[i];
                if (d.probe_source[s] != i) continue;
                for (int c = 0; c < 3; ++c) REQUIRE(d.positions[3 * s + c] == float(double(positions[3 * i + c]) - d.origin[c]));
            }
            // No sliver: with integer coordinates in [-4, 4] a real triangle's area is at least 1/2.
            for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
                const reference::Vec p0 = reference::position(d, d.cell_vertices[4 * c]);
                const reference::Vec p1 = reference::position(d, d.cell_vertices[4 * c + 1]);
                const reference::Vec p2 = reference::position(d, d.cell_vertices[4 * c + 2]);
                REQUIRE((p1 - p0).cross(p2 - p0).norm() > 0.5);
            }
            require_exact_at_inputs(d, positions);
        }
    }
}

TEST_CASE("builder: inner rows are anchored at each cell's most central probe", "[builder]") {
    // The rows' float error grows with the distance from the slot-d probe they are relative to, so
    // that slot holds the probe nearest the cell's centroid (needle cells: a near probe, not the far
    // one); the permutation is even, so every cell keeps its positive orientation.
    for (const families::ProbeSet& set : {families::dense_room_in_a_level(5), families::plane(50, 6)}) {
        const StoreData d = build(set.positions);
        structure::check_all(d);
        const uint32_t dim = d.dimension;
        for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
            reference::Vec centroid = reference::Vec::Zero();
            for (uint32_t k = 0; k <= dim; ++k) centroid += reference::position(d, d.cell_vertices[4 * c + k]) / double(dim + 1);
            const double anchor = (reference::position(d, d.cell_vertices[4 * c + dim]) - centroid).squaredNorm();
            for (uint32_t k = 0; k < dim; ++k)
                REQUIRE(anchor <= (reference::position(d, d.cell_vertices[4 * c + k]) - centroid).squaredNorm());
            for (uint32_t k = 0; k < dim; ++k) REQUIRE(d.inner_matrices[12 * c + 4 * k + 3] == 0.0f);
            const reference::Vec p0 = reference::position(d, d.cell_vertices[4 * c]);
            const reference::Vec e1 = reference::position(d, d.cell_vertices[4 * c + 1]) - p0;
            const reference::Vec e2 = reference::position(d, d.cell_vertices[4 * c + 2]) - p0;
            const double orientation = dim == 3 ? e1.cross(e2).dot(reference::position(d, d.cell_vertices[4 * c + 3]) - p0)
                                                : e1.cross(e2).dot(reference::plane_normal(d));
            REQUIRE(orientation >= 0);
        }
    }
}

TEST_CASE("builder: a needle on the hull is not peeled as a sliver", "[builder]") {
    // Found by fuzz_build: near the hull a needle cell (three probes close together, one far away)
    // has almost no volume relative to its longest edge, but peeling it left the probe at
    // (0.86, -1.05e15, 0) 1e-4 of the set's size beyond a new hull facet, whose outer cell then
    // answered a query at that probe. Peeling now requires every probe to stay that close.
    const std::vector<float> positions = {-2.3038981e-02f, 4.5559e-41f, 1.076e-42f, -9.228156e+18f, -2.5245947e-29f,
                                          1.36e-43f, 1.8525781e+02f, 1.6495023e-33f, 1.6495023e-33f, 1.6495023e-33f,
                                          1.6495023e-33f, 6.1743466e+16f, 6.1743466e+16f, 6.1743466e+16f,
                                          6.1743466e+16f, 8.568627e-01f, -1.0526106e+15f, -3.6268155e-14f};
    const StoreData d = build(positions);
    REQUIRE(d.dimension == 3);
    require_exact_at_inputs(d, positions);
}
