// How much inserting one held-out candidate into the current probes would lower the squared error
// summed over the held-out candidates (each stands for the same volume: the sum is the integrated
// error), estimated from the candidates' noisy values without building anything.
//
// The model is Delaunay insertion itself: the new probe's cavity is the connected set of cells whose
// circumsphere holds it, and inside the cavity the interpolant changes by phi(x) * r_i, where r_i is the
// candidate's residual (its value minus what the probes interpolate there) and phi its barycentric
// coordinate in the cone of new cells from it to the cavity's boundary (1 at the candidate, 0 on the
// boundary and beyond). So the gain is sum over held-out x of |r_x|^2 - |r_x - phi(x) r_i|^2
//   = sum 2 phi (r_x . r_i) - phi^2 |r_i|^2,
// with both terms corrected for the bake's noise: E[r_x . r_i] holds the noise the two share through
// common probes, E|r_i|^2 holds r_i's own; each is subtracted, so pure noise gains nothing on average.
// Outside the hull and in sets of lower dimension the cell alone is split (phi from the barycentric
// coordinates in the cell); beyond the hull the new probe also joins the hull, so phi there is at most a
// point's height above the outer cell's facet relative to the new probe's (the facet's points keep their
// values, as the new cell from the facet to the probe interpolates them). A candidate whose gain does not stand out from its noise (gain below
// kSignificance standard deviations) is chosen for coverage instead: the one that would take over the
// most held-out volume.
#pragma once

#include "bake/placement_signal.h"
#include "core/store.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

// Standard deviations by which a gain must exceed zero to be trusted.
constexpr double kSignificance = 1.0;

// What one round knows: the store of the chosen probes and, per candidate, where it falls and how far
// the interpolation is from its value.
struct RoundState {
    const Store* store = nullptr;
    std::vector<uint32_t> candidate_of_stored;  // stored probe -> candidate index
    std::vector<float> probe_noise;             // per stored probe: its candidate's noise variance
    // Per candidate (chosen ones too: their residual is zero).
    std::vector<int32_t> cell;
    std::vector<uint32_t> probes;    // 4 per candidate, stored indices
    std::vector<float> weights;      // 4 per candidate
    std::vector<double> residual;    // kSignalSize per candidate
    std::vector<double> noise;       // per candidate: the residual's noise variance (own and interpolated)
    std::vector<uint8_t> active;     // held out and counted in the error
    // Active candidates grouped by cell (CSR over cell ids).
    std::vector<uint32_t> cell_start, cell_members;
    // Inner cells' circumspheres (local coordinates): centre and squared radius (3-dimensional sets only).
    std::vector<double> spheres;     // 4 per inner cell
    std::vector<float> local;        // 3 per candidate: position in the store's local frame
};

struct InsertionGain {
    double gain = 0;       // noise-corrected drop of the summed squared error (sum over the kSignalSize)
    double deviation = 0;  // its noise's standard deviation
    double coverage = 0;   // sum of phi over the active candidates: the held-out volume it would take over
    std::vector<uint32_t> cavity;  // cells whose interpolant changes
};

// Fills spheres and cell_start / cell_members from the other fields.
void prepare_round(RoundState& state);

// The gain of inserting active candidate i (see above).
InsertionGain insertion_gain(const RoundState& state, uint32_t i);

}  // namespace tetprobe
