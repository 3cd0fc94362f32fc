// The query front end: every query of a store — interpolate (with or without occlusion), locate,
// weights and their batches — goes through the kernels the store chose at load (locate_kernel.h): to the
// store's frame, locate, weigh for leaks (answer()), then the caller's outputs. Interpolations without
// occlusion take the kernel's fused locate + blend, which blends the lean walk's answer straight into the
// caller's buffer (the same bits as locate + answer_sh); with leak control, a query whose cell holds a
// blocked pair is then answered again through the pipeline from its cell (reweigh_blocked). Nothing here
// allocates, throws or starts a thread: a batch runs on the calling thread (an engine splits a frame
// into ranges for its own workers, see tp_batch_options).
#include "core/leak_control.h"
#include "core/locate.h"
#include "core/store.h"
#include "core/store_impl.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace tetprobe {

namespace {

// The one pipeline: count queries (<= kMaxBatchGroup) at local positions from their hints, located
// and weighed as the store answers them (leak control applied to every located query). The answers
// are written into out in place, every field of them (a batch does not reset its Locations first).
void answer(const Store::Impl& s, size_t count, const float (*local)[3], const int32_t* hints, Location* out) {
    if (count == 1)
        s.locate.locate(s, local[0], hints[0], out[0]);
    else
        s.locate.locate_batch(s, count, local, hints, out);
    if (s.leak_offsets)
        for (size_t i = 0; i < count; ++i)
            if (out[i].status == Status::ok) weigh_by_visibility(s, local[i], out[i]);
}

// One query at a world position, answered in loc (a default Location).
void answer_one(const Store::Impl& s, const float world[3], int32_t hint, Location& loc) {
    float local[1][3];
    local_position(s, world, local[0]);
    answer(s, 1, local, &hint, &loc);
}

// After the fused kernel (locate + blend without leak control): a query whose cell holds a blocked pair
// is answered again through the pipeline, weighed for leaks and blended again into out_sh. From an inner
// cell that holds the point the walk stops at once; an outer cell's choice (and the exhaustive fallback's)
// can depend on where the walk starts, so there it starts again from the caller's hint. Answers in other
// cells are already the pipeline's, bit for bit.
void reweigh_blocked(const Store::Impl& s, const float local[3], int32_t start, int32_t* cell, Status* status,
                     float out_sh[27]) {
    if (!s.leak_offsets || *status != Status::ok || *cell < 0 || !s.leak_cells.get()[*cell]) return;
    Location loc;
    const float at[1][3] = {{local[0], local[1], local[2]}};
    int32_t from = uint32_t(*cell) < s.inner_cell_count ? *cell : start;
    answer(s, 1, at, &from, &loc);
    *cell = loc.cell;
    *status = answer_sh(s, loc, out_sh, nullptr);
}

// The four probes' SH records, decoded as they are weighed (the encoding's kernel, sh_blend.h).
void blend(const Store::Impl& s, const Location& loc, float out_sh[27]) {
    const uint8_t* records[4];
    for (int k = 0; k < 4; ++k) records[k] = s.sh + size_t(loc.probes[k]) * s.sh_stride;
    s.blend_sh(records, loc.weights, out_sh);
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

// A group's local positions and start hints (-1 without hints) from the caller's strided buffers.
void read_group(const Store::Impl& s, size_t group, size_t n, const float* positions, size_t position_stride,
                const int32_t* hints, size_t hint_stride, float (*local)[3], int32_t* start) {
    for (size_t j = 0; j < n; ++j) {
        float world[3];
        std::memcpy(world, strided(positions, group + j, position_stride), sizeof world);
        local_position(s, world, local[j]);
        start[j] = -1;
        if (hints) std::memcpy(&start[j], strided(hints, group + j, hint_stride), sizeof start[j]);
    }
}

// Runs a batch in groups of kMaxBatchGroup through answer() (reading and writing the hints), then
// hands every location to output(i, loc). Returns ok, or the status of the first query that failed
// with *first_outside its index.
template <class Output>
Status run_batch(const Store::Impl& s, size_t count, const float* positions, size_t position_stride, int32_t* hints,
                 size_t hint_stride, bool chain_hints, size_t* first_outside, Output output) {
    size_t first = count;
    Status failure = Status::ok;
    int32_t chained = -1;
    float local[kMaxBatchGroup][3];
    int32_t start[kMaxBatchGroup];
    Location located[kMaxBatchGroup];
    for (size_t group = 0; group < count; group += kMaxBatchGroup) {
        const size_t n = std::min(kMaxBatchGroup, count - group);
        read_group(s, group, n, positions, position_stride, hints, hint_stride, local, start);
        if (hints || !chain_hints) {
            answer(s, n, local, start, located);
        } else {  // each query starts where the previous one ended: one after the other
            for (size_t j = 0; j < n; ++j) {
                start[j] = chained;
                answer(s, 1, local + j, start + j, located + j);
                chained = located[j].cell;
            }
        }
        for (size_t j = 0; j < n; ++j) {
            const size_t i = group + j;
            if (hints) std::memcpy(strided(hints, i, hint_stride), &located[j].cell, sizeof located[j].cell);
            if (located[j].status != Status::ok && first == count) first = i, failure = located[j].status;
            output(i, located[j]);
        }
    }
    if (first_outside) *first_outside = first;
    return failure;
}

// A batch of interpolations on the store's fused kernel (no occlusion; with leak control, the queries in
// cells with a blocked pair answered again, reweigh_blocked):
// groups as run_batch, each query's SH blended straight into the caller's buffer when it is aligned for
// floats (else into a local one copied out: a misaligned stride is legal). Same answers as run_batch.
Status run_interpolate_batch(const Store::Impl& s, size_t count, const float* positions, size_t position_stride,
                             int32_t* hints, size_t hint_stride, bool chain_hints, float* out_sh, size_t sh_stride,
                             size_t* first_outside) {
    const bool direct = reinterpret_cast<uintptr_t>(out_sh) % alignof(float) == 0 && sh_stride % alignof(float) == 0;
    size_t first = count;
    Status failure = Status::ok;
    int32_t chained = -1;
    float local[kMaxBatchGroup][3];
    int32_t cell[kMaxBatchGroup];
    Status status[kMaxBatchGroup];
    float* target[kMaxBatchGroup];
    float scratch[kMaxBatchGroup][27];  // a misaligned buffer's answers, copied out
    for (size_t group = 0; group < count; group += kMaxBatchGroup) {
        const size_t n = std::min(kMaxBatchGroup, count - group);
        read_group(s, group, n, positions, position_stride, hints, hint_stride, local, cell);
        for (size_t j = 0; j < n; ++j)
            target[j] = direct ? reinterpret_cast<float*>(strided(out_sh, group + j, sh_stride)) : scratch[j];
        if (hints || !chain_hints) {
            int32_t start[kMaxBatchGroup];
            std::copy(cell, cell + n, start);
            s.locate.interpolate_batch(s, n, local, cell, target, status);
            for (size_t j = 0; j < n; ++j) reweigh_blocked(s, local[j], start[j], &cell[j], &status[j], target[j]);
        } else {  // each query starts where the previous one ended: one after the other
            for (size_t j = 0; j < n; ++j) {
                cell[j] = chained;
                status[j] = s.locate.interpolate(s, local[j], &cell[j], target[j]);
                reweigh_blocked(s, local[j], chained, &cell[j], &status[j], target[j]);
                chained = cell[j];
            }
        }
        for (size_t j = 0; j < n; ++j) {
            const size_t i = group + j;
            if (hints) std::memcpy(strided(hints, i, hint_stride), &cell[j], sizeof cell[j]);
            if (!direct) std::memcpy(strided(out_sh, i, sh_stride), scratch[j], sizeof scratch[j]);
            if (status[j] != Status::ok && first == count) first = i, failure = status[j];
        }
    }
    if (first_outside) *first_outside = first;
    return failure;
}

}  // namespace

Status answer_sh(const Store::Impl& s, const Location& loc, float out_sh[27], float* out_occlusion) {
    if (loc.status != Status::ok) {
        std::fill(out_sh, out_sh + 27, 0.0f);
        if (out_occlusion) std::fill(out_occlusion, out_occlusion + kOcclusionChannels, 0.0f);
        return loc.status;
    }
    blend(s, loc, out_sh);
    if (out_occlusion) blend_occlusion(s, loc, out_occlusion);
    return Status::ok;
}


Location Store::locate(const float world_position[3], int32_t hint) const {
    Location loc;
    answer_one(*impl_, world_position, hint, loc);
    return loc;
}

Location Store::locate_exhaustive(const float world_position[3], Cells cells) const {
    float q[3];
    local_position(*impl_, world_position, q);
    return tetprobe::locate_exhaustive(*impl_, q, cells == Cells::outer);
}

Status Store::interpolate(const float world_position[3], int32_t* hint, float out_sh[27], float out_occlusion[4]) const {
    const Impl& s = *impl_;
    if (!out_occlusion && s.locate.interpolate) {
        float local[3];
        local_position(s, world_position, local);
        const int32_t start = hint ? *hint : -1;
        int32_t cell = start;
        Status status = s.locate.interpolate(s, local, &cell, out_sh);
        reweigh_blocked(s, local, start, &cell, &status, out_sh);
        if (hint) *hint = cell;
        return status;
    }
    Location loc;
    answer_one(*impl_, world_position, hint ? *hint : -1, loc);
    if (hint) *hint = loc.cell;
    return answer_sh(*impl_, loc, out_sh, out_occlusion);
}

Status Store::interpolate_batch(size_t count, const float* positions, size_t position_stride, int32_t* hints,
                                size_t hint_stride, float* out_sh, size_t sh_stride, const BatchSettings& settings,
                                size_t* first_outside, float* out_occlusion, size_t occlusion_stride) const {
    const Impl& s = *impl_;
    if (!out_occlusion && s.locate.interpolate_batch)
        return run_interpolate_batch(s, count, positions, position_stride, hints, hint_stride, settings.chain_hints, out_sh,
                                     sh_stride, first_outside);
    // An aligned float buffer (the usual case) takes the blend directly: blending into a local array and
    // copying it out costs a store-forwarding stall on every query (about 5 ns at 1.5k probes).
    const bool direct = reinterpret_cast<uintptr_t>(out_sh) % alignof(float) == 0 && sh_stride % alignof(float) == 0;
    return run_batch(s, count, positions, position_stride, hints, hint_stride, settings.chain_hints, first_outside,
                     [&](size_t i, const Location& loc) {
                         float sh[27], occlusion[kOcclusionChannels];
                         uint8_t* target = strided(out_sh, i, sh_stride);
                         answer_sh(s, loc, direct ? reinterpret_cast<float*>(target) : sh, out_occlusion ? occlusion : nullptr);
                         if (!direct) std::memcpy(target, sh, sizeof sh);
                         if (out_occlusion) std::memcpy(strided(out_occlusion, i, occlusion_stride), occlusion, sizeof occlusion);
                     });
}

Status Store::weights_batch(size_t count, const float* positions, size_t position_stride, int32_t* hints,
                            size_t hint_stride, uint32_t* out_probes, size_t probes_stride, float* out_weights,
                            size_t weights_stride, const BatchSettings& settings, size_t* first_outside) const {
    return run_batch(*impl_, count, positions, position_stride, hints, hint_stride, settings.chain_hints, first_outside,
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
