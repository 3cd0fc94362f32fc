// Vector3: three floats (x, y, z), blittable, with the layout of Unity's UnityEngine.Vector3. Inside Unity
// (UNITY_5_3_OR_NEWER) the binding uses UnityEngine.Vector3 itself instead.
#if !UNITY_5_3_OR_NEWER
using System;
using System.Runtime.InteropServices;

namespace TetProbe
{
    [StructLayout(LayoutKind.Sequential)]
    public struct Vector3 : IEquatable<Vector3>
    {
        public float x;
        public float y;
        public float z;

        public Vector3(float x, float y, float z)
        {
            this.x = x;
            this.y = y;
            this.z = z;
        }

        public bool Equals(Vector3 other) { return x == other.x && y == other.y && z == other.z; }
        public override bool Equals(object other) { return other is Vector3 && Equals((Vector3)other); }
        public override int GetHashCode() { return x.GetHashCode() ^ (y.GetHashCode() << 2) ^ (z.GetHashCode() >> 2); }
        public override string ToString() { return "(" + x + ", " + y + ", " + z + ")"; }
    }
}
#endif
