// Our SH (the contract of capi/tetprobe.h: projected radiance, orthonormal basis) as the shader constants of
// Unity's built-in pipeline, unity_SHAr/Ag/Ab (and unity_SHBr/Bg/Bb, unity_SHC), which UnityCG.cginc's ShadeSH9
// evaluates: SHEvalLinearL0L1 is dot(SHAc, (n, 1)), SHEvalLinearL2 is dot(SHBc, n.xyzz * n.yzzx) + SHC.c (x^2 - y^2),
// and their sum is the exit radiance of a white Lambertian surface, E(n) / pi.
//
// Unity's coefficient i is ours times kUnityShScale[i] (u_i = c_i K_i A_l / pi: K_i the basis constants, A_l the
// cosine lobe's band factors pi, 2pi/3, pi/4), packed as SHAc = (u3, u1, u2, u0 - u6), SHBc = (u4, u5, 3 u6, u7),
// SHC = (u8 of r, g, b, 1). The L1 form drops band 2 (u4..u8 = 0): SHAc = (u3, u1, u2, u0), the L0 + L1 terms
// that Light Probe Proxy Volume textures hold.
#pragma once

namespace tetprobe {

// 1/(2 sqrt(pi)), sqrt(3)/(3 sqrt(pi)) for band 1, sqrt(15)/(8 sqrt(pi)) for L2-2, L2-1, L21, sqrt(5)/(16 sqrt(pi))
// for L20, sqrt(15)/(16 sqrt(pi)) for L22, each rounded to float.
extern const float kUnityShScale[9];

// Floats unity_sh_constants writes: 3 float4 (L1) or 7 (L2).
constexpr int kUnityL1Floats = 12;
constexpr int kUnityL2Floats = 28;

// Writes SHAr, SHAg, SHAb (with_l2: then SHBr, SHBg, SHBb, SHC) as float4s (x, y, z, w) into out, each product
// u_i = c_i * kUnityShScale[i] rounded to float, then w = u0 - u6 and 3 u6 (3 * u6 rounded) as written above.
void unity_sh_constants(const float sh[27], bool with_l2, float* out);

}  // namespace tetprobe
