// Our SH (the contract of capi/tetprobe.h: projected radiance, orthonormal basis) to and from Unity's
// SphericalHarmonicsL2 and its shader constants unity_SHAr..unity_SHC. Compiled inside Unity only.
//
// Derivation. UnityCG.cginc's ShadeSH9(n) = SHEvalLinearL0L1 + SHEvalLinearL2 evaluates the seven constants, which
// Unity packs from its SphericalHarmonicsL2 u as SHA = (u3, u1, u2, u0 - u6), SHB = (u4, u5, 3 u6, u7), SHC = u8, so
// ShadeSH9(n) = sum_i u_i P_i(n) over the bare polynomials P = (1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2). The
// shader multiplies it by the albedo: it is the exit radiance of a white Lambertian surface, E(n) / pi. Our probes
// give E(n) = sum_i A_l c_i K_i P_i(n) (K_i the basis constants of the header, A_l = pi, 2pi/3, pi/4). Hence
// u_i = c_i K_i A_l / pi = c_i * (1/(2 sqrt(pi)); sqrt(3)/(3 sqrt(pi)) for L1; sqrt(15)/(8 sqrt(pi)) for L2-2, L2-1, L21;
// sqrt(5)/(16 sqrt(pi)) for L20; sqrt(15)/(16 sqrt(pi)) for L22): the constants of appendix A10 of Sloan's "Stupid
// Spherical Harmonics Tricks", the reconstruction Unity's manual names, and of SRP's SphericalHarmonicMath (whose
// alternating signs only turn Sloan's Condon-Shortley basis into ours). So Unity's AddAmbientLight(C), u0 += C, is
// uniform radiance C (our AddAmbientLight(C)); its AddDirectionalLight(d, C, I) projects Sloan's directional light, a
// radiance delta arriving from d of weight 2 I C * 16pi/17 (16pi/17 puts the L2 lobe's exit radiance facing the light at
// 1; the 2 is Unity's), which is our AddDirectionalLight(-d, 2 I C * 16pi/17).
#if UNITY_5_3_OR_NEWER
using System;
using UnityEngine;
using UnitySH = UnityEngine.Rendering.SphericalHarmonicsL2;

namespace TetProbe
{
    /// <summary>Conversions between our SH and Unity's conventions (see the derivation at the top of this file).</summary>
    public static class UnitySphericalHarmonics
    {
        /// <summary>Unity's coefficient i = ours * Scale[i] (the same for each colour channel).</summary>
        public static readonly float[] Scale = ComputeScale();

        static float[] ComputeScale()
        {
            double sqrtPi = Math.Sqrt(Math.PI);
            double l0 = 1 / (2 * sqrtPi), l1 = Math.Sqrt(3) / (3 * sqrtPi), l2 = Math.Sqrt(15) / (8 * sqrtPi);
            double l20 = Math.Sqrt(5) / (16 * sqrtPi), l22 = Math.Sqrt(15) / (16 * sqrtPi);
            return new[] { (float)l0, (float)l1, (float)l1, (float)l1, (float)l2, (float)l2, (float)l20, (float)l2, (float)l22 };
        }

        /// <summary>Unity's SphericalHarmonicsL2 of the same light (what LightProbes and RenderSettings.ambientProbe hold).</summary>
        public static UnitySH ToUnity(SphericalHarmonicsL2 sh)
        {
            var unity = new UnitySH();
            for (int c = 0; c < 3; ++c)
                for (int i = 0; i < 9; ++i) unity[c, i] = sh[c, i] * Scale[i];
            return unity;
        }

        /// <summary>Our SH (projected radiance) of a Unity SphericalHarmonicsL2, e.g. RenderSettings.ambientProbe as a sky.</summary>
        public static SphericalHarmonicsL2 FromUnity(UnitySH unity)
        {
            var sh = new SphericalHarmonicsL2();
            for (int c = 0; c < 3; ++c)
                for (int i = 0; i < 9; ++i) sh[c, i] = unity[c, i] / Scale[i];
            return sh;
        }

        /// <summary>Writes unity_SHAr, unity_SHAg, unity_SHAb, unity_SHBr, unity_SHBg, unity_SHBb, unity_SHC (in that order)
        /// into constants[0..6]: ShadeSH9 of them is the irradiance of `sh` divided by pi.</summary>
        public static void ToShaderConstants(SphericalHarmonicsL2 sh, Vector4[] constants)
        {
            if (constants == null || constants.Length < 7) throw new ArgumentException("constants must hold 7", "constants");
            UnitySH u = ToUnity(sh);
            for (int c = 0; c < 3; ++c)
            {
                constants[c] = new Vector4(u[c, 3], u[c, 1], u[c, 2], u[c, 0] - u[c, 6]);
                constants[3 + c] = new Vector4(u[c, 4], u[c, 5], 3 * u[c, 6], u[c, 7]);
            }
            constants[6] = new Vector4(u[0, 8], u[1, 8], u[2, 8], 1);
        }
    }
}
#endif
