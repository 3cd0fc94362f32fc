// Stand-in of UnityEngine.Rendering.SphericalHarmonicsL2 whose AddAmbientLight and AddDirectionalLight follow Unity's
// published formulas, not ours: the C# reference source doubles the intensity (color * (2 * intensity)) and the native
// part projects Sloan's directional light (Condon-Shortley basis, normalised by 16pi/17 so the exit radiance facing it
// is 1) and stores each radiance coefficient times the constants of appendix A10 of "Stupid SH Tricks" (the
// reconstruction Unity's manual cites; the same as SRP's SphericalHarmonicMath). Ambient: radiance C is coefficient
// 2 sqrt(pi) C, stored times 1/(2 sqrt(pi)).
using System;

namespace UnityEngine.Rendering
{
    public enum LightProbeUsage { Off = 0, BlendProbes = 1, UseProxyVolume = 2, CustomProvided = 4 }

    public static class GraphicsSettings
    {
        /// <summary>Off by default in the built-in pipeline: colour times intensity is linearised together.</summary>
        public static bool lightsUseLinearIntensity { get; set; }
    }

    public struct SphericalHarmonicsL2
    {
        // Read and written through a pointer to shr0 (the 27 floats are sequential), hence "never used".
#pragma warning disable 169
        float shr0, shr1, shr2, shr3, shr4, shr5, shr6, shr7, shr8;
        float shg0, shg1, shg2, shg3, shg4, shg5, shg6, shg7, shg8;
        float shb0, shb1, shb2, shb3, shb4, shb5, shb6, shb7, shb8;
#pragma warning restore 169

        public float this[int rgb, int coefficient]
        {
            get
            {
                unsafe
                {
                    fixed (float* first = &shr0) return first[Index(rgb, coefficient)];
                }
            }
            set
            {
                unsafe
                {
                    fixed (float* first = &shr0) first[Index(rgb, coefficient)] = value;
                }
            }
        }

        static int Index(int rgb, int coefficient)
        {
            if (rgb < 0 || rgb > 2 || coefficient < 0 || coefficient > 8) throw new IndexOutOfRangeException("Invalid index!");
            return rgb * 9 + coefficient;
        }

        static readonly double SqrtPi = Math.Sqrt(Math.PI);

        // Appendix A10 of Sloan's "Stupid SH Tricks": stored coefficient = A10[i] * radiance coefficient (Condon-Shortley).
        static readonly double[] A10 =
        {
            1 / (2 * SqrtPi), -Math.Sqrt(3) / (3 * SqrtPi), Math.Sqrt(3) / (3 * SqrtPi), -Math.Sqrt(3) / (3 * SqrtPi),
            Math.Sqrt(15) / (8 * SqrtPi), -Math.Sqrt(15) / (8 * SqrtPi), Math.Sqrt(5) / (16 * SqrtPi), -Math.Sqrt(15) / (8 * SqrtPi),
            Math.Sqrt(15) / (16 * SqrtPi),
        };

        /// <summary>Sloan's SHEvalDirection9: the real SH basis with the Condon-Shortley phase.</summary>
        static double[] EvalDirection(Vector3 d)
        {
            return new[]
            {
                1 / (2 * SqrtPi), -Math.Sqrt(3) / (2 * SqrtPi) * d.y, Math.Sqrt(3) / (2 * SqrtPi) * d.z, -Math.Sqrt(3) / (2 * SqrtPi) * d.x,
                Math.Sqrt(15) / (2 * SqrtPi) * d.x * d.y, -Math.Sqrt(15) / (2 * SqrtPi) * d.y * d.z,
                Math.Sqrt(5) / (4 * SqrtPi) * (3 * d.z * d.z - 1), -Math.Sqrt(15) / (2 * SqrtPi) * d.x * d.z,
                Math.Sqrt(15) / (4 * SqrtPi) * (d.x * d.x - d.y * d.y),
            };
        }

        void AddRadiance(double[] radiance, Color color)
        {
            float[] rgb = { color.r, color.g, color.b };
            for (int c = 0; c < 3; ++c)
                for (int i = 0; i < 9; ++i) this[c, i] += (float)(A10[i] * radiance[i] * rgb[c]);
        }

        public void AddAmbientLight(Color color)
        {
            AddRadiance(new[] { 2 * SqrtPi, 0, 0, 0, 0, 0, 0, 0, 0 }, color);
        }

        /// <summary>direction: from the probe towards the light (Unity's documentation).</summary>
        public void AddDirectionalLight(Vector3 direction, Color color, float intensity)
        {
            Color colorAndIntensity = color * (2.0f * intensity);
            double[] basis = EvalDirection(direction);
            double normalization = 16 * Math.PI / 17;
            for (int i = 0; i < 9; ++i) basis[i] *= normalization;
            AddRadiance(basis, colorAndIntensity);
        }
    }
}
