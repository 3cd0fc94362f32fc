#include "bake/probe_pruning.h"

#include "bake/sampling.h"
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/sh.h"
#include "core/store.h"
#include "core/store_format.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <thread>
#include <vector>
#include <tuple>

namespace tetprobe {

namespace {

// Single-probe removals tried, cheapest first, before a round that would cross the bound stops pruning.
constexpr size_t kSingleTries = 8;

// A store of a subset of the probes, and its arrays (for the Delaunay neighbours).
struct SubsetStore {
    std::vector<uint32_t> probes;  // indices into the full set, ascending; the store's input order
    StoreData data;
    std::unique_ptr<Store> store;
};

class Pruner {
public:
    Pruner(const std::vector<float>& positions, const std::vector<float>& sh, const std::vector<float>& points,
           uint32_t threads)
        : positions_(positions), sh_(sh), points_(points), threads_(threads) {
        const size_t n = positions.size() / 3;
        irradiance_.resize(27 * n);
        for (size_t i = 0; i < n; ++i) irradiance_coefficients(&sh[27 * i], &irradiance_[27 * i]);
    }

    SubsetStore build(std::vector<uint32_t> probes) const {
        SubsetStore s;
        s.probes = std::move(probes);
        std::vector<float> p(3 * s.probes.size()), c(27 * s.probes.size());
        for (size_t i = 0; i < s.probes.size(); ++i) {
            std::copy_n(&positions_[3 * size_t(s.probes[i])], 3, &p[3 * i]);
            std::copy_n(&sh_[27 * size_t(s.probes[i])], 27, &c[27 * i]);
        }
        s.data = build_store_data(p.data(), 12, c.data(), 108, s.probes.size(), BuildSettings{});
        const std::vector<uint8_t> blob = write_store_blob(s.data);
        s.store = Store::load(blob.data(), blob.size());
        return s;
    }

    // range(begin, end) over [0, count) split into contiguous ranges on up to threads_ threads (the run
    // time's batches never start threads: the bake splits its own). Hint-less queries start from the
    // grid, so the answers do not depend on the split.
    template <class Range>
    void on_threads(size_t count, Range range) const {
        const size_t parts = std::max<size_t>(1, std::min<size_t>(std::max(1u, threads_), count / 4096));
        std::vector<std::thread> workers;
        for (size_t t = 1; t < parts; ++t) workers.emplace_back(range, count * t / parts, count * (t + 1) / parts);
        range(size_t(0), count / parts);
        for (std::thread& worker : workers) worker.join();
    }

    // Irradiance coefficients interpolated at every held-out point.
    std::vector<double> interpolate(const SubsetStore& s) const {
        const size_t count = points_.size() / 3;
        std::vector<float> out(27 * count);
        on_threads(count, [&](size_t begin, size_t end) {
            s.store->interpolate_batch(end - begin, &points_[3 * begin], 12, nullptr, 4, &out[27 * begin], 108,
                                       BatchSettings{}, nullptr);
        });
        std::vector<double> e(27 * count);
        for (size_t i = 0; i < count; ++i) irradiance_coefficients(&out[27 * i], &e[27 * i]);
        return e;
    }

    // Each held-out point's weight in the error: one over its reference irradiance squared, so dim and
    // bright places count alike (a floor of a thousandth of the mean keeps black points finite).
    void set_reference(const std::vector<double>& reference) {
        reference_ = reference;
        const size_t count = reference.size() / 27;
        std::vector<double> magnitude(count);
        double mean = 0;
        for (size_t i = 0; i < count; ++i) mean += (magnitude[i] = irradiance_rms(&reference[27 * i])) / double(count);
        point_weights_.resize(count);
        for (size_t i = 0; i < count; ++i) {
            const double m = std::max(magnitude[i], 1e-3 * mean);
            point_weights_[i] = m > 0 ? 1.0 / (m * m) : 1.0;
        }
    }

