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
};

// False unless the store is a format-5 blob in the half encoding (what this benchmark reads).
bool read_blob_sh(const tp_store* store, BlobSh* out);
// The same from a blob's bytes (valid while they live); false also for a blob too short for its sections.
bool read_blob_sh(const void* blob, size_t size, BlobSh* out);

}  // namespace bench
