#include "bake/probe_selection.h"

#include "bake/insertion_gain.h"
#include "bake/parallel_jobs.h"
#include "bake/sampling.h"
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/store_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace tetprobe {

namespace {

// The well-spread start (its hull holds most candidates, so few insertions fall outside the hull, where
// the gain's model is a cell's split only), the batches' largest growth, and the candidates of a cell
// whose gain is computed (half the largest residuals, half spread over the cell).
constexpr uint32_t kStartProbes = 16;
constexpr double kGrowth = 0.25;
constexpr size_t kTrialsPerCell = 8;
// The exchanges at the target: the best insertions one step tries (no two in cells that share a probe),
// and the probes all their stores may hold together, a try at n probes counted as (n + 1)(n + 2) (n stores
// of n, as if no star were known from an earlier try, and the grown and exchanged sets), so sets of a
// thousand or more get none. Below that the cap does not bind at small n: the bound is at most n steps of
// kExchangeProposals tries, each evaluating every candidate up to twice, far above the greedy's few
// rounds. bench_levels' equal-memory part relies on a 4,000 target getting no exchange (its prefixes are
// the greedy's sets).
constexpr size_t kExchangeProposals = 4;
constexpr size_t kExchangeWork = 1000000;
// The share of the selection's progress the greedy reports into when an exchange follows (where one runs,
// it takes about as long as the greedy).
constexpr double kGreedyShare = 0.5;

// Whether a set of n probes gets exchanges: a removal must leave more than one cell's probes for the
// held-out error to rank removals by (fewer than 5 is the start's spread alone), and every try fits the cap.
bool exchange_fits(size_t n) { return n >= 5 && (n + 1) * (n + 2) <= kExchangeWork; }

// A cell by its vertices (candidate indices, sorted; an outer cell's marker kept): the same key in two
// rounds is the same cell.
using CellKey = std::array<uint32_t, 4>;
struct CellKeyHash {
    size_t operator()(const CellKey& k) const {
        uint64_t h = 0;
        for (uint32_t v : k) h = mix64(h ^ v);
        return size_t(h);
    }
};

CellKey key_of(const RoundState& s, uint32_t cell) {
    uint32_t v[4], n[4];
    s.store->cell(cell, v, n);
    CellKey k;
    for (int i = 0; i < 4; ++i) k[size_t(i)] = v[i] < s.candidate_of_stored.size() ? s.candidate_of_stored[v[i]] : v[i];
    std::sort(k.begin(), k.end());
    return k;
}

// The best insertion a cell offers this round.
struct CellChoice {
    bool significant = false;
    double key = 0;          // the trusted gain, or the coverage
    uint32_t candidate = 0;
    std::vector<uint32_t> cavity;
};

class Selector {
public:
    Selector(const SignalPoints& candidates, const SignalPoints& validation, uint32_t threads)
        : c_(candidates), v_(validation), threads_(std::max(1u, threads)) {
        count_ = c_.positions.size() / 3;
        double sum = 0;
        size_t n = 0;
        for (size_t i = 0; i < v_.positions.size() / 3; ++i)
            if (v_.counted[i]) {
                for (int k = 0; k < kSignalSize; ++k) sum += v_.signal.value[kSignalSize * i + size_t(k)];
                ++n;
            }
        mean_ = n ? sum / double(kSignalSize * n) : 0.0;
    }

    size_t count() const { return count_; }

    // Farthest points among the counted candidates, from the one nearest their centroid.
    std::vector<uint32_t> start(size_t n) const {
        std::vector<uint32_t> pool;
        for (uint32_t i = 0; i < count_; ++i)
            if (c_.counted[i]) pool.push_back(i);
        std::vector<uint32_t> chosen;
        if (pool.empty() || n == 0) return chosen;
        double centre[3] = {0, 0, 0};
        for (uint32_t i : pool)
            for (int a = 0; a < 3; ++a) centre[a] += double(c_.positions[3 * size_t(i) + size_t(a)]) / double(pool.size());
        std::vector<double> distance(pool.size());
        auto squared = [&](uint32_t i, const double* q) {
            double d = 0;
            for (int a = 0; a < 3; ++a) d += (c_.positions[3 * size_t(i) + size_t(a)] - q[a]) * (c_.positions[3 * size_t(i) + size_t(a)] - q[a]);
            return d;
        };
        size_t next = 0;
        for (size_t k = 0; k < pool.size(); ++k)
            if (squared(pool[k], centre) < squared(pool[next], centre)) next = k;
        std::fill(distance.begin(), distance.end(), INFINITY);
        while (chosen.size() < std::min(n, pool.size())) {
            chosen.push_back(pool[next]);
            double q[3];
            for (int a = 0; a < 3; ++a) q[a] = c_.positions[3 * size_t(pool[next]) + size_t(a)];
            size_t far = 0;
            for (size_t k = 0; k < pool.size(); ++k) {
                distance[k] = std::min(distance[k], squared(pool[k], q));
                if (distance[k] > distance[far]) far = k;
            }
            next = far;
        }
        return chosen;
    }

    std::unique_ptr<Store> build(const std::vector<uint32_t>& chosen) const {
        std::vector<float> positions(3 * chosen.size()), sh(27 * chosen.size(), 0.0f);
        for (size_t i = 0; i < chosen.size(); ++i) std::copy_n(&c_.positions[3 * size_t(chosen[i])], 3, &positions[3 * i]);
        const StoreData data = build_store_data(positions.data(), 12, sh.data(), 108, chosen.size(), BuildSettings{});
        const std::vector<uint8_t> blob = write_store_blob(data);
        return Store::load(blob.data(), blob.size());
    }

    // Every point's cell, probes and weights (each query from the start grid, so the cell a point on a
    // shared facet lands in does not depend on how the batch was split among threads).
    void locate(const Store& store, const std::vector<float>& positions, std::vector<int32_t>* cells,
                std::vector<uint32_t>* probes, std::vector<float>* weights) const {
        const size_t n = positions.size() / 3;
        cells->assign(n, -1);
        probes->assign(4 * n, 0);
        weights->assign(4 * n, 0.0f);
        // Batches never start threads: this one is split into disjoint ranges over bake's job runner.
        constexpr size_t kChunk = 2048;
        run_jobs((n + kChunk - 1) / kChunk, threads_, [&](size_t job) {
            const size_t first = job * kChunk, count = std::min(kChunk, n - first);
            size_t first_outside = 0;
            store.weights_batch(count, &positions[3 * first], 12, &(*cells)[first], 4, &(*probes)[4 * first], 16,
                                &(*weights)[4 * first], 16, BatchSettings{}, &first_outside);
        }, Progress{}, "locate");
    }

    // A point's residual r (its baked value minus the interpolation of the candidates candidate(q) with
    // weights w[q]) from its own value and noise; returns the residual's noise (its own and the probes').
    template <class CandidateOf>
    double residual_of(const float* value, double noise, const float* w, CandidateOf candidate, double* r) const {
        for (int k = 0; k < kSignalSize; ++k) r[k] = value[k];
        for (int q = 0; q < 4; ++q) {
            if (w[q] == 0) continue;
            const uint32_t c = candidate(q);
            for (int k = 0; k < kSignalSize; ++k) r[k] -= double(w[q]) * c_.signal.value[kSignalSize * size_t(c) + size_t(k)];
            noise += double(w[q]) * double(w[q]) * c_.signal.noise[c];
        }
        return noise;
    }

    // The error estimate at the validation points (see probe_selection.h).
    double estimate(const Store& store, const std::vector<uint32_t>& chosen) const {
        if (!(mean_ > 0)) return 0.0;
        std::vector<int32_t> cells;
        std::vector<uint32_t> probes;
        std::vector<float> weights;
        locate(store, v_.positions, &cells, &probes, &weights);
        double sum = 0;
        size_t n = 0;
        for (size_t i = 0; i < v_.positions.size() / 3; ++i) {
            if (!v_.counted[i]) continue;
            double r[kSignalSize];
            const double noise = residual_of(&v_.signal.value[kSignalSize * i], v_.signal.noise[i], &weights[4 * i],
                                             [&](int q) { return chosen[store.probe_source(probes[4 * i + size_t(q)])]; }, r);
            for (double x : r) sum += x * x;
            sum -= noise;
            ++n;
        }
        return n ? std::sqrt(std::max(0.0, sum / double(kSignalSize * n))) / mean_ : 0.0;
    }

    // What the round knows about every candidate (insertion_gain.h).
    void evaluate(const Store& store, const std::vector<uint32_t>& chosen, const std::vector<uint8_t>& in_set,
                  RoundState* s) const {
        s->store = &store;
        const uint32_t stored = store.header().probe_count;
        s->candidate_of_stored.resize(stored);
        s->probe_noise.resize(stored);
        for (uint32_t p = 0; p < stored; ++p) {
            s->candidate_of_stored[p] = chosen[store.probe_source(p)];
            s->probe_noise[p] = c_.signal.noise[s->candidate_of_stored[p]];
        }
        locate(store, c_.positions, &s->cell, &s->probes, &s->weights);
        s->residual.assign(kSignalSize * count_, 0.0);
        s->noise.assign(count_, 0.0);
        s->active.assign(count_, 0);
        s->local.resize(3 * count_);
        const double* origin = store.header().origin;
        for (size_t i = 0; i < count_; ++i) {
            for (int a = 0; a < 3; ++a) s->local[3 * i + size_t(a)] = float(double(c_.positions[3 * i + size_t(a)]) - origin[a]);
            if (in_set[i]) continue;
            s->active[i] = c_.counted[i] && s->cell[i] >= 0;
            s->noise[i] = residual_of(&c_.signal.value[kSignalSize * i], c_.signal.noise[i], &s->weights[4 * i],
                                      [&](int q) { return s->candidate_of_stored[s->probes[4 * i + size_t(q)]]; },
                                      &s->residual[kSignalSize * i]);
        }
        prepare_round(*s);
    }

    // Up to `want` candidates to insert, best first, no two in cells that share a probe. A cell whose
    // choice was made in an earlier round keeps it while every cell the choice read (its cavity and the
    // cells around it) is still there: the gain depends on nothing else, so only cells near the last
    // insertions are computed again.
    std::vector<uint32_t> choose(const RoundState& s, size_t want) {
        const uint32_t cell_count = s.store->header().cell_count;
        std::vector<CellKey> keys(cell_count);
        std::unordered_map<CellKey, uint32_t, CellKeyHash> current;
        current.reserve(cell_count);
        for (uint32_t c = 0; c < cell_count; ++c) current.emplace(keys[c] = key_of(s, c), c);
        std::vector<uint32_t> cells;
        for (uint32_t c = 0; c + 1 < s.cell_start.size(); ++c)
            if (s.cell_start[c + 1] > s.cell_start[c]) cells.push_back(c);
        std::vector<CellChoice> choices(cells.size());
        std::vector<std::vector<CellKey>> supports(cells.size());
        std::vector<size_t> fresh;
        for (size_t k = 0; k < cells.size(); ++k) {
            const auto it = cache_.find(keys[cells[k]]);
            bool valid = it != cache_.end();
            for (size_t q = 0; valid && q < it->second.support.size(); ++q) valid = current.count(it->second.support[q]) > 0;
            if (!valid) {
                fresh.push_back(k);
                continue;
            }
            CellChoice& c = choices[k];
            c.significant = it->second.significant, c.key = it->second.key, c.candidate = it->second.candidate;
            for (const CellKey& key : it->second.cavity) c.cavity.push_back(current.at(key));
            supports[k] = std::move(it->second.support);
        }
        run_jobs(fresh.size(), threads_, [&](size_t f) {
            const size_t k = fresh[f];
            choices[k] = best_in_cell(s, cells[k]);
            std::vector<uint32_t> read = choices[k].cavity;
            for (uint32_t c : choices[k].cavity) {
                uint32_t v[4], n[4];
                s.store->cell(c, v, n);
                for (uint32_t x : n)
                    if (x < cell_count) read.push_back(x);
            }
            std::sort(read.begin(), read.end());
            read.erase(std::unique(read.begin(), read.end()), read.end());
            for (uint32_t c : read) supports[k].push_back(keys[c]);
        }, {}, "select");
        cache_.clear();
        for (size_t k = 0; k < cells.size(); ++k) {
            CachedChoice& e = cache_[keys[cells[k]]];
            e.significant = choices[k].significant, e.key = choices[k].key, e.candidate = choices[k].candidate;
            for (uint32_t c : choices[k].cavity) e.cavity.push_back(keys[c]);
            e.support = std::move(supports[k]);
        }
        std::vector<size_t> order(cells.size());
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
            const CellChoice &x = choices[a], &y = choices[b];
            return std::make_tuple(!x.significant, -x.key, x.candidate) < std::make_tuple(!y.significant, -y.key, y.candidate);
        });
        std::vector<uint8_t> blocked(s.candidate_of_stored.size(), 0);
        std::vector<uint32_t> batch;
        bool significant = false;
        for (size_t k : order) {
            if (batch.size() == want) break;
            const CellChoice& choice = choices[k];
            // Coverage only where nothing stands out: a round with trusted gains waits for the next
            // round's measurements rather than spend probes on guesses.
            if (!choice.significant && significant) break;
            uint32_t v[4], n[4];
            s.store->cell(choice.cavity.front(), v, n);
            bool free = true;
            for (uint32_t p : v) free = free && (p >= blocked.size() || !blocked[p]);
            if (!free) continue;
            for (uint32_t p : v)
                if (p < blocked.size()) blocked[p] = 1;
            batch.push_back(choice.candidate);
            significant = significant || choice.significant;
        }
        return batch;
    }

    // The held-out error of a round: per candidate, its noise-corrected squared residual (0 unless active)
    // and that term's variance; summed, the quantity every insertion lowers (insertion_gain.h).
    struct HeldOutTerms {
        std::vector<double> term, variance;
        double sum = 0;
    };
    static HeldOutTerms held_out_terms(const RoundState& s) {
        HeldOutTerms t;
        t.term.assign(s.active.size(), 0.0);
        t.variance.assign(s.active.size(), 0.0);
        for (size_t x = 0; x < s.active.size(); ++x) {
            if (!s.active[x]) continue;
            const double rr = squared_residual(s, uint32_t(x));
            t.term[x] = rr - s.noise[x];
            t.variance[x] = squared_residual_variance(rr, s.noise[x]);
            t.sum += t.term[x];
        }
        return t;
    }

    // The held-out error's change if probe `removed` (an index into chosen) left the probes of round s:
    // only the candidates it interpolates (and itself, held out again) change, located in the store
    // built without it.
    double removal_change(const HeldOutTerms& terms, const std::vector<uint32_t>& chosen,
                          size_t removed, const std::vector<uint32_t>& affected) const {
        std::vector<uint32_t> rest(chosen);
        rest.erase(rest.begin() + std::ptrdiff_t(removed));
        const std::unique_ptr<Store> store = build(rest);
        std::vector<float> positions(3 * affected.size());
        for (size_t k = 0; k < affected.size(); ++k) std::copy_n(&c_.positions[3 * size_t(affected[k])], 3, &positions[3 * k]);
        std::vector<int32_t> cells(affected.size(), -1);
        std::vector<uint32_t> probes(4 * affected.size(), 0);
        std::vector<float> weights(4 * affected.size(), 0.0f);
        size_t first_outside = 0;
        store->weights_batch(affected.size(), positions.data(), 12, cells.data(), 4, probes.data(), 16, weights.data(), 16,
                             BatchSettings{}, &first_outside);
        double change = 0;
        for (size_t k = 0; k < affected.size(); ++k) {
            const uint32_t x = affected[k];
            if (cells[k] < 0) continue;
            double r[kSignalSize];
            const double noise = residual_of(&c_.signal.value[kSignalSize * size_t(x)], c_.signal.noise[x], &weights[4 * k],
                                             [&](int q) { return rest[store->probe_source(probes[4 * k + size_t(q)])]; }, r);
            double rr = 0;
            for (double v : r) rr += v * v;
            change += rr - noise - terms.term[x];
        }
        return change;
    }

    // Exchanges at the target. The greedy never takes a probe back: the start is chosen for spread alone
    // and early insertions for a coarse set's errors, so a small set keeps probes a later one made
    // redundant. A step tries the round's best insertions in turn: one goes in and the probe whose removal
    // then costs least goes out, kept only when the held-out error (the insertion gain's sum, measured
    // with the stores built) drops by more than the noise of the terms that changed. The validation points
    // stay out of it, so the error reported for the result is still measured where nothing was fitted.
    // Returns whether an exchange was kept. Reports into `progress` per step (cancel included).
    bool exchange(std::vector<uint32_t>* chosen, std::vector<uint8_t>* in_set, const Progress& progress) {
        size_t work = 0;
        const size_t n = chosen->size();
        if (!exchange_fits(n)) return false;
        double done = 0;  // the larger of the steps' and the work's share of their caps
        progress.report(0.0, "exchange");
        RoundState state;
        std::unique_ptr<Store> store = build(*chosen);
        evaluate(*store, *chosen, *in_set, &state);
        HeldOutTerms terms = held_out_terms(state);
        std::unordered_map<uint32_t, std::pair<std::vector<CellKey>, double>> removal_cache;  // by candidate
        // One exchange: candidate b in, the probe whose removal then costs least out; true when kept.
        auto try_exchange = [&](uint32_t b) {
            std::vector<uint32_t> grown(*chosen);
            grown.push_back(b);
            std::vector<uint8_t> grown_in(*in_set);
            grown_in[b] = 1;
            RoundState with;
            const std::unique_ptr<Store> with_store = build(grown);
            evaluate(*with_store, grown, grown_in, &with);
            const HeldOutTerms with_terms = held_out_terms(with);
            // An insertion that does not lower the error itself: no removal after it can make up for it.
            if (!(with_terms.sum < terms.sum)) return false;
            // Per probe of the grown set (by its place in grown): the candidates it interpolates.
            std::vector<std::vector<uint32_t>> affected(grown.size());
            std::vector<uint32_t> place_of_stored(with.candidate_of_stored.size());
            for (uint32_t p = 0; p < with.candidate_of_stored.size(); ++p) place_of_stored[p] = with_store->probe_source(p);
            for (size_t x = 0; x < count_; ++x) {
                if (!with.active[x]) continue;
                for (int q = 0; q < 4; ++q)
                    if (with.weights[4 * x + size_t(q)] != 0) affected[place_of_stored[with.probes[4 * x + size_t(q)]]].push_back(uint32_t(x));
            }
            for (size_t k = 0; k < n; ++k)
                if (c_.counted[grown[k]]) affected[k].push_back(grown[k]);
            // A removal's change depends almost only on the probe's star (the cells around it; also the hull
            // normals of its link, and ties on degenerate sets): one whose star is as in an earlier try keeps
            // that try's change, and only the stars near the exchanges so far are built again. A cached
            // change only picks the probe to try; the kept set is measured in full.
            std::vector<std::vector<CellKey>> star(grown.size());
            const uint32_t cell_count = with_store->header().cell_count;
            for (uint32_t c = 0; c < cell_count; ++c) {
                uint32_t v[4], neighbours[4];
                with_store->cell(c, v, neighbours);
                const CellKey key = key_of(with, c);
                for (uint32_t p : v)
                    if (p < place_of_stored.size()) star[place_of_stored[p]].push_back(key);
            }
            std::vector<double> change(n);
            std::vector<uint8_t> known(n, 0);
            for (size_t k = 0; k < n; ++k) {
                std::sort(star[k].begin(), star[k].end());
                const auto it = removal_cache.find(grown[k]);
                if (it != removal_cache.end() && it->second.first == star[k]) change[k] = it->second.second, known[k] = 1;
            }
            run_jobs(n, threads_, [&](size_t k) {
                if (known[k]) return;
                std::sort(affected[k].begin(), affected[k].end());
                affected[k].erase(std::unique(affected[k].begin(), affected[k].end()), affected[k].end());
                change[k] = removal_change(with_terms, grown, k, affected[k]);
            }, progress.part(done, done), "exchange");
            for (size_t k = 0; k < n; ++k) removal_cache[grown[k]] = {std::move(star[k]), change[k]};
            work += (n + 1) * (n + 2);
            size_t out = 0;
            for (size_t k = 1; k < n; ++k)
                if (change[k] < change[out]) out = k;
            // The exchanged set, measured in full against the current one.
            std::vector<uint32_t> next(*chosen);
            next[out] = b;
            std::vector<uint8_t> next_in(*in_set);
            next_in[(*chosen)[out]] = 0, next_in[b] = 1;
            RoundState after;
            std::unique_ptr<Store> after_store = build(next);
            evaluate(*after_store, next, next_in, &after);
            // A candidate the exchanged set's store no longer reaches would stop counting and lower the sum
            // for free (a hull probe out where the outer cells do not cover it): such an exchange is refused.
            for (size_t x = 0; x < count_; ++x)
                if (x != b && state.active[x] && !after.active[x]) return false;
            HeldOutTerms after_terms = held_out_terms(after);
            double variance = 0;
            for (size_t x = 0; x < count_; ++x)
                if (after_terms.term[x] != terms.term[x]) variance += after_terms.variance[x] + terms.variance[x];
            if (!(terms.sum - after_terms.sum > kSignificance * std::sqrt(variance))) return false;
            *chosen = std::move(next), *in_set = std::move(next_in);
            store = std::move(after_store), state = std::move(after), terms = std::move(after_terms);
            state.store = store.get();
            return true;
        };
        bool changed = false;
        for (size_t step = 0; step < n; ++step) {
            done = std::max(double(step) / double(n), double(work) / double(kExchangeWork));
            progress.report(done, "exchange");
            bool kept = false;
            for (uint32_t b : choose(state, kExchangeProposals)) {
                if (work + (n + 1) * (n + 2) > kExchangeWork) return changed;
                if ((kept = try_exchange(b))) break;
            }
            if (!kept) break;
            changed = true;
        }
        return changed;
    }

private:
    // |interpolated - baked|² at candidate x, over the signal's components.
    static double squared_residual(const RoundState& s, uint32_t x) {
        const double* r = &s.residual[kSignalSize * size_t(x)];
        double rr = 0;
        for (int k = 0; k < kSignalSize; ++k) rr += r[k] * r[k];
        return rr;
    }

    // The variance of a squared residual rr whose expected noise part is noise: the noise's cross term with
    // the true residual and its own square (Gaussian noise per component).
    static double squared_residual_variance(double rr, double noise) {
        const double true_part = std::max(0.0, rr - noise);
        return (4.0 * true_part * noise + 2.0 * noise * noise) / kSignalSize;
    }

    // Whether the members' summed squared residual exceeds their noise by more than its standard
    // deviation: a sum over every member, so picking the largest of many noisy residuals does not make
    // pure noise stand out.
    static bool error_stands_out(const RoundState& s, const uint32_t* first, size_t members) {
        double excess = 0, variance = 0;
        for (size_t m = 0; m < members; ++m) {
            const uint32_t x = first[m];
            const double rr = squared_residual(s, x);
            excess += rr - s.noise[x];
            variance += squared_residual_variance(rr, s.noise[x]);
        }
        return excess > kSignificance * std::sqrt(variance);
    }

    CellChoice best_in_cell(const RoundState& s, uint32_t cell) const {
        const uint32_t* first = &s.cell_members[s.cell_start[cell]];
        const size_t members = s.cell_start[cell + 1] - s.cell_start[cell];
        const size_t per_cell = kTrialsPerCell;
        std::vector<uint32_t> trials;
        if (members <= per_cell) {
            trials.assign(first, first + members);
        } else {
            std::vector<std::pair<double, uint32_t>> excess(members);
            for (size_t m = 0; m < members; ++m) {
                const uint32_t x = first[m];
                excess[m] = {-(squared_residual(s, x) - s.noise[x]), x};
            }
            std::partial_sort(excess.begin(), excess.begin() + per_cell / 2, excess.end());
            for (size_t m = 0; m < per_cell / 2; ++m) trials.push_back(excess[m].second);
            for (size_t m = 0; m < per_cell / 2; ++m) trials.push_back(first[(2 * m + 1) * members / per_cell]);
            std::sort(trials.begin(), trials.end());
            trials.erase(std::unique(trials.begin(), trials.end()), trials.end());
        }
        CellChoice best, cover, own;
        for (uint32_t x : trials) {
            InsertionGain g = insertion_gain(s, x);
            // What inserting x removes at x itself, whatever the model says of its neighbours (trusted as
            // the gain is: less a standard deviation of its noise).
            const double rr = squared_residual(s, x);
            const double own_trusted = rr - s.noise[x] - kSignificance * std::sqrt(squared_residual_variance(rr, s.noise[x]));
            if (own_trusted > 0 && (own.cavity.empty() || own_trusted > own.key)) own.key = own_trusted, own.candidate = x, own.cavity = g.cavity;
            const double trusted = g.gain - kSignificance * g.deviation;
            if (trusted > 0 && (!best.significant || trusted > best.key)) {
                best.significant = true, best.key = trusted, best.candidate = x, best.cavity = g.cavity;
            }
            if (cover.cavity.empty() || g.coverage > cover.key) cover.key = g.coverage, cover.candidate = x, cover.cavity = std::move(g.cavity);
        }
        if (best.significant) return best;
        // Beyond the hull the model is a split of one outer cell, which can hold a whole region the probes
        // have not reached (bright and dark points mixed): no single insertion is predicted to gain there,
        // and ranked by coverage behind every trusted gain it would never get a probe. A point the probes
        // miss by more than its noise is inserted instead, ranked by the error it removes at itself.
        if (cell >= s.store->header().inner_cell_count && !own.cavity.empty() && error_stands_out(s, first, members)) {
            own.significant = true;
            return own;
        }
        return cover;
    }

    struct CachedChoice {
        bool significant = false;
        double key = 0;
        uint32_t candidate = 0;
        std::vector<CellKey> cavity, support;
    };

    const SignalPoints& c_;
    const SignalPoints& v_;
    std::unordered_map<CellKey, CachedChoice, CellKeyHash> cache_;
    uint32_t threads_;
    size_t count_ = 0;
    double mean_ = 0;
};

}  // namespace

