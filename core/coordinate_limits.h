// The coordinate limit shared by the store builder and the loader: the builder refuses probes beyond
// it, and the loader refuses a blob whose origin or positions lie beyond what the builder can write.
#pragma once

namespace tetprobe {

// Largest world coordinate magnitude a probe may have: far beyond any world, small enough that squared
// distances and cross products stay finite in double, and that a query's local position (world minus
// an origin within it) stays a finite float for every finite float query.
constexpr double kMaxCoordinate = 1e30;

// Largest local coordinate magnitude (world minus the origin) the builder writes. The origin is the
// centre of the probes' bounding box, so a probe is within kMaxCoordinate of it; a probe moved onto the
// fitted plane or line of a flat or line set moves by at most (1 + sqrt 3) x its distance from it,
// at most the flat tolerance (<= 0.1) x the set's diagonal (<= 2 sqrt(3) kMaxCoordinate): less than
// 0.95 kMaxCoordinate more.
constexpr double kMaxLocalCoordinate = 2 * kMaxCoordinate;

}  // namespace tetprobe
