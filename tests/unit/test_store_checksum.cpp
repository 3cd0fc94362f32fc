// The blob checksum: any one changed word changes it, and so do the pairs of top-bit flips that a
// word-wise FNV-1a without mixing lets cancel (found in review: two SH sign flips loaded as valid).
#include "core/store_format.h"

#include <catch2/catch.hpp>

#include <random>
#include <vector>

using namespace tetprobe;

TEST_CASE("the checksum sees every single bit flip and pairs of top-bit flips", "[store_blob]") {
    std::mt19937 rng(11);
    std::vector<uint8_t> blob(1024);
    for (uint8_t& b : blob) b = uint8_t(rng());
    const uint64_t original = store_checksum(blob.data(), blob.size());
    for (size_t byte = 0; byte < blob.size(); ++byte) {
        if (byte >= kChecksumOffset && byte < kChecksumOffset + 8) continue;  // read as zero
        for (int bit = 0; bit < 8; ++bit) {
            blob[byte] ^= uint8_t(1u << bit);
            REQUIRE(store_checksum(blob.data(), blob.size()) != original);
            blob[byte] ^= uint8_t(1u << bit);
        }
    }
    // Bit 63 of two words (the sign bit of the last half in each), in many word pairs.
    for (size_t a = 128; a + 8 <= blob.size(); a += 56) {
        for (size_t b = a + 8; b + 8 <= blob.size(); b += 72) {
            blob[a + 7] ^= 0x80;
            blob[b + 7] ^= 0x80;
            REQUIRE(store_checksum(blob.data(), blob.size()) != original);
            blob[a + 7] ^= 0x80;
            blob[b + 7] ^= 0x80;
        }
    }
    // The field itself is read as zero: a blob can carry its own checksum.
    blob[kChecksumOffset] ^= 0xFF;
    CHECK(store_checksum(blob.data(), blob.size()) == original);
}
