#include "bake/quake3_patch.h"

#include <cstddef>

namespace tetprobe {

namespace {

// The quadratic Bernstein weights at t.
void bernstein2(double t, double out[3]) {
    const double s = 1.0 - t;
    out[0] = s * s, out[1] = 2.0 * s * t, out[2] = t * t;
}

}  // namespace

PatchTessellation tessellate_quake3_patch(const double* positions, const double* normals, int width, int height,
                                          uint32_t segments) {
    PatchTessellation out;
    const uint32_t side = segments + 1;
    for (int piece_row = 0; piece_row + 2 < height; piece_row += 2)
        for (int piece_column = 0; piece_column + 2 < width; piece_column += 2) {
            const uint32_t first = uint32_t(out.positions.size() / 3);
            for (uint32_t j = 0; j <= segments; ++j) {
                double bv[3];
                bernstein2(double(j) / double(segments), bv);
                for (uint32_t i = 0; i <= segments; ++i) {
                    double bu[3];
                    bernstein2(double(i) / double(segments), bu);
                    double p[3] = {0, 0, 0}, n[3] = {0, 0, 0};
                    for (int r = 0; r < 3; ++r)
                        for (int c = 0; c < 3; ++c) {
                            const double w = bv[r] * bu[c];
                            const size_t k = 3 * (size_t(piece_row + r) * size_t(width) + size_t(piece_column + c));
                            for (int a = 0; a < 3; ++a) p[a] += w * positions[k + a], n[a] += w * normals[k + a];
                        }
                    out.positions.insert(out.positions.end(), p, p + 3);
                    out.normals.insert(out.normals.end(), n, n + 3);
                }
            }
            for (uint32_t j = 0; j < segments; ++j)
                for (uint32_t i = 0; i < segments; ++i) {
                    const uint32_t a = first + j * side + i, b = a + 1, c = a + side + 1, d = a + side;
                    const uint32_t quad[6] = {a, b, c, a, c, d};
                    out.triangles.insert(out.triangles.end(), quad, quad + 6);
                }
        }
    return out;
}

}  // namespace tetprobe
