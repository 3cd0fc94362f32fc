// The run-time store: a validated, immutable blob and the queries on it. Queries never allocate,
// never throw, and are safe from any number of threads at once.
#pragma once

#include "capi/tetprobe.h"
#include "core/store_format.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tetprobe {

// Everything one query used (the C ABI's tp_location, in stored-probe and input-probe terms).
struct Location {
    tp_status status = TP_OK;     // TP_OK or TP_ERROR_OUTSIDE (store built without extrapolation)
    int32_t cell = -1;
    uint32_t kind = TP_CELL_INNER;
    uint32_t steps = 0;
    bool fallback = false;
    uint32_t probes[4] = {0, 0, 0, 0};  // stored probe indices; unused slots repeat slot 0 with weight 0
    float weights[4] = {0, 0, 0, 0};
    float t = 0;
};

class Store {
public:
    // Copies and validates a blob; throws Error(TP_ERROR_INVALID_BLOB / TP_ERROR_VERSION) on failure.
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

    // Finds the cell of a world-space position starting from hint (-1 = none: start from the grid).
    Location locate(const float world_position[3], int32_t hint) const;
    // The walk's referee: the cell decided in double over every cell (O(cells)), or over the outer
    // cells alone (the walk's fallback for a point beyond the hull; cell -1 if none holds it).
    enum class Cells { all, outer };
    Location locate_exhaustive(const float world_position[3], Cells cells) const;
    // locate + blend; *hint (may be null) is read and updated. Returns TP_OK or TP_ERROR_OUTSIDE.
    tp_status interpolate(const float world_position[3], int32_t* hint, float out_sh[27]) const;

    struct Impl;

private:
    Store();
    std::unique_ptr<Impl> impl_;
};

// Serialises StoreData into a blob (chooses 16- or 32-bit indices, converts SH to half).
// Throws Error(TP_ERROR_INVALID_ARGUMENT) on data the format cannot hold.
std::vector<uint8_t> write_store_blob(const struct StoreData& data);

}  // namespace tetprobe
