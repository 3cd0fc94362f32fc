// Sloan's deringing window ("Deringing Spherical Harmonics", SIGGRAPH Asia 2017 technical briefs) and
// the search for the weakest one that keeps the float irradiance non-negative.
#pragma once

namespace tetprobe {

// The least-squares fit to the coefficients penalised by strength times the squared Laplacian, whose
// eigenvalue on band l is -l(l+1): band l scaled by 1 / (1 + strength (l (l + 1))^2); band 0 keeps 1
// and strength 0 is the identity.
double sh_sloan_window(int band, double strength);

// Scales each band of sh by sh_sloan_window (each product rounded once to float); infinite strength
// keeps band 0 only.
void sh_apply_sloan_window(float sh[27], double strength);

// The strength of the Sloan window for already ordered SH under which sh_eval_irradiance (in float) is
// provably non-negative at every normal: a channel passes when its proven lower bound of the minimum
// (sh_channel_min_irradiance) is at least sh_irradiance_rounding_bound of its windowed coefficients.
// 0 when every channel passes unwindowed, else the bisection (on the float strengths) between a strength
// that fails and one that passes, the two ending adjacent. Channels whose band 0 is not positive cannot
// be made non-negative by any window and are left out. Passing is not proven monotone in strength, so
// this is the smallest at the boundary the search brackets, from strength 2^-10 doubled upwards.
// Returns infinity when no finite float strength suffices.
double sh_nonnegative_window_strength(const float ordered_sh[27]);

}  // namespace tetprobe
