// tetprobe on a real level: a probe set baked with the level's probe settings, built into a store of one
// layout (store_layouts.h), and measured with the level's metric (level_eval.h). Bytes are the blob's size
// (what ships) and the heap the loaded store holds (the compact layout rebuilds its neighbours on load).
#pragma once

#include "level_eval.h"
#include "store_layouts.h"

#include <vector>

namespace bench {

// positions: 3 floats per probe; sh: 27 per probe (their bake). Throws std::runtime_error with
// tp_last_error when the build fails.
LevelResult evaluate_tetprobe(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh,
                              const StoreLayout& layout);

// The bytes of the blob the first `count` probes build into with the layout (what evaluate_tetprobe reports).
size_t tetprobe_store_bytes(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh,
                            size_t count, const StoreLayout& layout);

// A count whose first `count` probes build into at most `budget` bytes with the layout, found by bisection
// over [4, positions / 3] (the bytes grow with the count, up to a cell's worth either way, so it is the
// largest or within a few probes of it), or 0 when 4 probes exceed the budget.
size_t tetprobe_count_within(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh,
                             size_t budget, const StoreLayout& layout);

}  // namespace bench
