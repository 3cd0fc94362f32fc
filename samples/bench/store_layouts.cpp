#include "store_layouts.h"

namespace bench {

const std::vector<StoreLayout>& store_layouts() {
    static const std::vector<StoreLayout> layouts = {
        {"fast", "fast layout", [](tp_build_options*, const tp_scene*) {}},
        {"compact", "compact layout", [](tp_build_options* o, const tp_scene*) { o->flags |= TP_BUILD_COMPACT; }},
    };
    return layouts;
}

namespace {

// Measured on request (tetprobe_bench levels eval --layout ID), not by every part.
const std::vector<StoreLayout>& optional_layouts() {
    static const std::vector<StoreLayout> layouts = {
        {"fast_leak", "fast layout, leak control", [](tp_build_options* o, const tp_scene* s) { o->scene = s; }},
        {"compact_leak", "compact layout, leak control",
         [](tp_build_options* o, const tp_scene* s) { o->flags |= TP_BUILD_COMPACT, o->scene = s; }},
    };
    return layouts;
}

}  // namespace

const StoreLayout* find_store_layout(const std::string& id) {
    for (const auto* list : {&store_layouts(), &optional_layouts()})
        for (const StoreLayout& layout : *list)
            if (layout.id == id) return &layout;
    return nullptr;
}

}  // namespace bench
