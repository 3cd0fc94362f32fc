// The C ABI's structs and callbacks translated into bake/'s own types, one function each and nowhere
// else (full library only; the options structs are read next to their entry points: api_build.cpp,
// api_scene.cpp, api_placement.cpp).
#pragma once

#include "capi/tetprobe.h"

#include "bake/progress.h"

namespace tetprobe {

// tp_progress_fn has ProgressCallback's signature: the caller's callback is called as it is.
inline Progress progress_from_c(tp_progress_fn callback, void* user) {
    Progress progress;
    progress.callback = callback;
    progress.user = user;
    return progress;
}

}  // namespace tetprobe
