#include "level_tetprobe.h"

#include <malloc.h>

#include <chrono>
#include <memory>
#include <stdexcept>

namespace bench {

namespace {

// Bytes of heap in use (small blocks and mapped large ones): the difference around a load is what the
// loaded store holds.
size_t heap_in_use() {
    const struct mallinfo2 info = mallinfo2();
    return info.uordblks + info.hblkhd;
}

}  // namespace

nlohmann::ordered_json LevelResult::json() const {
    nlohmann::ordered_json j = {{"method", method}, {"layout", layout}, {"label", label}, {"probes", probes},
                                {"bytes", bytes}, {"resident_bytes", resident_bytes},
                                {"rms_error", error.rms}, {"p95_error", error.p95}, {"max_error", error.max},
                                {"worst_jump", error.worst_jump}, {"ns_per_query", ns_per_query},
                                {"placement_seconds", placement_seconds}, {"bake_seconds", bake_seconds},
                                {"build_seconds", build_seconds}};
    if (!note.empty()) j["note"] = note;
    return j;
}

LevelResult evaluate_tetprobe(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh,
                              const StoreLayout& layout) {
    LevelResult r;
    r.method = "tetprobe";
    r.layout = layout.id;
    r.label = "tetprobe, " + layout.label;
    r.probes = positions.size() / 3;
    tp_build_options options;
    tp_build_options_init(&options);
    layout.apply(&options, level.handle.get());
    tp_store* built = nullptr;
    const auto start = std::chrono::steady_clock::now();
    if (tp_store_build(positions.data(), 0, sh.data(), 0, r.probes, &options, &built) != TP_OK)
        throw std::runtime_error(level.name + ": tp_store_build (" + layout.id + "): " + tp_last_error());
    r.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::unique_ptr<tp_store, tp_status (*)(tp_store*)> owner(built, tp_store_release);
    const void* blob = nullptr;
    size_t size = 0;
    tp_store_blob(built, &blob, &size);
    r.bytes = size;
    // The store every query below uses is the one loaded from the blob, as a game loads it.
    const size_t before = heap_in_use();
    tp_store* loaded = nullptr;
    if (tp_store_load(blob, size, &loaded) != TP_OK)
        throw std::runtime_error(level.name + ": tp_store_load (" + layout.id + "): " + tp_last_error());
    r.resident_bytes = heap_in_use() - before;
    std::unique_ptr<tp_store, tp_status (*)(tp_store*)> store(loaded, tp_store_release);
    int32_t hint = -1;
    measure_method(level, [&] { hint = -1; }, [&](const float* p, float* out) { tp_store_interpolate(loaded, p, &hint, out); },
                   &r);
    return r;
}

size_t tetprobe_store_bytes(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh,
                            size_t count, const StoreLayout& layout) {
    tp_build_options options;
    tp_build_options_init(&options);
    layout.apply(&options, level.handle.get());
    tp_store* built = nullptr;
    if (tp_store_build(positions.data(), 0, sh.data(), 0, count, &options, &built) != TP_OK)
        throw std::runtime_error(level.name + ": tp_store_build (" + layout.id + "): " + tp_last_error());
    std::unique_ptr<tp_store, tp_status (*)(tp_store*)> owner(built, tp_store_release);
    const void* blob = nullptr;
    size_t size = 0;
    tp_store_blob(built, &blob, &size);
    return size;
}

size_t tetprobe_count_within(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh,
                             size_t budget, const StoreLayout& layout) {
    size_t lo = 4, hi = positions.size() / 3;  // the answer lies in [lo, hi] once lo fits
    if (hi < lo || tetprobe_store_bytes(level, positions, sh, lo, layout) > budget) return 0;
    if (tetprobe_store_bytes(level, positions, sh, hi, layout) <= budget) return hi;
    while (hi - lo > 1) {  // lo fits, hi does not
        const size_t mid = lo + (hi - lo) / 2;
        (tetprobe_store_bytes(level, positions, sh, mid, layout) <= budget ? lo : hi) = mid;
    }
    return lo;
}

}  // namespace bench
