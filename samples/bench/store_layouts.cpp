#include "store_layouts.h"

namespace bench {

const std::vector<StoreLayout>& store_layouts() {
    static const std::vector<StoreLayout> layouts = {
        {"fast", "fast layout", [](tp_build_options*) {}},
        {"compact", "compact layout", [](tp_build_options* o) { o->flags |= TP_BUILD_COMPACT; }},
    };
    return layouts;
}

const StoreLayout* find_store_layout(const std::string& id) {
    for (const StoreLayout& layout : store_layouts())
        if (layout.id == id) return &layout;
    return nullptr;
}

}  // namespace bench
