// tp_sh_eval_options and the run time's ShEvalOptions, both directions in one place: the defaults
// tp_sh_eval_options_init writes, and the reading of a caller's struct (of any struct_size).
#pragma once

#include "capi/boundary.h"
#include "capi/tetprobe.h"
#include "core/sh_eval_options.h"

#include <cmath>
#include <cstddef>
#include <string>

namespace tetprobe {

// One set of values: the C ABI's order and window constants are the run time's enumerators.
static_assert(TP_SH_ORDER_L2 == uint32_t(ShOrder::l2) && TP_SH_ORDER_L1 == uint32_t(ShOrder::l1) &&
                  TP_SH_ORDER_ZH3 == uint32_t(ShOrder::zh3),
              "TP_SH_ORDER_* must equal ShOrder");
static_assert(TP_SH_WINDOW_NONE == uint32_t(ShWindow::none) && TP_SH_WINDOW_SLOAN == uint32_t(ShWindow::sloan) &&
                  TP_SH_WINDOW_NONNEGATIVE == uint32_t(ShWindow::nonnegative),
              "TP_SH_WINDOW_* must equal ShWindow");

// The public struct holding options, full size.
inline tp_sh_eval_options to_tp_sh_eval_options(const ShEvalOptions& settings) {
    tp_sh_eval_options options{};
    options.struct_size = sizeof(tp_sh_eval_options);
    options.order = uint32_t(settings.order);
    options.window = uint32_t(settings.window);
    options.window_strength = settings.window_strength;
    return options;
}

// L2, no window: the run time's ShEvalOptions defaults.
inline tp_sh_eval_options default_sh_eval_options() { return to_tp_sh_eval_options(ShEvalOptions{}); }

// Whether a caller's struct of struct_size bytes reaches to the end of the field.
#define TP_SH_OPTION_FIELD(options, field)                                                        \
    (size_t((options)->struct_size) >= offsetof(tp_sh_eval_options, field) + sizeof((options)->field))

// Only the order from the caller's options (NULL = L2), for functions that read no other field:
// the window fields are not checked. Bad values give TP_ERROR_INVALID_ARGUMENT with a message.
inline tp_status read_sh_order(const tp_sh_eval_options* options, ShOrder& out) {
    out = ShEvalOptions{}.order;
    if (!options) return TP_OK;
    if (!TP_SH_OPTION_FIELD(options, order))
        return fail(TP_ERROR_INVALID_ARGUMENT, "options->struct_size " + std::to_string(options->struct_size) +
                                                   " is too small (call tp_sh_eval_options_init)");
    if (options->order > TP_SH_ORDER_ZH3)
        return fail(TP_ERROR_INVALID_ARGUMENT, "options->order " + std::to_string(options->order) +
                                                   " is not a TP_SH_ORDER_* value");
    out = ShOrder(options->order);
    return TP_OK;
}

// The run time's options from the caller's (NULL = defaults); fields past struct_size keep their
// defaults. Bad values give TP_ERROR_INVALID_ARGUMENT with a message.
inline tp_status read_sh_eval_options(const tp_sh_eval_options* options, ShEvalOptions& out) {
    out = ShEvalOptions{};
    if (tp_status s = read_sh_order(options, out.order)) return s;
    if (!options) return TP_OK;
    if (TP_SH_OPTION_FIELD(options, window)) {
        if (options->window > TP_SH_WINDOW_NONNEGATIVE)
            return fail(TP_ERROR_INVALID_ARGUMENT, "options->window " + std::to_string(options->window) +
                                                       " is not a TP_SH_WINDOW_* value");
        out.window = ShWindow(options->window);
    }
    if (out.window == ShWindow::sloan) {
        const float strength = TP_SH_OPTION_FIELD(options, window_strength) ? options->window_strength : 0.0f;
        if (!std::isfinite(strength) || strength < 0)
            return fail(TP_ERROR_INVALID_ARGUMENT, "options->window_strength " + std::to_string(strength) +
                                                       " must be finite and >= 0");
        out.window_strength = strength;
    }
    return TP_OK;
}

#undef TP_SH_OPTION_FIELD

}  // namespace tetprobe
