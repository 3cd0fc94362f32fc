#include "core/sh_eval_options.h"

#include "core/sh.h"
#include "core/sh_min_irradiance.h"
#include "core/sh_window.h"
#include "core/sh_zh3.h"

#include <cstring>

namespace tetprobe {

void sh_apply_order(float sh[27], ShOrder order) {
    switch (order) {
        case ShOrder::l2: return;
        case ShOrder::l1:
            for (int c = 0; c < 3; ++c)
                for (int i = 4; i < 9; ++i) sh[9 * c + i] = 0.0f;
            return;
        case ShOrder::zh3: sh_apply_zh3(sh); return;
    }
}

void sh_apply_eval_options(float sh[27], const ShEvalOptions& options) {
    sh_apply_order(sh, options.order);
    switch (options.window) {
        case ShWindow::none: return;
        case ShWindow::sloan: sh_apply_sloan_window(sh, options.window_strength); return;
        case ShWindow::nonnegative: sh_apply_sloan_window(sh, sh_nonnegative_window_strength(sh)); return;
    }
}

void sh_eval_irradiance_with_options(const float sh[27], const float n[3], const ShEvalOptions& options,
                                     float out_rgb[3]) {
    if (options.window == ShWindow::none && options.order != ShOrder::zh3) {
        sh_eval_irradiance_bands(sh, n, options.order == ShOrder::l1 ? 2 : 3, out_rgb);
        return;
    }
    float rewritten[27];
    std::memcpy(rewritten, sh, sizeof rewritten);
    sh_apply_eval_options(rewritten, options);
    sh_eval_irradiance(rewritten, n, out_rgb);
}

void sh_min_irradiance_with_options(const float sh[27], const ShEvalOptions& options, float out_min_rgb[3],
                                    float out_normal[3]) {
    float rewritten[27];
    std::memcpy(rewritten, sh, sizeof rewritten);
    sh_apply_eval_options(rewritten, options);
    sh_min_irradiance(rewritten, out_min_rgb, out_normal);
}

}  // namespace tetprobe
