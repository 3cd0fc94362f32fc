// Store::interpolate and the batches: locate, then blend the four probes' half SH (the dispatched
// F16C path or the portable one, see half.h). Batches split into ranges, one per thread.
#include "core/half.h"
#include "core/leak_control.h"
#include "core/locate.h"
#include "core/store.h"
#include "core/store_impl.h"

#include <algorithm>
#include <cstring>
#include <thread>
#include <vector>

namespace tetprobe {

namespace {

void blend(const Store::Impl& s, const Location& loc, float out_sh[27]) {
    const uint16_t* sh[4];
    for (int k = 0; k < 4; ++k) sh[k] = s.sh + size_t(loc.probes[k]) * s.sh_halves;
    blend_sh_halves(sh, loc.weights, out_sh);
}

// Mixed lights' visibility at the location: the weighted occlusion bytes, in [0, 1]; 1 for channels
// the store has no light for (or a store without occlusion).
void blend_occlusion(const Store::Impl& s, const Location& loc, float out[4]) {
    for (uint32_t i = 0; i < kOcclusionChannels; ++i) out[i] = 1.0f;
    if (!s.occlusion) return;
    for (uint32_t i = 0; i < s.occlusion_lights; ++i) {
        float sum = 0;
        for (int k = 0; k < 4; ++k) sum += loc.weights[k] * float(s.occlusion[size_t(loc.probes[k]) * kOcclusionChannels + i]);
        const float value = sum / 255.0f;
        out[i] = value < 0 ? 0 : (value > 1 ? 1 : value);
    }
}

// Element i of a caller's strided buffer, as bytes: strides need no alignment, so every element is
// read and written with memcpy, never through a typed pointer.
const uint8_t* strided(const void* base, size_t i, size_t stride) { return static_cast<const uint8_t*>(base) + i * stride; }
uint8_t* strided(void* base, size_t i, size_t stride) { return static_cast<uint8_t*>(base) + i * stride; }

// Queries located before any is answered: their walks are independent, so the processor overlaps
// them, and the cells of the group after next are prefetched.
constexpr size_t kGroup = kMaxGroup;

// Runs the queries [begin, end) in groups: locate each (reading and writing the hints), then hand
// every location to answer(i, loc). Returns the first index that failed (or end), its status in *failure.
template <class Answer>
size_t run_range(const Store::Impl& s, size_t begin, size_t end, const float* positions, size_t position_stride,
                 int32_t* hints, size_t hint_stride, bool chain_hints, Answer answer, Status* failure) {
    size_t first_outside = end;
    int32_t chained = -1;
    Location located[kGroup];
    for (size_t group = begin; group < end; group += kGroup) {
        const size_t count = std::min(kGroup, end - group);
        if (hints) {
            const size_t ahead = group + 2 * kGroup;
            for (size_t i = ahead; i < std::min(ahead + kGroup, end); ++i) {
                int32_t hint;
                std::memcpy(&hint, strided(hints, i, hint_stride), sizeof hint);
                prefetch_cell(s, hint);
            }
        }
        float q[kGroup][3];
        int32_t start[kGroup];
        for (size_t j = 0; j < count; ++j) {
            const size_t i = group + j;
            float world[3];
            std::memcpy(world, strided(positions, i, position_stride), sizeof world);
            local_position(s, world, q[j]);
            start[j] = -1;
            if (hints) std::memcpy(&start[j], strided(hints, i, hint_stride), sizeof start[j]);
        }
        if (hints || !chain_hints) {
            locate_group(s, count, q, start, located);
        } else {  // each query starts where the previous one ended: one after the other
            for (size_t j = 0; j < count; ++j) {
                located[j] = locate_local(s, q[j], chained);
                chained = located[j].cell;
            }
        }
        for (size_t j = 0; j < count; ++j) {
            const size_t i = group + j;
            if (hints) std::memcpy(strided(hints, i, hint_stride), &located[j].cell, sizeof located[j].cell);
            if (located[j].status != Status::ok) {
                if (first_outside == end) first_outside = i, *failure = located[j].status;
            } else if (s.leak_offsets) {
                weigh_by_visibility(s, located[j]);
            }
        }
        for (size_t j = 0; j < count; ++j) answer(group + j, located[j]);
    }
    return first_outside;
}

// Smallest batch worth a thread of its own (spawning one costs tens of microseconds).
constexpr size_t kQueriesPerThread = 4096;

template <class Answer>
Status run_batch(const Store::Impl& s, size_t count, const float* positions, size_t position_stride, int32_t* hints,
                 size_t hint_stride, const BatchSettings& settings, size_t* first_outside, Answer answer) {
    const size_t threads =
        std::max<size_t>(1, std::min<size_t>(settings.threads, (count + kQueriesPerThread - 1) / kQueriesPerThread));
    std::vector<size_t> outside(threads, count);
    std::vector<Status> failure(threads, Status::ok);
    auto range = [&](size_t t) {
        const size_t begin = count * t / threads, end = count * (t + 1) / threads;
        const size_t first = run_range(s, begin, end, positions, position_stride, hints, hint_stride,
                                       settings.chain_hints, answer, &failure[t]);
        outside[t] = first < end ? first : count;
    };
    if (threads == 1) {
        range(0);
    } else {
        std::vector<std::thread> pool;
        pool.reserve(threads - 1);
        for (size_t t = 1; t < threads; ++t) pool.emplace_back(range, t);
        range(0);
        for (std::thread& thread : pool) thread.join();
    }
    const size_t t = size_t(std::min_element(outside.begin(), outside.end()) - outside.begin());
    if (first_outside) *first_outside = outside[t];
    return outside[t] < count ? failure[t] : Status::ok;
}

}  // namespace

Status Store::interpolate(const float world_position[3], int32_t* hint, float out_sh[27], float out_occlusion[4]) const {
    float q[3];
    local_position(*impl_, world_position, q);
    Location loc = locate_local(*impl_, q, hint ? *hint : -1);
    if (hint) *hint = loc.cell;
    if (loc.status != Status::ok) {
        std::fill(out_sh, out_sh + 27, 0.0f);
        if (out_occlusion) std::fill(out_occlusion, out_occlusion + kOcclusionChannels, 0.0f);
        return loc.status;
    }
    if (impl_->leak_offsets) weigh_by_visibility(*impl_, loc);
    blend(*impl_, loc, out_sh);
    if (out_occlusion) blend_occlusion(*impl_, loc, out_occlusion);
    return Status::ok;
}

Status Store::interpolate_batch(size_t count, const float* positions, size_t position_stride, int32_t* hints,
                                size_t hint_stride, float* out_sh, size_t sh_stride, const BatchSettings& settings,
                                size_t* first_outside, float* out_occlusion, size_t occlusion_stride) const {
    const Impl& s = *impl_;
    return run_batch(s, count, positions, position_stride, hints, hint_stride, settings, first_outside,
                     [&](size_t i, const Location& loc) {
                         float sh[27], occlusion[kOcclusionChannels];
                         if (loc.status == Status::ok) {
                             blend(s, loc, sh);
                             if (out_occlusion) blend_occlusion(s, loc, occlusion);
                         } else {
                             std::fill(sh, sh + 27, 0.0f);
                             std::fill(occlusion, occlusion + kOcclusionChannels, 0.0f);
                         }
                         std::memcpy(strided(out_sh, i, sh_stride), sh, sizeof sh);
                         if (out_occlusion) std::memcpy(strided(out_occlusion, i, occlusion_stride), occlusion, sizeof occlusion);
                     });
}

Status Store::weights_batch(size_t count, const float* positions, size_t position_stride, int32_t* hints,
                            size_t hint_stride, uint32_t* out_probes, size_t probes_stride, float* out_weights,
                            size_t weights_stride, const BatchSettings& settings, size_t* first_outside) const {
    return run_batch(*impl_, count, positions, position_stride, hints, hint_stride, settings, first_outside,
                     [&](size_t i, const Location& loc) {
                         uint32_t probes[4] = {0, 0, 0, 0};
                         float weights[4] = {0, 0, 0, 0};
                         if (loc.status == Status::ok)
                             for (int k = 0; k < 4; ++k) probes[k] = loc.probes[k], weights[k] = loc.weights[k];
                         std::memcpy(strided(out_probes, i, probes_stride), probes, sizeof probes);
                         std::memcpy(strided(out_weights, i, weights_stride), weights, sizeof weights);
                     });
}

}  // namespace tetprobe