    // RMS over the held-out points of the relative irradiance change against the reference.
    double relative_error(const std::vector<double>& values) const {
        const size_t count = point_weights_.size();
        double sum = 0;
        for (size_t i = 0; i < count; ++i) {
            double d[27];
            for (int k = 0; k < 27; ++k) d[k] = values[27 * i + k] - reference_[27 * i + k];
            const double r = irradiance_rms(d);
            sum += r * r * point_weights_[i];
        }
        return count ? std::sqrt(sum / double(count)) : 0.0;
    }

    // The probes of s (as positions in s.probes) in order of their estimated removal cost.
    std::vector<uint32_t> removal_order(const SubsetStore& s, std::vector<std::vector<uint32_t>>* neighbours) const {
        const StoreData& d = s.data;
        const uint32_t stored = d.probe_count();
        // Delaunay neighbours, in the subset's input numbering.
        neighbours->assign(s.probes.size(), {});
        for (uint32_t c = 0; c < d.cell_count(); ++c) {
            const uint32_t* v = &d.cell_vertices[4 * size_t(c)];
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    if (a != b && v[a] < stored && v[b] < stored)
                        (*neighbours)[d.probe_source[v[a]]].push_back(d.probe_source[v[b]]);
        }
        for (auto& list : *neighbours) {
            std::sort(list.begin(), list.end());
            list.erase(std::unique(list.begin(), list.end()), list.end());
        }
        // Sum over held-out points of each probe's squared weight.
        const size_t count = points_.size() / 3;
        std::vector<uint32_t> cell_probes(4 * count);
        std::vector<float> weights(4 * count);
        on_threads(count, [&](size_t begin, size_t end) {
            s.store->weights_batch(end - begin, &points_[3 * begin], 12, nullptr, 4, &cell_probes[4 * begin], 16,
                                   &weights[4 * begin], 16, BatchSettings{}, nullptr);
        });
        std::vector<double> weight_squares(s.probes.size(), 0.0);
        for (size_t i = 0; i < 4 * count; ++i)
            weight_squares[s.store->probe_source(cell_probes[i])] += double(weights[i]) * weights[i] * point_weights_[i / 4];

        std::vector<std::tuple<double, double, uint32_t>> keyed(s.probes.size());
        for (uint32_t i = 0; i < s.probes.size(); ++i) {
            const double deviation = deviation_from_neighbours(s, i, (*neighbours)[i]);
            keyed[i] = std::make_tuple(deviation * deviation * weight_squares[i], deviation, i);
        }
        std::sort(keyed.begin(), keyed.end());
        std::vector<uint32_t> order(keyed.size());
        for (size_t i = 0; i < keyed.size(); ++i) order[i] = std::get<2>(keyed[i]);
        return order;
    }

private:
    // |E_p - A(p)|: p's irradiance against the affine fit of its neighbours' (RMS over normals and channels).
    double deviation_from_neighbours(const SubsetStore& s, uint32_t i, const std::vector<uint32_t>& neighbours) const {
        if (neighbours.empty()) return 0.0;
        const float* p = &positions_[3 * size_t(s.probes[i])];
        const Eigen::Index k = Eigen::Index(neighbours.size());
        Eigen::MatrixXd design(k, 4), values(k, 27);
        double scale = 0;
        for (Eigen::Index r = 0; r < k; ++r) {
            const float* q = &positions_[3 * size_t(s.probes[neighbours[size_t(r)]])];
            for (int a = 0; a < 3; ++a) scale = std::max(scale, std::abs(double(q[a]) - p[a]));
        }
        if (!(scale > 0)) scale = 1;
        for (Eigen::Index r = 0; r < k; ++r) {
            const uint32_t j = s.probes[neighbours[size_t(r)]];
            const float* q = &positions_[3 * size_t(j)];
            design(r, 0) = 1.0;
            for (int a = 0; a < 3; ++a) design(r, a + 1) = (double(q[a]) - p[a]) / scale;
            for (int c = 0; c < 27; ++c) values(r, c) = irradiance_[27 * size_t(j) + c];
        }
        // The minimum-norm least-squares fit, so flat and collinear neighbourhoods fit in their own span.
        const Eigen::MatrixXd fit = design.completeOrthogonalDecomposition().solve(values);
        double difference[27];
        for (int c = 0; c < 27; ++c) difference[c] = irradiance_[27 * size_t(s.probes[i]) + c] - fit(0, c);
        return irradiance_rms(difference);
    }

