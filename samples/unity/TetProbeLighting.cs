// Lights renderers from a tetprobe store the way Unity lights them from its own light probes: each renderer keeps
// its cell hint, every frame one batch query interpolates the SH at every renderer's probe position, and each
// renderer receives its SH through a MaterialPropertyBlock (LightProbeUsage.CustomProvided), converted to Unity's
// SphericalHarmonicsL2 so that the built-in and SRP shaders evaluate it as they evaluate Unity's probes.
#if UNITY_5_3_OR_NEWER
using TetProbe;
using UnityEngine;
using UnityEngine.Rendering;
using ProbeSH = TetProbe.SphericalHarmonicsL2;
using UnitySH = UnityEngine.Rendering.SphericalHarmonicsL2;

[DisallowMultipleComponent]
public class TetProbeLighting : MonoBehaviour
{
    [Tooltip("The store LightProbeBaker wrote (a .bytes asset).")]
    public TextAsset store;

    [Tooltip("Renderers lit by the store; empty = every Renderer on this object and its children.")]
    public Renderer[] renderers;

    ProbeStore probes;
    int[] hints;
    Vector3[] positions;
    ProbeSH[] interpolated;
    readonly UnitySH[] one = new UnitySH[1];
    MaterialPropertyBlock block;

    void OnEnable()
    {
        if (store == null) return;
        if (renderers == null || renderers.Length == 0) renderers = GetComponentsInChildren<Renderer>();
        probes = ProbeStore.Load(store.bytes);
        hints = new int[renderers.Length];
        for (int i = 0; i < hints.Length; ++i) hints[i] = -1;  // no cell yet: the first query starts cold
        positions = new Vector3[renderers.Length];
        interpolated = new ProbeSH[renderers.Length];
        block = new MaterialPropertyBlock();
        foreach (Renderer r in renderers) r.lightProbeUsage = LightProbeUsage.CustomProvided;
    }

    void Update()
    {
        if (probes == null) return;
        for (int i = 0; i < renderers.Length; ++i)
        {
            Renderer r = renderers[i];
            // Where Unity samples its probes for a renderer: the anchor override, else the bounds' centre.
            positions[i] = r.probeAnchor != null ? r.probeAnchor.position : r.bounds.center;
        }
        probes.Interpolate(positions, hints, interpolated);
        for (int i = 0; i < renderers.Length; ++i)
        {
            one[0] = UnitySphericalHarmonics.ToUnity(interpolated[i]);
            renderers[i].GetPropertyBlock(block);
            block.CopySHCoefficientArraysFrom(one);
            renderers[i].SetPropertyBlock(block);
        }
    }

    void OnDisable()
    {
        if (probes != null) probes.Dispose();
        probes = null;
    }
}
#endif
