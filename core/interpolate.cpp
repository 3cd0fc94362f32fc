// Store::interpolate: locate, then blend the four probes' half SH (the dispatched F16C path or the
// portable one, see half.h).
#include "core/half.h"
#include "core/store.h"
#include "core/store_impl.h"

#include <algorithm>

namespace tetprobe {

tp_status Store::interpolate(const float world_position[3], int32_t* hint, float out_sh[27]) const {
    const Location loc = impl_->locate(*impl_, world_position, hint ? *hint : -1);
    if (hint) *hint = loc.cell;
    if (loc.status != TP_OK) {
        std::fill(out_sh, out_sh + 27, 0.0f);
        return loc.status;
    }
    const uint16_t* sh[4];
    for (int k = 0; k < 4; ++k) sh[k] = impl_->sh + size_t(loc.probes[k]) * 27;
    blend_sh_halves(sh, loc.weights, out_sh);
    return TP_OK;
}

}  // namespace tetprobe
