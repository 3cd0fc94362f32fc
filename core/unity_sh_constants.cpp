// Our SH to Unity's ShadeSH9 constants (see the header for the derivation).
#include "core/unity_sh_constants.h"

namespace tetprobe {

namespace {
constexpr float kL0 = float(0.28209479177387814);
constexpr float kL1 = float(0.32573500793527993);
constexpr float kL2 = float(0.2731371076480198);
constexpr float kL20 = float(0.07884789131313001);
constexpr float kL22 = float(0.1365685538240099);
}  // namespace

const float kUnityShScale[9] = {kL0, kL1, kL1, kL1, kL2, kL2, kL20, kL2, kL22};

void unity_sh_constants(const float sh[27], bool with_l2, float* out) {
    float u[3][9];
    const int bands = with_l2 ? 9 : 4;
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 9; ++i) u[c][i] = i < bands ? sh[9 * c + i] * kUnityShScale[i] : 0.0f;
    for (int c = 0; c < 3; ++c) {
        float* a = out + 4 * c;
        a[0] = u[c][3];
        a[1] = u[c][1];
        a[2] = u[c][2];
        a[3] = u[c][0] - u[c][6];
        if (!with_l2) continue;
        float* b = out + 12 + 4 * c;
        b[0] = u[c][4];
        b[1] = u[c][5];
        b[2] = 3.0f * u[c][6];
        b[3] = u[c][7];
    }
    if (!with_l2) return;
    out[24] = u[0][8];
    out[25] = u[1][8];
    out[26] = u[2][8];
    out[27] = 1.0f;
}

}  // namespace tetprobe