Selection select_probes(const SignalPoints& candidates, const SignalPoints& validation, const SelectionSettings& settings,
                        const Progress& progress) {
    Selector selector(candidates, validation, settings.threads);
    const size_t count = selector.count();
    const size_t target = settings.target_count ? std::min<size_t>(settings.target_count, count) : count;
    Selection result;
    result.order = selector.start(std::min<size_t>(kStartProbes, target));
    std::vector<uint8_t> in_set(count, 0);
    for (uint32_t i : result.order) in_set[i] = 1;
    // The greedy reports into its share, the exchange (where one can run) into the rest.
    const bool exchanges = settings.exchange && settings.target_count && target < count && exchange_fits(target);
    const Progress greedy = progress.part(0.0, exchanges ? kGreedyShare : 1.0);
    greedy.report(0.0, "select");
    const double log_span = std::log(std::max(2.0, double(target) / kStartProbes));
    // Candidates no round would insert (none counts) fill a target beyond the counted ones, in order.
    auto fill = [&] {
        for (uint32_t i = 0; i < count && result.order.size() < target; ++i)
            if (!in_set[i]) result.order.push_back(i), in_set[i] = 1;
    };
    if (result.order.empty()) fill();
    std::vector<uint32_t> previous_batch;
    std::unique_ptr<Store> store = selector.build(result.order);
    for (;;) {
        const double error = selector.estimate(*store, result.order);
        result.curve.push_back({uint32_t(result.order.size()), error});
        const size_t n = result.order.size();
        greedy.report(settings.target_count ? std::log(double(n) / kStartProbes) / log_span
                                              : std::min(1.0, settings.error_bound / std::max(error, 1e-300)),
                        "select");
        if (n >= target || (!settings.target_count && settings.error_bound > 0 && error <= settings.error_bound)) break;
        RoundState state;
        selector.evaluate(*store, result.order, in_set, &state);
        const size_t want = std::min(target - n, std::max<size_t>(1, size_t(std::ceil(kGrowth * double(n)))));
        std::vector<uint32_t> batch = selector.choose(state, want);
        if (batch.empty()) {
            fill();
            if (result.order.size() == n) break;
        }
        for (uint32_t i : batch) result.order.push_back(i), in_set[i] = 1;
        previous_batch = std::move(batch);
        store = selector.build(result.order);
    }
    // A target gets its own set: exchanged there, the probe that goes out replaced in the order by the one
    // that comes in, and the curve's last point measured again when one was kept.
    if (exchanges && result.order.size() == target &&
        selector.exchange(&result.order, &in_set, progress.part(kGreedyShare, 1.0)))
        result.curve.back().error = selector.estimate(*selector.build(result.order), result.order);
    // A bound met inside the last batch: the shortest prefix of it that meets it.
    if (!settings.target_count && settings.error_bound > 0 && result.curve.size() > 1 &&
        result.curve.back().error <= settings.error_bound && !previous_batch.empty()) {
        const size_t full = result.order.size(), base = full - previous_batch.size();
        size_t low = base, high = full;  // low fails (or is the previous round), high meets
        double high_error = result.curve.back().error;
        while (high - low > 1) {
            const size_t mid = (low + high) / 2;
            const std::vector<uint32_t> prefix(result.order.begin(), result.order.begin() + std::ptrdiff_t(mid));
            const double e = selector.estimate(*selector.build(prefix), prefix);
            if (e <= settings.error_bound) high = mid, high_error = e;
            else low = mid;
        }
        result.order.resize(high);
        result.curve.back() = {uint32_t(high), high_error};
    }
    return result;
}

}  // namespace tetprobe
