// Progress and cancel of long bake-time work (the bake, placement, occlusion, the store build): a plain
// callback, the slice [from, to] of the caller's progress this work reports into, and one way to stop.
// The C ABI's tp_progress_fn has the callback's signature; the boundary adapts it once (progress_from_c).
#pragma once

namespace tetprobe {

// Returns non-zero to cancel. fraction is in [0, 1]; stage names the work ("bake", "select", ...).
using ProgressCallback = int (*)(void* user, float fraction, const char* stage);

struct Progress {
    ProgressCallback callback = nullptr;  // nullptr: nothing is reported, nothing cancels
    void* user = nullptr;
    float from = 0.0f, to = 1.0f;

    // Reports `fraction` of this slice; throws Error(Status::cancelled) when the callback asks to stop.
    void report(double fraction, const char* stage) const;
    // The sub-slice [a, b] of this one (a, b in [0, 1]), for work made of stages.
    Progress part(double a, double b) const;
};

}  // namespace tetprobe
