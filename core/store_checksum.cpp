#include "core/store_format.h"

#include <algorithm>
#include <cstring>

namespace tetprobe {

namespace {

constexpr uint64_t kFnvOffsetBasis = 0xcbf29ce484222325ull;
constexpr uint64_t kFnvPrime = 0x100000001b3ull;

// FNV-1a steps over little-endian 64-bit words (8 times fewer steps than over bytes; a corruption
// check, not a cryptographic hash); a last partial word is zero-padded. The xor-shift after each
// multiply carries the top bit down (a multiply alone moves a flipped bit 63 to bit 63 only, so two
// such flips would cancel); every step stays a bijection of the state, so any one changed word
// always changes the result.
uint64_t fnv1a_words(uint64_t hash, const uint8_t* data, size_t size) {
    for (size_t i = 0; i < size; i += 8) {
        uint64_t word = 0;
        std::memcpy(&word, data + i, std::min<size_t>(8, size - i));
        hash ^= word;
        hash *= kFnvPrime;
        hash ^= hash >> 29;
    }
    return hash;
}

}  // namespace

uint64_t store_checksum(const uint8_t* data, size_t size) {
    // The checksum field hashes as zero bytes, so a blob can carry its own checksum. The first
    // 128 bytes (the header, field included) are hashed from a copy with the field cleared.
    constexpr size_t kHead = 128;
    static_assert(kChecksumOffset + sizeof(uint64_t) <= kHead, "the checksum field lies in the head");
    uint8_t head[kHead] = {};
    const size_t head_size = std::min(size, kHead);
    std::memcpy(head, data, head_size);
    if (head_size > kChecksumOffset)
        std::memset(head + kChecksumOffset, 0, std::min(sizeof(uint64_t), head_size - kChecksumOffset));
    uint64_t hash = fnv1a_words(kFnvOffsetBasis ^ uint64_t(size), head, head_size);
    return size > kHead ? fnv1a_words(hash, data + kHead, size - kHead) : hash;
}

}  // namespace tetprobe
