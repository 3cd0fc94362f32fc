// What the blend-only floor and the peers read of a fast store's blob: its SH section (IEEE halves)
// and the input -> stored probe remap, so that every method blends the very same coefficients.
#pragma once

#include "capi/tetprobe.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bench {

struct BlobSh {
    const uint16_t* sh = nullptr;  // valid while the store lives
    size_t stride = 0;             // halves per probe
    std::vector<uint32_t> input_remap;
    // The SH section as records of any encoding (the half ones too): what core's blend kernels read.
    const uint8_t* records = nullptr;
    size_t record_bytes = 0;       // per probe
    uint32_t encoding = 0;         // TP_SH_ENCODING_*
};

// False unless the store is a format-5 blob in the half encoding (what this benchmark reads), or with
// any_encoding, in any encoding (sh and stride are then set for half only).
bool read_blob_sh(const tp_store* store, BlobSh* out, bool any_encoding = false);
// The same from a blob's bytes (valid while they live); false also for a blob too short for its sections.
bool read_blob_sh(const void* blob, size_t size, BlobSh* out, bool any_encoding = false);

}  // namespace bench
