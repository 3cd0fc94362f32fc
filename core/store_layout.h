// Where the sections of a blob go: their exact sizes from the header's counts and encodings, and their
// offsets. The writer lays a blob out with these and the loader checks a blob against them.
#pragma once

#include "core/store_format.h"

#include <cstdint>

namespace tetprobe {

// Bytes of one cell or grid index for the header's flags (2 or 4).
inline uint64_t store_index_bytes(uint32_t flags) { return (flags & kFlagIndex32) ? 4u : 2u; }
// Bytes of one probe-map entry for the input probe count (2 or 4).
inline uint64_t store_map_bytes(uint32_t input_probe_count) { return input_probe_count <= kMaxMapCount16 ? 2u : 4u; }

// Rounds an offset up to the section alignment.
inline uint64_t align_section_offset(uint64_t offset) {
    return (offset + (kSectionAlignment - 1)) & ~uint64_t(kSectionAlignment - 1);
}

// Exact byte size of every section implied by the header's counts, flags and encodings. Returns false
// when an encoding or layout is unknown, a size does not fit in 64 bits or the outer cell count is
// negative, which no valid blob has.
bool expected_section_sizes(const StoreHeader& header, uint64_t sizes[kSectionCount]);

}  // namespace tetprobe
