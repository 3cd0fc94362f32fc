// SphericalHarmonicsL2: 27 floats of L2 SH, channel-major [r0..r8, g0..g8, b0..b8], blittable, with the
// field layout of Unity's UnityEngine.Rendering.SphericalHarmonicsL2 (the contract is in capi/tetprobe.h).
using System;
using System.Runtime.InteropServices;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    [StructLayout(LayoutKind.Sequential)]
    public struct SphericalHarmonicsL2 : IEquatable<SphericalHarmonicsL2>
    {
        public const int Coefficients = 9;
        public const int Floats = 27;

        public float shr0;
        public float shr1;
        public float shr2;
        public float shr3;
        public float shr4;
        public float shr5;
        public float shr6;
        public float shr7;
        public float shr8;
        public float shg0;
        public float shg1;
        public float shg2;
        public float shg3;
        public float shg4;
        public float shg5;
        public float shg6;
        public float shg7;
        public float shg8;
        public float shb0;
        public float shb1;
        public float shb2;
        public float shb3;
        public float shb4;
        public float shb5;
        public float shb6;
        public float shb7;
        public float shb8;

        /// <summary>Coefficient `coefficient` (0..8) of channel `rgb` (0 red, 1 green, 2 blue).</summary>
        public float this[int rgb, int coefficient]
        {
            get { return Get(Index(rgb, coefficient)); }
            set { Set(Index(rgb, coefficient), value); }
        }

        static int Index(int rgb, int coefficient)
        {
            if (rgb < 0 || rgb > 2 || coefficient < 0 || coefficient >= Coefficients)
                throw new IndexOutOfRangeException("SphericalHarmonicsL2 index [" + rgb + ", " + coefficient + "] is outside [0..2, 0..8]");
            return rgb * Coefficients + coefficient;
        }

        float Get(int index)
        {
            switch (index)
            {
                case 0: return shr0;
                case 1: return shr1;
                case 2: return shr2;
                case 3: return shr3;
                case 4: return shr4;
                case 5: return shr5;
                case 6: return shr6;
                case 7: return shr7;
                case 8: return shr8;
                case 9: return shg0;
                case 10: return shg1;
                case 11: return shg2;
                case 12: return shg3;
                case 13: return shg4;
                case 14: return shg5;
                case 15: return shg6;
                case 16: return shg7;
                case 17: return shg8;
                case 18: return shb0;
                case 19: return shb1;
                case 20: return shb2;
                case 21: return shb3;
                case 22: return shb4;
                case 23: return shb5;
                case 24: return shb6;
                case 25: return shb7;
                case 26: return shb8;
                default: throw new IndexOutOfRangeException();
            }
        }

        void Set(int index, float value)
        {
            switch (index)
            {
                case 0: shr0 = value; break;
                case 1: shr1 = value; break;
                case 2: shr2 = value; break;
                case 3: shr3 = value; break;
                case 4: shr4 = value; break;
                case 5: shr5 = value; break;
                case 6: shr6 = value; break;
                case 7: shr7 = value; break;
                case 8: shr8 = value; break;
                case 9: shg0 = value; break;
                case 10: shg1 = value; break;
                case 11: shg2 = value; break;
                case 12: shg3 = value; break;
                case 13: shg4 = value; break;
                case 14: shg5 = value; break;
                case 15: shg6 = value; break;
                case 16: shg7 = value; break;
                case 17: shg8 = value; break;
                case 18: shb0 = value; break;
                case 19: shb1 = value; break;
                case 20: shb2 = value; break;
                case 21: shb3 = value; break;
                case 22: shb4 = value; break;
                case 23: shb5 = value; break;
                case 24: shb6 = value; break;
                case 25: shb7 = value; break;
                case 26: shb8 = value; break;
                default: throw new IndexOutOfRangeException();
            }
        }

        /// <summary>Adds uniform incoming radiance (r, g, b) from every direction.</summary>
        public void AddAmbientLight(float r, float g, float b)
        {
            NativeProxy.ShAddAmbient(ref this, r, g, b);
        }

        /// <summary>Adds a directional light travelling along `direction` whose irradiance facing it is (r, g, b).</summary>
        public void AddDirectionalLight(Vector3 direction, float r, float g, float b)
        {
            NativeProxy.ShAddDirectional(ref this, direction, r, g, b);
        }

        /// <summary>Radiance (r, g, b) arriving from unit direction `direction`, as a Vector3.</summary>
        public Vector3 EvaluateRadiance(Vector3 direction)
        {
            return NativeProxy.ShEvalRadiance(ref this, direction);
        }

        /// <summary>Irradiance (r, g, b) on a surface with unit normal `normal`, as a Vector3.</summary>
        public Vector3 EvaluateIrradiance(Vector3 normal)
        {
            return NativeProxy.ShEvalIrradiance(ref this, normal);
        }

        /// <summary>Irradiance on a surface with unit normal `normal` under the options' order and window; bit for bit
        /// EvaluateIrradiance of the SH after ApplyOptions(options).</summary>
        public Vector3 EvaluateIrradiance(Vector3 normal, ShEvalOptions options)
        {
            return NativeProxy.ShEvalIrradiance(ref this, normal, options);
        }

        /// <summary>Rewrites the coefficients so that the plain EvaluateIrradiance is the evaluation the options choose
        /// (apply once per probe, keep the engine's plain L2 evaluation).</summary>
        public void ApplyOptions(ShEvalOptions options)
        {
            NativeProxy.ShApplyOptions(ref this, options);
        }

        /// <summary>The smallest irradiance over all unit normals per channel under the options (exact, not sampled), and
        /// in `normal` the unit normal where the smallest of the three occurs.</summary>
        public Vector3 MinIrradiance(ShEvalOptions options, out Vector3 normal)
        {
            return NativeProxy.ShMinIrradiance(ref this, options, out normal);
        }

        /// <summary>The Sloan window strength ShWindow.NonNegative picks for this SH under `order`.</summary>
        public float NonNegativeWindowStrength(ShOrder order = ShOrder.L2)
        {
            return NativeProxy.ShNonNegativeWindowStrength(ref this, order);
        }

        public bool Equals(SphericalHarmonicsL2 other)
        {
            for (int i = 0; i < Floats; ++i)
                if (Get(i) != other.Get(i)) return false;
            return true;
        }

        public override bool Equals(object other)
        {
            return other is SphericalHarmonicsL2 && Equals((SphericalHarmonicsL2)other);
        }

        public override int GetHashCode()
        {
            int hash = 17;
            for (int i = 0; i < Floats; ++i) hash = hash * 31 + Get(i).GetHashCode();
            return hash;
        }

        public static bool operator ==(SphericalHarmonicsL2 a, SphericalHarmonicsL2 b) { return a.Equals(b); }
        public static bool operator !=(SphericalHarmonicsL2 a, SphericalHarmonicsL2 b) { return !a.Equals(b); }
    }
}
