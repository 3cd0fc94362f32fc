// C ABI of the run-time store: load, save, inspect and query.
#include "boundary.h"
#include "strides.h"
#include "core/file_io.h"
#include "core/position_quantization.h"
#include "core/store.h"
#include "grown_structs.h"
#include "struct_defaults.h"
#include "store_handle.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace tetprobe {

namespace {

const Store& store_of(const tp_store* handle) { return *handle->store; }

bool finite3(const float p[3]) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// Positions are validated once, before any query of a batch runs.
void require_finite_positions(const float* positions, size_t count, size_t stride) {
    for (size_t i = 0; i < count; ++i) {
        float p[3];
        std::memcpy(p, element_at(positions, i, stride), sizeof p);
        if (!finite3(p))
            throw Error(Status::invalid_argument, "positions[" + std::to_string(i) + "] is not finite");
    }
}

const char* const kOutsideMessage = "position is outside the probes' hull (store built without extrapolation)";
const char* const kGaveUpMessage =
    "the query gave up after examining its cap of cells: the store's tessellation is inconsistent (a corrupt or "
    "forged blob; a store this library built never gets here)";

// A single query's failure (no allocation: queries never allocate).
tp_status report_query(Status status) {
    if (status == Status::ok) return TP_OK;
    return fail_static(to_tp_status(status), status == Status::outside ? kOutsideMessage : kGaveUpMessage);
}

// A batch's: the first failed query, named.
tp_status report_batch(Status status, size_t first) {
    if (status == Status::ok) return TP_OK;
    if (status == Status::outside)
        return fail_formatted(to_tp_status(status),
                              "positions are outside the probes' hull (store built without extrapolation); the first "
                              "at index %zu (their SH and weights are zero)", first);
    return fail_formatted(to_tp_status(status), "%s; the first at index %zu (the SH and weights of failed queries are zero)",
                          kGaveUpMessage, first);
}

tp_batch_options default_batch_options() {
    tp_batch_options options{};
    options.struct_size = sizeof options;
    options.threads = 1;
    return options;
}

// The run time's batch settings from the caller's options (NULL = defaults).
BatchSettings batch_settings(const tp_batch_options* options) {
    BatchSettings settings;
    if (!options) return settings;
    if (options->struct_size < 3 * sizeof(uint32_t))
        throw Error(Status::invalid_argument, "options->struct_size is not set (use tp_batch_options_init)");
    if (options->flags & ~uint32_t(TP_BATCH_CHAIN_HINTS))
        throw Error(Status::invalid_argument, "unknown batch flags " + std::to_string(options->flags));
    settings.chain_hints = (options->flags & TP_BATCH_CHAIN_HINTS) != 0;  // threads: deprecated, ignored
    return settings;
}

// Fills a location's public form with input-probe indices.
void to_input_probes(const Store& store, const Location& loc, uint32_t probes[4], float weights[4]) {
    for (int k = 0; k < 4; ++k) {
        probes[k] = store.probe_source(loc.probes[k]);
        weights[k] = loc.weights[k];
    }
}

// Checks and resolves a batch query's arguments and runs it; with_occlusion: out_occlusion is required
// (tp_store_interpolate_occlusion_batch), else it is null.
tp_status interpolate_batch(const tp_store* store, size_t count, const float* positions, size_t position_stride,
                            int32_t* hints, size_t hint_stride, float* out_sh, size_t sh_stride, bool with_occlusion,
                            float* out_occlusion, size_t occlusion_stride, const tp_batch_options* options) {
    TP_REQUIRE_NOT_NULL(store);
    const BatchSettings settings = batch_settings(options);
    if (count == 0) return TP_OK;
    position_stride = checked_buffer(positions, "positions", count, "count", position_stride, "position_stride",
                                     3 * sizeof(float));
    if (hints) hint_stride = checked_buffer(hints, "hints", count, "count", hint_stride, "hint_stride", sizeof(int32_t));
    sh_stride = checked_buffer(out_sh, "out_sh", count, "count", sh_stride, "sh_stride", 27 * sizeof(float));
    if (with_occlusion)
        occlusion_stride = checked_buffer(out_occlusion, "out_occlusion", count, "count", occlusion_stride,
                                          "occlusion_stride", 4 * sizeof(float));
    require_finite_positions(positions, count, position_stride);
    size_t first_outside = count;
    const Status status = store_of(store).interpolate_batch(count, positions, position_stride, hints, hint_stride,
                                                            out_sh, sh_stride, settings, &first_outside,
                                                            out_occlusion, occlusion_stride);
    return report_batch(status, first_outside);
}

}  // namespace

}  // namespace tetprobe

