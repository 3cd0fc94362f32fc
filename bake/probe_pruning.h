// Error-driven pruning of a baked probe set: probes are removed, cheapest first, until a target
// count or an error bound, and the error is reported against the number of probes.
//
// Error: the irradiance the probes interpolate at held-out points (the given ones and every probe's
// own position, so a removed probe is held out too), compared with what the full set interpolates
// there: at each point the RMS over every normal direction and the three channels (the irradiance
// SH's own L2 norm) relative to the full set's own there, so dim and bright places count alike;
// then the RMS over the points. It is measured exactly after each round, on a real store
// built from the remaining probes.
//
// Cost of removing a probe, estimated locally: Delaunay removal changes the interpolant only in the
// probe's star, where the neighbours' values then interpolate linearly; so the change at a held-out
// point h is close to w_p(h) * (E_p - A(p)), with w_p(h) p's current weight at h and A the affine
// least-squares fit of p's Delaunay neighbours' irradiance, evaluated at p; the cost sums its square
// over the held-out points, each weighed as in the error. A round sorts the probes by that cost,
// removes a batch of the cheapest of which no two are neighbours (so the estimates stay independent;
// up to a tenth of the probes), rebuilds, and measures. A round that would cross the
// error bound is retried with half the batch, down to one probe; when the eight cheapest single
// probes each cross it, pruning stops.
#pragma once

#include "bake/parallel_jobs.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

struct PruneSettings {
    uint32_t target_count = 0;  // stop at this many probes (0: no target)
    double error_bound = 0;     // never exceed this relative error (0: no bound)
    uint32_t threads = 1;       // for the interpolation at held-out points
};

struct ErrorCurvePoint {
    uint32_t probes = 0;
    double error = 0;  // relative, see above
};

struct PruneResult {
    std::vector<uint32_t> kept;          // indices of the kept probes, ascending
    std::vector<ErrorCurvePoint> curve;  // one point per round, from the full set (error 0) down
};

// positions: 3 floats per probe (world); sh: 27 per probe; held_out: 3 per point (may be empty). Nothing is pruned when there is neither a target nor a bound. The result
// depends only on the input, not on the thread count. Throws Error(Status::cancelled) from progress.
PruneResult prune_probes(const std::vector<float>& positions, const std::vector<float>& sh,
                         const std::vector<float>& held_out, const PruneSettings& settings,
                         const Progress& progress);

// The irradiance SH of a probe's radiance SH (the cosine lobe's band factors applied).
void irradiance_coefficients(const float sh[27], double out[27]);
// RMS over every normal direction and the three channels of the irradiance given by coefficients.
double irradiance_rms(const double coefficients[27]);

}  // namespace tetprobe
