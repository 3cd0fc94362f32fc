// Peer of the benchmark (never linked into a tetprobe library): SH in Unity APV's 8-bit L2 encoding, as the
// real-level benchmark's grids store them. Per probe 32 bytes: the three channels' L0 as halves (plus two
// bytes of padding), then per channel its eight L1 and L2 coefficients divided by that channel's L0 and
// stored in 8 bits over the range the ratio can reach for non-negative radiance: |L1 / L0| <= sqrt(3),
// L2 m != 0 within +-sqrt(15) / 2, L2 m = 0 within [-sqrt(5) / 2, sqrt(5)] (the extremes of each basis
// function over the sphere, times sqrt(4 pi)). Ratios outside (ringing of a bake) are clamped.
#pragma once

#include <cstddef>
#include <cstdint>

namespace bench {

constexpr size_t kApvRecordBytes = 32;

// The smallest and largest ratio coefficient k (1..8 within a channel) over L0 can reach.
void apv_ratio_range(int k, float* lo, float* hi);

// Encodes 27 floats (channel-major) into a 32-byte record.
void apv_encode(const float sh[27], uint8_t record[kApvRecordBytes]);
// Decodes a record (scalar, the reference of the blend kernels).
void apv_decode(const uint8_t record[kApvRecordBytes], float sh[27]);

}  // namespace bench
