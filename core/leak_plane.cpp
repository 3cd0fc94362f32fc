#include "core/leak_plane.h"

#include "core/exact_sum.h"
#include "core/octahedral_normal.h"

#include <cmath>
#include <cstdlib>

namespace tetprobe {

namespace {

// Exact sign of t[0] + t[1] + t[2] + t[3].
int exact_sign_of_sum(const double t[4]) {
    double e[4];
    int n = 0;
    for (int k = 0; k < 4; ++k) n = grow_expansion(e, n, t[k]);
    return expansion_sign(e, n);
}

// The smallest float strictly above / below x (a double), or x's neighbour when x is a float.
float float_above(double x) {
    float f = float(x);
    while (!(double(f) > x)) f = std::nextafter(f, INFINITY);
    return f;
}

}  // namespace

void leak_plane_normal(const int16_t code[2], int32_t out[3]) {
    int32_t u = code[0] < -32767 ? -32767 : code[0], v = code[1] < -32767 ? -32767 : code[1];
    const int32_t z = 32767 - std::abs(u) - std::abs(v);
    if (z < 0) {
        const int32_t folded_u = (32767 - std::abs(v)) * (u >= 0 ? 1 : -1);
        v = (32767 - std::abs(u)) * (v >= 0 ? 1 : -1);
        u = folded_u;
    }
    out[0] = u, out[1] = v, out[2] = z;
}

int leak_plane_side(const int16_t code[2], float offset, const float point[3]) {
    LeakPlane plane;
    leak_plane_normal(code, plane.normal);
    plane.offset = offset;
    return leak_plane_side(plane, point);
}

int leak_plane_side(const LeakPlane& plane, const float point[3]) {
    const int32_t* n = plane.normal;
    const float offset = plane.offset;
    // Each term is exact (a 15-bit integer times a float); only the three additions round, each by at
    // most half an ulp of its result, so |computed - exact| <= 3 eps (1 + 3 eps) sum |t_k| (eps = 2^-53),
    // within 4 eps times the computed sum of magnitudes (itself rounded by at most 3 eps relative).
    const double t[4] = {double(n[0]) * point[0], double(n[1]) * point[1], double(n[2]) * point[2], -double(offset)};
    const double sum = ((t[0] + t[1]) + t[2]) + t[3];
    const double magnitude = ((std::fabs(t[0]) + std::fabs(t[1])) + std::fabs(t[2])) + std::fabs(t[3]);
    if (std::fabs(sum) > 0x1p-51 * magnitude) return sum > 0 ? 1 : -1;
    return exact_sign_of_sum(t);
}

bool make_leak_plane(const double normal[3], const double crossing[3], const float own[3], const float other[3],
                     int16_t code[2], float* offset) {
    // The offset through the crossing, then moved (by whole float steps) until own is strictly in front and
    // other strictly behind: the plane still passes within a few float steps of the crossing.
    const auto place = [&](const double direction[3]) {
        double towards_own = 0;
        for (int k = 0; k < 3; ++k) towards_own += direction[k] * (double(own[k]) - crossing[k]);
        double n[3];
        for (int k = 0; k < 3; ++k) n[k] = towards_own >= 0 ? direction[k] : -direction[k];
        if (!(std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]) > 0)) return false;
        encode_normal(n, code);
        int32_t m[3];
        leak_plane_normal(code, m);
        double along = 0;
        for (int k = 0; k < 3; ++k) along += double(m[k]) * crossing[k];
        float d = float(along);
        if (!std::isfinite(d)) return false;
        for (int step = 0; step < 64; ++step) {
            const bool own_front = leak_plane_side(code, d, own) > 0, other_behind = leak_plane_side(code, d, other) < 0;
            if (own_front && other_behind) return *offset = d, true;
            if (!own_front && !other_behind) return false;  // the code's normal does not separate them
            d = own_front ? float_above(double(d)) : std::nextafter(d, -INFINITY);
            if (!std::isfinite(d)) return false;
        }
        return false;
    };
    if (place(normal)) return true;
    const double along_segment[3] = {double(own[0]) - other[0], double(own[1]) - other[1], double(own[2]) - other[2]};
    return place(along_segment);
}

}  // namespace tetprobe
