#include "core/store_format.h"

namespace tetprobe {

namespace {

constexpr uint64_t kFnvOffsetBasis = 0xcbf29ce484222325ull;
constexpr uint64_t kFnvPrime = 0x100000001b3ull;

uint64_t fnv1a(uint64_t hash, const uint8_t* data, size_t size) {
    for (size_t i = 0; i < size; ++i) {
        hash ^= data[i];
        hash *= kFnvPrime;
    }
    return hash;
}

}  // namespace

uint64_t store_checksum(const uint8_t* data, size_t size) {
    // The checksum field hashes as zero bytes, so a blob can carry its own checksum.
    static const uint8_t kZeroField[sizeof(uint64_t)] = {};
    const size_t field_end = kChecksumOffset + sizeof(uint64_t);
    if (size <= kChecksumOffset) return fnv1a(kFnvOffsetBasis, data, size);
    uint64_t hash = fnv1a(kFnvOffsetBasis, data, kChecksumOffset);
    if (size < field_end) return fnv1a(hash, kZeroField, size - kChecksumOffset);
    hash = fnv1a(hash, kZeroField, sizeof kZeroField);
    return fnv1a(hash, data + field_end, size - field_end);
}

}  // namespace tetprobe
