// The run-time store: a validated, immutable blob and the queries on it. Queries never allocate,
// never throw, and are safe from any number of threads at once.
#pragma once

#include "core/error.h"
#include "core/store_format.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tetprobe {

enum class CellKind : uint32_t { inner = 0, outer = 1 };

// Everything one query used (the C ABI's tp_location, in stored-probe terms).
struct Location {
    // ok; outside (a store built without extrapolation); invalid_blob: the query gave up at its cap of
    // examined cells (walk.cpp, exhaustive_search.cpp), which only a corrupt or forged store's cells reach.
    Status status = Status::ok;
    int32_t cell = -1;
    CellKind kind = CellKind::inner;
    uint32_t steps = 0;
    bool fallback = false;        // the walk handed the decision to the exhaustive search
    uint32_t searched = 0;        // cells the exhaustive search examined
    uint32_t probes[4] = {0, 0, 0, 0};  // stored probe indices; unused slots repeat slot 0 with weight 0
    float weights[4] = {0, 0, 0, 0};
    float t = 0;
};

// How a batch runs (see tp_batch_options). A batch runs on the calling thread.
struct BatchSettings {
    bool chain_hints = false;  // without hints, each query starts where the previous one ended
};

class Store {
public:
    // Copies and validates a blob; throws Error(Status::invalid_blob / Status::version) on failure.
    static std::unique_ptr<Store> load(const void* data, size_t size);
    ~Store();

    const uint8_t* blob_data() const;
    size_t blob_size() const;
    const StoreHeader& header() const;

    // Input index of a stored probe, and stored index of an input probe.
    uint32_t probe_source(uint32_t stored) const;
    uint32_t input_to_stored(uint32_t input) const;
    // Decodes a stored probe's half SH to 27 floats.
    void probe_sh(uint32_t stored, float out[27]) const;
    // A stored probe's occlusion bytes (4; all 255 in a store without occlusion).
    void probe_occlusion(uint32_t stored, uint8_t out[4]) const;
    // A stored probe's local position (3 floats).
    const float* probe_position(uint32_t stored) const;
    // The four vertex and four neighbour slots of a cell, widened to 32 bits (kNone32, kOuter32).
    void cell(uint32_t cell, uint32_t vertices[4], uint32_t neighbours[4]) const;

    // Finds the cell of a world-space position starting from hint (-1 = none: start from the grid);
    // the weights are those a query blends (leak control applied when the store has it).
    Location locate(const float world_position[3], int32_t hint) const;
    // The walk's referee: the cell decided over every cell by exact orientations (O(cells)), or over
    // the outer cells alone (the walk's fallback for a point beyond the hull; cell -1 if none holds it).
    enum class Cells { all, outer };
    Location locate_exhaustive(const float world_position[3], Cells cells) const;
    // locate + blend; *hint (may be null) is read and updated. Returns ok or outside (SH zero).
    // out_occlusion (may be null) receives the mixed lights' interpolated visibility (4 floats in
    // [0, 1]; 1 for channels without a light; zero outside).
    Status interpolate(const float world_position[3], int32_t* hint, float out_sh[27],
                       float out_occlusion[4] = nullptr) const;

    // count queries at byte strides (already resolved, > 0; no alignment needed: every element is
    // copied with memcpy); hints may be null. Returns ok, or the status of the first query that
    // failed (outside, or invalid_blob, see Location) with *first_outside its index (the SH and
    // weights of every failed query zero).
    // out_occlusion (may be null): 4 floats per query at occlusion_stride bytes, as interpolate's.
    Status interpolate_batch(size_t count, const float* positions, size_t position_stride, int32_t* hints,
                             size_t hint_stride, float* out_sh, size_t sh_stride, const BatchSettings& settings,
                             size_t* first_outside, float* out_occlusion = nullptr,
                             size_t occlusion_stride = 0) const;
    // The same for weights: out_probes are stored probe indices.
    Status weights_batch(size_t count, const float* positions, size_t position_stride, int32_t* hints,
                         size_t hint_stride, uint32_t* out_probes, size_t probes_stride, float* out_weights,
                         size_t weights_stride, const BatchSettings& settings, size_t* first_outside) const;

    struct Impl;

private:
    Store();
    std::unique_ptr<Impl> impl_;
};

// Serialises StoreData into a blob (chooses 16- or 32-bit indices, converts SH to half, lays out the
// fast or the compact layout). Throws Error(Status::invalid_argument) on data the format cannot hold.
std::vector<uint8_t> write_store_blob(const struct StoreData& data);

}  // namespace tetprobe