    const std::vector<float>& positions_;
    const std::vector<float>& sh_;
    const std::vector<float>& points_;
    uint32_t threads_;
    std::vector<double> irradiance_;     // 27 per probe
    std::vector<double> reference_;      // 27 per held-out point: what every candidate interpolates
    std::vector<double> point_weights_;  // per held-out point
};

}  // namespace

void irradiance_coefficients(const float sh[27], double out[27]) {
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 9; ++k) out[9 * c + k] = sh_cosine_lobe_band(k == 0 ? 0 : k < 4 ? 1 : 2) * sh[9 * c + k];
}

double irradiance_rms(const double coefficients[27]) {
    double sum = 0;
    for (int i = 0; i < 27; ++i) sum += coefficients[i] * coefficients[i];
    return std::sqrt(sum / (4.0 * kPi * 3.0));  // orthonormal basis: the mean of the square over the sphere
}

PruneResult prune_probes(const std::vector<float>& positions, const std::vector<float>& sh,
                         const std::vector<float>& held_out, const PruneSettings& settings,
                         const Progress& progress) {
    const uint32_t n = uint32_t(positions.size() / 3);
    PruneResult result;
    result.kept.resize(n);
    std::iota(result.kept.begin(), result.kept.end(), 0u);
    result.curve.push_back({n, 0.0});
    const bool target = settings.target_count > 0, bound = settings.error_bound > 0;
    if (n == 0 || (!target && !bound) || (target && settings.target_count >= n)) return result;

    // Removed probes are held out too: their own baked light is what the full set gives there.
    std::vector<float> points = held_out;
    points.insert(points.end(), positions.begin(), positions.end());
    Pruner pruner(positions, sh, points, settings.threads);
    SubsetStore current = pruner.build(result.kept);
    pruner.set_reference(pruner.interpolate(current));
    progress.report(0.0, "prune");

    // Near the bound batches shrink; a round starts at twice the last accepted batch, not a tenth again.
    size_t batch_limit = SIZE_MAX;
    while (current.probes.size() > 1 && (!target || current.probes.size() > settings.target_count)) {
        const size_t size = current.probes.size();
        std::vector<std::vector<uint32_t>> neighbours;
        const std::vector<uint32_t> order = pruner.removal_order(current, &neighbours);
        size_t batch = std::min(batch_limit, std::max<size_t>(1, size / 10));
        if (target) batch = std::min(batch, size - settings.target_count);
        // Single probes whose removal alone crossed the bound, skipped this round.
        std::vector<uint8_t> rejected(size, 0);
        size_t rejections = 0;
        bool accepted = false;
        while (!accepted) {
            // The cheapest probes of which no two are neighbours.
            std::vector<uint8_t> removed(size, 0), blocked(rejected);
            size_t chosen = 0, single = 0;
            for (uint32_t i : order) {
                if (chosen == batch) break;
                if (blocked[i]) continue;
                removed[i] = 1, ++chosen, single = i;
                for (uint32_t j : neighbours[i]) blocked[j] = 1;
            }
            if (chosen == 0) break;
            std::vector<uint32_t> rest;
            for (size_t i = 0; i < size; ++i)
                if (!removed[i]) rest.push_back(current.probes[i]);
            SubsetStore trial = pruner.build(std::move(rest));
            const double error = pruner.relative_error(pruner.interpolate(trial));
            if (bound && error > settings.error_bound) {
                if (chosen > 1) {
                    batch = chosen / 2;
                } else {
                    // The estimate misjudged this one: try the next cheapest few before giving up.
                    rejected[single] = 1;
                    if (++rejections == kSingleTries) break;
                }
                continue;
            }
            if (bound) batch_limit = 2 * chosen;
            current = std::move(trial);
            result.curve.push_back({uint32_t(current.probes.size()), error});
            accepted = true;
            double done = target ? double(n - current.probes.size()) / double(n - settings.target_count)
                                 : error / settings.error_bound;
            progress.report(done, "prune");
        }
        if (!accepted) break;
    }
    result.kept = current.probes;
    return result;
}

}  // namespace tetprobe
