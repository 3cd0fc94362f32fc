#include "bake/exact_orientation.h"

#include "bake/tetgen_guard.h"

#include <tetgen.h>

#include <cmath>
#include <mutex>

// Also in libtet (Shewchuk's predicates as TetGen 1.5 ships them), not declared by tetgen.h.
REAL orient3dexact(REAL* pa, REAL* pb, REAL* pc, REAL* pd);
REAL orient2dexact(REAL* pa, REAL* pb, REAL* pc);

namespace tetprobe {

namespace {

constexpr double kEpsilon = 0x1p-53;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;  // Shewchuk's o3derrboundA
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;  // Shewchuk's ccwerrboundA
// Below this the bound's products may be denormal (relative rounding no longer holds): go exact.
constexpr double kUnderflowGuard = 1e-280;

// The exact predicates read constants that exactinit sets (TetGen sets the same ones on every call).
void ensure_exact_arithmetic() {
    static std::once_flag once;
    std::call_once(once, [] {
        std::lock_guard<std::mutex> lock(tetgen_mutex());
        exactinit(0, 0, 0, 1.0, 1.0, 1.0);
    });
}

int sign_of(double value) { return (value > 0) - (value < 0); }

}  // namespace

int orient3d_sign(const double* a, const double* b, const double* c, const double* d) {
    // Shewchuk's filter, with the differences taken from a instead of d (the same bound holds).
    const double adx = b[0] - a[0], ady = b[1] - a[1], adz = b[2] - a[2];
    const double bdx = c[0] - a[0], bdy = c[1] - a[1], bdz = c[2] - a[2];
    const double cdx = d[0] - a[0], cdy = d[1] - a[1], cdz = d[2] - a[2];
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    const double cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                             (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                             (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
    const double bound = kOrient3dBound * permanent;
    if ((det > bound || -det > bound) && permanent > kUnderflowGuard) return sign_of(det);
    ensure_exact_arithmetic();
    // TetGen's (Shewchuk's) orient3d(p, q, r, s) = det[p-s, q-s, r-s] = -det[q-p, r-p, s-p].
    double p[3] = {a[0], a[1], a[2]}, q[3] = {b[0], b[1], b[2]}, r[3] = {c[0], c[1], c[2]}, s[3] = {d[0], d[1], d[2]};
    return -sign_of(orient3dexact(p, q, r, s));
}

int orient2d_sign(const double* a, const double* b, const double* c) {
    // det[b - a, c - a] = Shewchuk's orient2d(a, b, c) = (a - c) x (b - c).
    const double left = (a[0] - c[0]) * (b[1] - c[1]);
    const double right = (a[1] - c[1]) * (b[0] - c[0]);
    const double det = left - right;
    const double bound = kOrient2dBound * (std::fabs(left) + std::fabs(right));
    if ((det > bound || -det > bound) && std::fabs(left) + std::fabs(right) > kUnderflowGuard) return sign_of(det);
    ensure_exact_arithmetic();
    double p[2] = {a[0], a[1]}, q[2] = {b[0], b[1]}, r[2] = {c[0], c[1]};
    return sign_of(orient2dexact(p, q, r));
}

}  // namespace tetprobe
