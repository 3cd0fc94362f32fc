// Peer of the benchmark: the blend of a trilinear fetch, the 8 probes of a lattice cell weighted by the
// query's fractions within it, for the grids' two encodings (half SH padded to 28 halves, and APV's 32-byte
// 8-bit record, apv_sh_encoding.h). F16C/AVX2/FMA when the CPU has them (core/half.h decides once), else
// scalar: as fast as a CPU engine would make it, with the weights formed in registers next to the loads.
#pragma once

#include <cstddef>
#include <cstdint>

namespace bench {

constexpr int kGridHalves = 28;  // 27 coefficients and one half of padding: every load is whole

// corner c (bit 0: +x, bit 1: +y, bit 2: +z) is the record at base + offsets[c]; frac: the query's position
// in the cell, each in [0, 1]. out = sum_c w_c * SH(corner c), w_c the product of frac or 1 - frac per axis.
void trilinear_halves(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]);
void trilinear_apv(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]);

// The scalar versions (the reference of the tests).
void trilinear_halves_scalar(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]);
void trilinear_apv_scalar(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]);

}  // namespace bench
