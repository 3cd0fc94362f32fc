// The store layouts the real-level benchmark builds for every tetprobe probe set, by name: each fills
// tp_build_options its own way, so a new build option (an SH encoding, quantised positions) is one more
// row of store_layouts.cpp and every part that loops over the layouts measures it. Layouts that need the
// level's scene (leak control) get it too.
#pragma once

#include "capi/tetprobe.h"

#include <string>
#include <vector>

namespace bench {

struct StoreLayout {
    std::string id;     // "fast", "compact", ...
    std::string label;  // for tables and legends
    // Sets the layout's options on initialised defaults; scene: the level's (valid during the build).
    void (*apply)(tp_build_options* options, const tp_scene* scene);
};

// The layouts every part measures.
const std::vector<StoreLayout>& store_layouts();

// The layout named id among those and the optional ones (leak control: "fast_leak", "compact_leak"),
// or nullptr.
const StoreLayout* find_store_layout(const std::string& id);

}  // namespace bench
