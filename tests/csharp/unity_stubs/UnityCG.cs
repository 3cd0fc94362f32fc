// The built-in shaders' ShadeSH9 (UnityCG.cginc) on the CPU: SHEvalLinearL0L1 + SHEvalLinearL2 over the seven
// constants unity_SHAr, unity_SHAg, unity_SHAb, unity_SHBr, unity_SHBg, unity_SHBb, unity_SHC (linear colour space).
using UnityEngine;

public static class UnityCG
{
    static float Dot(Vector4 a, Vector4 b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }

    public static Vector3 ShadeSH9(Vector4[] sh, Vector3 normal)
    {
        var n = new Vector4(normal.x, normal.y, normal.z, 1);
        // SHEvalLinearL0L1: dot(unity_SHAx, float4(n, 1)).
        float r = Dot(sh[0], n), g = Dot(sh[1], n), b = Dot(sh[2], n);
        // SHEvalLinearL2: vB = n.xyzz * n.yzzx, dot with unity_SHBx; vC = x^2 - y^2 times unity_SHC.rgb.
        var vB = new Vector4(n.x * n.y, n.y * n.z, n.z * n.z, n.z * n.x);
        float vC = n.x * n.x - n.y * n.y;
        r += Dot(sh[3], vB) + sh[6].x * vC;
        g += Dot(sh[4], vB) + sh[6].y * vC;
        b += Dot(sh[5], vB) + sh[6].z * vC;
        return new Vector3(r, g, b);
    }
}