using namespace tetprobe;

extern "C" {

TP_API tp_status tp_store_load(const void* data, size_t size, tp_store** out_store) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(out_store);
    *out_store = nullptr;
    if (!data) return fail(TP_ERROR_INVALID_ARGUMENT, "data is NULL");
    checked_packed(data, "data", size, "size", 1);
    std::unique_ptr<tp_store> handle(new tp_store);
    handle->store = Store::load(data, size);
    *out_store = handle.release();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_load_file_ex(const char* path, const tp_store_load_options* options, tp_store** out_store) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(out_store);
    *out_store = nullptr;
    TP_REQUIRE_NOT_NULL(path);
    tp_store_load_options settings = default_store_load_options();
    if (options) {
        if (options->struct_size < sizeof(uint32_t))
            return fail(TP_ERROR_INVALID_ARGUMENT, "options->struct_size is not set (use tp_store_load_options_init)");
        // Fields beyond the caller's struct_size (an older caller's smaller struct) keep their defaults.
        if (options->struct_size >= offsetof(tp_store_load_options, max_file_bytes) + sizeof(uint64_t))
            settings.max_file_bytes = options->max_file_bytes;
    }
    const std::vector<uint8_t> bytes = read_file(path, settings.max_file_bytes);
    std::unique_ptr<tp_store> handle(new tp_store);
    try {
        handle->store = Store::load(bytes.data(), bytes.size());
    } catch (const Error& e) {
        throw Error(e.status(), std::string(e.what()) + " (file '" + path + "')");
    }
    *out_store = handle.release();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_load_file(const char* path, tp_store** out_store) {
    return tp_store_load_file_ex(path, nullptr, out_store);
}

TP_API tp_status tp_store_save_file(const tp_store* store, const char* path) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(path);
    if (!*path) return fail(TP_ERROR_INVALID_ARGUMENT, "path is empty");
    write_file_atomically(path, store_of(store).blob_data(), store_of(store).blob_size());
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_blob(const tp_store* store, const void** out_data, size_t* out_size) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(out_data);
    TP_REQUIRE_NOT_NULL(out_size);
    *out_data = store_of(store).blob_data();
    *out_size = store_of(store).blob_size();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_release(tp_store* store) {
    TP_API_BEGIN
    delete store;
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_get_info(const tp_store* store, tp_store_info* info) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(info);
    if (info->struct_size < sizeof(uint32_t))
        return fail(TP_ERROR_INVALID_ARGUMENT, "info->struct_size is not set (use sizeof(tp_store_info))");
    const Store& s = store_of(store);
    const StoreHeader& h = s.header();
    tp_store_info full;
    std::memset(&full, 0, sizeof full);
    full.struct_size = info->struct_size;
    full.format_version = h.format_version;
    full.dimension = h.dimension;
    full.probes = h.probe_count;
    full.input_probes = h.input_probe_count;
    full.merged_probes = h.input_probe_count - h.probe_count;
    full.cells = h.cell_count;
    full.inner_cells = h.inner_cell_count;
    full.outer_cells = h.cell_count - h.inner_cell_count;
    full.index_bits = (h.flags & kFlagIndex32) ? 32 : 16;
    // The same bits as TP_BUILD_* (boundary.h); the scene-data bits are reported by their own fields.
    full.flags = (h.flags & (kFlagNoExtrapolation | kFlagIndex32)) | (h.layout == kLayoutCompact ? TP_BUILD_COMPACT : 0u);
    for (int k = 0; k < 3; ++k) {
        full.grid[k] = h.grid[k];
        full.origin[k] = h.origin[k];
        full.bounds_min[k] = float(h.origin[k] + double(h.bounds_min[k]));
        full.bounds_max[k] = float(h.origin[k] + double(h.bounds_max[k]));
    }
    full.bytes = s.blob_size();
    full.occlusion_lights = h.occlusion_lights;
    full.leak_edges = h.leak_edge_count;
    full.layout = h.layout;
    full.sh_encoding = h.sh_encoding;
    full.quantized_positions = h.position_encoding == kPositionsUnorm16;
    full.hull_probes = h.hull_probe_count;
    if (full.quantized_positions && info->struct_size >= offsetof(tp_store_info, position_step) + sizeof full.position_step)
        for (int k = 0; k < 3; ++k) full.position_step[k] = position_max_gap(h.bounds_min[k], h.bounds_max[k]);
    SectionEntry table[kSectionCount];
    std::memcpy(table, s.blob_data() + sizeof(StoreHeader), sizeof table);
    static_assert(kSectionCount + 2 == TP_STORE_SECTION_COUNT && TP_STORE_SECTION_POSITIONS == kSectionPositions + 1 &&
                      TP_STORE_SECTION_NORMALS == kSectionNormals + 1 && TP_STORE_SECTION_SH == kSectionSh + 1 &&
                      TP_STORE_SECTION_PROBE_SOURCE == kSectionProbeSource + 1 &&
                      TP_STORE_SECTION_INPUT_REMAP == kSectionInputRemap + 1 && TP_STORE_SECTION_CELLS == kSectionCells + 1 &&
                      TP_STORE_SECTION_GRID == kSectionGrid + 1 && TP_STORE_SECTION_OCCLUSION == kSectionOcclusion + 1 &&
                      TP_STORE_SECTION_LEAK_OFFSETS == kSectionLeakOffsets + 1 &&
                      TP_STORE_SECTION_LEAK_EDGES == kSectionLeakEdges + 1,
                  "tp_store_info.section_bytes follows the blob's section table, after the header");
    uint64_t parts = kHeaderSize;
    full.section_bytes[TP_STORE_SECTION_HEADER] = kHeaderSize;
    for (uint32_t k = 0; k < kSectionCount; ++k) {
        full.section_bytes[TP_STORE_SECTION_POSITIONS + k] = table[k].size;
        parts += table[k].size;
    }
    full.section_bytes[TP_STORE_SECTION_PADDING] = s.blob_size() - parts;
    copy_fitting_fields(info, full, info->struct_size);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_probe_sh(const tp_store* store, uint32_t probe, float out_sh[27]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(out_sh);
    const Store& s = store_of(store);
    if (probe >= s.header().input_probe_count)
        return fail(TP_ERROR_INVALID_ARGUMENT, "probe " + std::to_string(probe) + " is not an input probe (the store has " +
                                                   std::to_string(s.header().input_probe_count) + ")");
    s.probe_sh(s.input_to_stored(probe), out_sh);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_interpolate(const tp_store* store, const float position[3], int32_t* cell_hint,
                                      float out_sh[27]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(position);
    TP_REQUIRE_NOT_NULL(out_sh);
    if (!finite3(position)) return fail(TP_ERROR_INVALID_ARGUMENT, "position is not finite");
    const Status status = store_of(store).interpolate(position, cell_hint, out_sh);
    return report_query(status);
    TP_API_END
}

TP_API tp_status tp_store_interpolate_occlusion(const tp_store* store, const float position[3], int32_t* cell_hint,
                                                float out_sh[27], float out_occlusion[4]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(position);
    TP_REQUIRE_NOT_NULL(out_sh);
    TP_REQUIRE_NOT_NULL(out_occlusion);
    if (!finite3(position)) return fail(TP_ERROR_INVALID_ARGUMENT, "position is not finite");
    const Status status = store_of(store).interpolate(position, cell_hint, out_sh, out_occlusion);
    return report_query(status);
    TP_API_END
}

TP_API tp_status tp_store_interpolate_occlusion_batch(const tp_store* store, size_t count, const float* positions,
                                                      size_t position_stride, int32_t* hints, size_t hint_stride,
                                                      float* out_sh, size_t sh_stride, float* out_occlusion,
                                                      size_t occlusion_stride, const tp_batch_options* options) {
    TP_API_BEGIN
    return interpolate_batch(store, count, positions, position_stride, hints, hint_stride, out_sh, sh_stride, true,
                             out_occlusion, occlusion_stride, options);
    TP_API_END
}

TP_API tp_status tp_batch_options_init(tp_batch_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(options);
    *options = default_batch_options();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_interpolate_batch(const tp_store* store, size_t count, const float* positions,
                                            size_t position_stride, int32_t* hints, size_t hint_stride,
                                            float* out_sh, size_t sh_stride, const tp_batch_options* options) {
    TP_API_BEGIN
    return interpolate_batch(store, count, positions, position_stride, hints, hint_stride, out_sh, sh_stride, false,
                             nullptr, 0, options);
    TP_API_END
}

TP_API tp_status tp_store_weights(const tp_store* store, const float position[3], int32_t* cell_hint,
                                  uint32_t out_probes[4], float out_weights[4]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(position);
    TP_REQUIRE_NOT_NULL(out_probes);
    TP_REQUIRE_NOT_NULL(out_weights);
    if (!finite3(position)) return fail(TP_ERROR_INVALID_ARGUMENT, "position is not finite");
    const Store& s = store_of(store);
    const Location loc = s.locate(position, cell_hint ? *cell_hint : -1);
    if (cell_hint) *cell_hint = loc.cell;
    to_input_probes(s, loc, out_probes, out_weights);
    return report_query(loc.status);
    TP_API_END
}

TP_API tp_status tp_store_weights_batch(const tp_store* store, size_t count, const float* positions,
                                        size_t position_stride, int32_t* hints, size_t hint_stride,
                                        uint32_t* out_probes, size_t probes_stride, float* out_weights,
                                        size_t weights_stride, const tp_batch_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    const BatchSettings settings = batch_settings(options);
    if (count == 0) return TP_OK;
    position_stride = checked_buffer(positions, "positions", count, "count", position_stride, "position_stride",
                                     3 * sizeof(float));
    if (hints) hint_stride = checked_buffer(hints, "hints", count, "count", hint_stride, "hint_stride", sizeof(int32_t));
    probes_stride = checked_buffer(out_probes, "out_probes", count, "count", probes_stride, "probes_stride",
                                   4 * sizeof(uint32_t));
    weights_stride = checked_buffer(out_weights, "out_weights", count, "count", weights_stride, "weights_stride",
                                    4 * sizeof(float));
    require_finite_positions(positions, count, position_stride);
    const Store& s = store_of(store);
    size_t first_outside = count;
    const Status status = s.weights_batch(count, positions, position_stride, hints, hint_stride, out_probes,
                                          probes_stride, out_weights, weights_stride, settings, &first_outside);
    for (size_t i = 0; i < count; ++i) {  // stored probes to the input probes the caller knows
        uint32_t probes[4];
        std::memcpy(probes, element_at(out_probes, i, probes_stride), sizeof probes);
        for (int k = 0; k < 4; ++k) probes[k] = s.probe_source(probes[k]);
        std::memcpy(element_at(out_probes, i, probes_stride), probes, sizeof probes);
    }
    return report_batch(status, first_outside);
    TP_API_END
}

TP_API tp_status tp_store_locate(const tp_store* store, const float position[3], int32_t* cell_hint,
                                 tp_location* location) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(position);
    TP_REQUIRE_NOT_NULL(location);
    if (location->struct_size < sizeof(uint32_t))
        return fail(TP_ERROR_INVALID_ARGUMENT, "location->struct_size is not set (use sizeof(tp_location))");
    if (!finite3(position)) return fail(TP_ERROR_INVALID_ARGUMENT, "position is not finite");
    const Store& s = store_of(store);
    const Location loc = s.locate(position, cell_hint ? *cell_hint : -1);
    if (cell_hint) *cell_hint = loc.cell;
    tp_location full;
    std::memset(&full, 0, sizeof full);
    full.struct_size = location->struct_size;
    full.cell = loc.cell;
    full.cell_kind = uint32_t(loc.kind);
    full.steps = loc.steps;
    full.fallback = loc.fallback ? 1u : 0u;
    to_input_probes(s, loc, full.probes, full.weights);
    full.t = loc.t;
    copy_fitting_fields(location, full, location->struct_size);
    return report_query(loc.status);
    TP_API_END
}

}  // extern "C"
