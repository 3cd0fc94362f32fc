// Vector4: four floats (x, y, z, w), blittable, with the layout of Unity's UnityEngine.Vector4 (occlusion probes'
// four light channels). Inside Unity (UNITY_5_3_OR_NEWER) the binding uses UnityEngine.Vector4 itself instead.
#if !UNITY_5_3_OR_NEWER
using System;
using System.Runtime.InteropServices;

namespace TetProbe
{
    [StructLayout(LayoutKind.Sequential)]
    public struct Vector4 : IEquatable<Vector4>
    {
        public float x;
        public float y;
        public float z;
        public float w;

        public Vector4(float x, float y, float z, float w)
        {
            this.x = x;
            this.y = y;
            this.z = z;
            this.w = w;
        }

        public bool Equals(Vector4 other) { return x == other.x && y == other.y && z == other.z && w == other.w; }
        public override bool Equals(object other) { return other is Vector4 && Equals((Vector4)other); }
        public override int GetHashCode() { return x.GetHashCode() ^ (y.GetHashCode() << 2) ^ (z.GetHashCode() >> 2) ^ (w.GetHashCode() >> 1); }
        public override string ToString() { return "(" + x + ", " + y + ", " + z + ", " + w + ")"; }
    }
}
#endif
