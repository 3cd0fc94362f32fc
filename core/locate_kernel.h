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

// How a 3-dimensional store's interpolate_batch walks: lanes, eight queries at once in structure of arrays
// (walk_lanes.inl), or loop, the single walk query after query with their loads asked for ahead. The same
// bits either way. TP_BATCH_KERNEL=loop or =lanes in the environment chooses (read at load, as TP_NO_AVX2:
// for tests and the benchmark).
enum class BatchKernel { loop, lanes };
BatchKernel detect_batch_kernel();

// The most queries a kernel's locate_batch takes at once.
constexpr size_t kMaxBatchGroup = 64;

// A store's walk compiled for its index width, its dimension and an instruction set, chosen once when
// the store is loaded (so no query tests any of them). The functions give the same answer for a
// query, bit for bit, and the same as the exhaustive search inside the hull.
struct LocateKernel {
    // One query at a local position, from hint (-1 or out of range: the start grid's cell), answered
    // in out (every field written, whatever it held: answers are written in place, never copied whole).
    void (*locate)(const Store::Impl& store, const float local[3], int32_t hint, Location& out);
    // count <= kMaxBatchGroup queries, one after the other with their loads asked for ahead, out as above.
    void (*locate_batch)(const Store::Impl& store, size_t count, const float (*local)[3], const int32_t* hints,
                         Location* out);
    // locate and answer_sh in one, without leak control (a store with it answers the queries in cells with a
    // blocked pair again, store_queries.cpp): from *hint as above, the SH into out_sh and the cell into *hint.
    // The lean walk's answer goes straight to the blend, with no Location in between.
    Status (*interpolate)(const Store::Impl& store, const float local[3], int32_t* hint, float out_sh[27]);
    // count <= kMaxBatchGroup of them: hints[i] in and out, out_sh[i] (27 floats each), status[i].
    void (*interpolate_batch)(const Store::Impl& store, size_t count, const float (*local)[3], int32_t* hints,
                              float* const* out_sh, Status* status);
    InstructionSet instruction_set;
    BatchKernel batch_kernel;  // which one interpolate_batch is (3-dimensional stores; the others have one)
};
LocateKernel choose_locate_kernel(const Store::Impl& store, InstructionSet instruction_set);

// A located query's SH (the store's blend; zero when it failed) and occlusion (when out_occlusion is not
// null). Returns its status. The front end's (store_queries.cpp), which the kernels call on their rare path.
Status answer_sh(const Store::Impl& store, const Location& loc, float out_sh[27], float* out_occlusion);

}  // namespace tetprobe
