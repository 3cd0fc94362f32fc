// Shadow caster volumes: cull an engine's potential shadow casters of a light into a convex region.
using System;
#if UNITY_5_3_OR_NEWER
using Vector3 = UnityEngine.Vector3;
#endif

namespace TetProbe
{
    /// <summary>A light for ShadowCasterVolume.Build.</summary>
    public enum ShadowLight
    {
        /// <summary>light vector = the direction the light travels</summary>
        Directional = 0,
        /// <summary>light vector = the light's position</summary>
        Point = 1,
    }

    public static class ShadowCasterVolume
    {
        /// <summary>Inward planes (nx, ny, nz, d per plane; n.x + d &gt;= 0 inside) of everything that can cast a
        /// shadow from the light into the bounded convex polyhedron `planes` (same form).</summary>
        public static float[] Build(float[] planes, ShadowLight light, Vector3 lightVector)
        {
            CheckPlanes(planes);
            return NativeProxy.ShadowCasterVolume(planes, (uint)light, lightVector);
        }

        /// <summary>False only when the box certainly lies outside the volume.</summary>
        public static bool TestAabb(float[] planes, Vector3 min, Vector3 max)
        {
            CheckPlanes(planes);
            return NativeProxy.VolumeTestAabb(planes, min, max);
        }

        /// <summary>False only when the sphere certainly lies outside the volume.</summary>
        public static bool TestSphere(float[] planes, Vector3 center, float radius)
        {
            CheckPlanes(planes);
            return NativeProxy.VolumeTestSphere(planes, center, radius);
        }

        static void CheckPlanes(float[] planes)
        {
            if (planes == null) throw new ArgumentNullException("planes");
            if (planes.Length % 4 != 0) throw new ArgumentException("planes holds 4 floats per plane", "planes");
        }
    }
}
