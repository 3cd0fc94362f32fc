#include "core/octahedral_normal.h"

#include <cmath>

namespace tetprobe {

namespace {

constexpr double kCodeScale = 32767.0;

inline double sign_of(double x) { return x >= 0 ? 1.0 : -1.0; }

// The octahedral square's point of a direction (x, y, z), not necessarily unit.
void project(const double n[3], double* u, double* v) {
    const double l1 = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
    const double x = n[0] / l1, y = n[1] / l1, z = n[2] / l1;
    if (z >= 0) {
        *u = x, *v = y;
    } else {
        *u = (1 - std::fabs(y)) * sign_of(x);
        *v = (1 - std::fabs(x)) * sign_of(y);
    }
}

// Cosine of the angle between a and b (both non-zero).
double cosine(const float a[3], const double b[3]) {
    double dot = 0, aa = 0, bb = 0;
    for (int k = 0; k < 3; ++k) {
        dot += double(a[k]) * b[k];
        aa += double(a[k]) * double(a[k]);
        bb += b[k] * b[k];
    }
    return dot / (std::sqrt(aa) * std::sqrt(bb));
}

}  // namespace

void decode_normal(const int16_t code[2], float out[3]) {
    double u = std::fmax(double(code[0]) / kCodeScale, -1.0), v = std::fmax(double(code[1]) / kCodeScale, -1.0);
    const double z = 1 - std::fabs(u) - std::fabs(v);
    if (z < 0) {
        const double folded_u = (1 - std::fabs(v)) * sign_of(u);
        v = (1 - std::fabs(u)) * sign_of(v);
        u = folded_u;
    }
    const double length = std::sqrt(u * u + v * v + z * z);
    out[0] = float(u / length);
    out[1] = float(v / length);
    out[2] = float(z / length);
}

void encode_normal(const double n[3], int16_t code[2]) {
    double u, v;
    project(n, &u, &v);
    const long cu = std::lround(u * kCodeScale), cv = std::lround(v * kCodeScale);
    double best = -2;
    for (long a = cu - 1; a <= cu + 1; ++a) {
        for (long b = cv - 1; b <= cv + 1; ++b) {
            if (a < -32767 || a > 32767 || b < -32767 || b > 32767) continue;
            const int16_t candidate[2] = {int16_t(a), int16_t(b)};
            float d[3];
            decode_normal(candidate, d);
            const double c = cosine(d, n);
            if (c > best) best = c, code[0] = candidate[0], code[1] = candidate[1];
        }
    }
}

void quantize_normal(const double n[3], float out[3]) {
    int16_t code[2];
    encode_normal(n, code);
    decode_normal(code, out);
}

}  // namespace tetprobe
