// The insertion gain's model of a probe inserted beyond the hull of the chosen ones (bake/insertion_gain.h).
#include <catch2/catch.hpp>

#include "bake/insertion_gain.h"
#include "bake/store_builder.h"
#include "core/store.h"
#include "core/store_data.h"

#include <memory>
#include <vector>

using namespace tetprobe;

namespace {

// One tetrahedron of probes and held-out candidates with their residuals (noise zero), as a round of
// placement sees them.
struct Round {
    std::unique_ptr<Store> store;
    RoundState state;
};

void make_round(const std::vector<float>& probes, const std::vector<float>& candidates,
                const std::vector<double>& residuals, Round* r) {
    const size_t n = probes.size() / 3, m = candidates.size() / 3;
    const std::vector<float> sh(27 * n, 0.0f);
    const StoreData data = build_store_data(probes.data(), 12, sh.data(), 108, n, BuildSettings{});
    const std::vector<uint8_t> blob = write_store_blob(data);
    r->store = Store::load(blob.data(), blob.size());
    RoundState& s = r->state;
    s.store = r->store.get();
    s.candidate_of_stored.resize(n);
    for (uint32_t p = 0; p < n; ++p) s.candidate_of_stored[p] = p;
    s.probe_noise.assign(n, 0.0f);
    s.cell.assign(m, -1);
    s.probes.assign(4 * m, 0);
    s.weights.assign(4 * m, 0.0f);
    size_t first_outside = 0;
    r->store->weights_batch(m, candidates.data(), 12, s.cell.data(), 4, s.probes.data(), 16, s.weights.data(), 16,
                            BatchSettings{}, &first_outside);
    s.residual = residuals;
    s.noise.assign(m, 0.0);
    s.active.assign(m, 1);
    s.local.resize(3 * m);
    const double* origin = r->store->header().origin;
    for (size_t i = 0; i < 3 * m; ++i) s.local[i] = float(double(candidates[i]) - origin[i % 3]);
    prepare_round(s);
}

}  // namespace

TEST_CASE("insertion gain: beyond the hull, points at the facet keep their values", "[placement]") {
    // The facet z = 0 of the tetrahedron faces up; three candidates stand above it in its outer cell: the
    // one inserted (2 m up, residual r), one as high (residual r) and one just above the facet (residual 0,
    // already right). Inserting the first makes the new cell from the facet to it: the high one takes its
    // residual, the low one barely changes (its coordinate is its height over the new probe's, 1/200).
    const std::vector<float> probes = {0, 0, 0, 4, 0, 0, 0, 4, 0, 0, 0, -4};
    const std::vector<float> candidates = {1.0f, 1.0f, 2.0f, 1.2f, 1.0f, 2.0f, 1.0f, 1.2f, 0.01f};
    std::vector<double> residuals(kSignalSize * 3, 0.0);
    for (int k = 0; k < kSignalSize; ++k) residuals[size_t(k)] = residuals[kSignalSize + size_t(k)] = 1.0;
    Round r;
    make_round(probes, candidates, residuals, &r);
    const RoundState& s = r.state;
    REQUIRE(s.store->header().dimension == 3);
    // All three in the same outer cell (beyond the hull).
    REQUIRE(s.cell[0] >= int32_t(s.store->header().inner_cell_count));
    REQUIRE(s.cell[1] == s.cell[0]);
    REQUIRE(s.cell[2] == s.cell[0]);
    const InsertionGain g = insertion_gain(s, 0);
    const double rr = kSignalSize;  // |r|^2
    // Its own error and its twin's are removed (the twin's phi is 1 at the same height, less the facet
    // split's lateral share), the low one loses at most phi^2 |r|^2 with phi <= 1/200.
    CHECK(g.gain > 1.8 * rr);
    CHECK(g.gain <= 2.0 * rr + 1e-9);
    CHECK(g.coverage < 2.01);
}
