// Material: tp_material as a blittable struct (an array of them crosses the C ABI as it is).
using System;
using System.Runtime.InteropServices;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    /// <summary>A mesh's surface for the bake: diffuse albedo (each in [0, 1]), emitted radiance (&gt;= 0), sidedness.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Material
    {
        uint structSize;
        /// <summary>Diffuse reflectance per channel, each in [0, 1].</summary>
        public Vector3 Albedo;
        /// <summary>Emitted radiance per channel, &gt;= 0.</summary>
        public Vector3 Emission;
        int twoSided;

        /// <summary>True: both faces reflect and emit.</summary>
        public bool TwoSided
        {
            get { return twoSided != 0; }
            set { twoSided = value ? 1 : 0; }
        }

        /// <summary>The library's default material (grey, one-sided, not emissive).</summary>
        public static Material Default
        {
            get
            {
                NativeProxy.EnsureVersion();
                Material material;
                NativeProxy.Check(NativeMethods.tp_material_init(out material));
                return material;
            }
        }

        /// <summary>A diffuse material of albedo (r, g, b) emitting `emission` (default none), two-sided by default.</summary>
        public static Material Diffuse(Vector3 albedo, Vector3 emission = default(Vector3), bool twoSided = true)
        {
            Material material = Default;
            material.Albedo = albedo;
            material.Emission = emission;
            material.TwoSided = twoSided;
            return material;
        }

        /// <summary>The struct as it crosses the C ABI, struct_size set even on a default(Material).</summary>
        internal Material Sized()
        {
            Material copy = this;
            copy.structSize = (uint)Marshal.SizeOf(typeof(Material));
            return copy;
        }
    }
}
