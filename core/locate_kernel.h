// The query kernel of a store: its walk compiled for its index width, its dimension and the CPU's
// instruction set, chosen once at load and kept in the store (no query tests any of them again).
#pragma once

#include "core/store.h"

#include <cstddef>
#include <cstdint>

namespace tetprobe {

// The instruction sets the query kernels are compiled for: portable C++, or AVX2 with F16C and FMA
// (every CPU with AVX2 has the other two; FMA is never used where it would change a result).
enum class InstructionSet { portable, avx2 };
// The best this CPU runs; TP_NO_AVX2 in the environment forces the portable one (read here only,
// once per store at load, so that tests and the benchmark can compare the two).
InstructionSet detect_instruction_set();

// The most queries a kernel's locate_batch takes at once.
constexpr size_t kMaxBatchGroup = 64;

// A store's walk compiled for its index width, its dimension and an instruction set, chosen once when
// the store is loaded (so no query tests any of them). Both functions give the same answer for a
// query, bit for bit, and the same as the exhaustive search inside the hull.
struct LocateKernel {
    // One query at a local position, from hint (-1 or out of range: the start grid's cell), answered
    // in out (every field written, whatever it held: answers are written in place, never copied whole).
    void (*locate)(const Store::Impl& store, const float local[3], int32_t hint, Location& out);
    // count <= kMaxBatchGroup queries, one after the other with their loads asked for ahead,
    // out as above.
    void (*locate_batch)(const Store::Impl& store, size_t count, const float (*local)[3], const int32_t* hints,
                         Location* out);
    InstructionSet instruction_set;
};
LocateKernel choose_locate_kernel(const Store::Impl& store, InstructionSet instruction_set);

}  // namespace tetprobe
