// samples/unity and the Unity conversions, compiled against the stand-ins in unity_stubs/ and run with the real
// library: a light added on either side evaluates to the same irradiance on the other (the stubs' Unity
// SphericalHarmonicsL2 follows Unity's published formulas, ShadeSH9 is UnityCG.cginc's) and the conversion of a
// directional light gives coefficients derived by hand from those formulas; then the editor script bakes
// a small stub scene and TetProbeLighting lights a renderer from the store it wrote.
using System;
using System.IO;
using System.Reflection;
using TetProbe;
using UnityEngine;
using ProbeSH = TetProbe.SphericalHarmonicsL2;
using UnitySH = UnityEngine.Rendering.SphericalHarmonicsL2;

static class UnityTests
{
    static int passed, failed;

    static void Check(bool condition, string what)
    {
        if (condition) { ++passed; return; }
        ++failed;
        Console.WriteLine("FAIL: " + what);
    }

    static Vector3[] Normals(int n, System.Random random)
    {
        var normals = new Vector3[n];
        for (int i = 0; i < n; ++i)
        {
            Vector3 v;
            do v = new Vector3((float)random.NextDouble() * 2 - 1, (float)random.NextDouble() * 2 - 1, (float)random.NextDouble() * 2 - 1);
            while (v.magnitude < 0.1f || v.magnitude > 1);
            normals[i] = v.normalized;
        }
        normals[0] = new Vector3(0, 1, 0);
        normals[1] = new Vector3(0, 0, -1);
        return normals;
    }

    /// <summary>Largest |pi * ShadeSH9(constants, n) - E(n)| over the normals, relative to the largest |E|.</summary>
    static double ShaderVersusIrradiance(Vector4[] constants, ProbeSH sh, Vector3[] normals)
    {
        double worst = 0, scale = 1e-6;
        foreach (Vector3 n in normals)
        {
            Vector3 shader = UnityCG.ShadeSH9(constants, n);
            Vector3 irradiance = sh.EvaluateIrradiance(n);
            scale = Math.Max(scale, Math.Max(Math.Abs(irradiance.x), Math.Max(Math.Abs(irradiance.y), Math.Abs(irradiance.z))));
            worst = Math.Max(worst, Math.Abs(Math.PI * shader.x - irradiance.x));
            worst = Math.Max(worst, Math.Abs(Math.PI * shader.y - irradiance.y));
            worst = Math.Max(worst, Math.Abs(Math.PI * shader.z - irradiance.z));
        }
        return worst / scale;
    }

    static double MaxDifference(ProbeSH a, ProbeSH b)
    {
        double worst = 0, scale = 1e-6;
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i)
            {
                worst = Math.Max(worst, Math.Abs(a[c, i] - b[c, i]));
                scale = Math.Max(scale, Math.Abs(b[c, i]));
            }
        return worst / scale;
    }

    static Vector4[] Constants(ProbeSH sh)
    {
        var constants = new Vector4[7];
        UnitySphericalHarmonics.ToShaderConstants(sh, constants);
        return constants;
    }

    static Vector4[] UnityPacked(UnitySH unity)
    {
        var block = new MaterialPropertyBlock();
        block.CopySHCoefficientArraysFrom(new[] { unity });
        string[] names = { "unity_SHAr", "unity_SHAg", "unity_SHAb", "unity_SHBr", "unity_SHBg", "unity_SHBb", "unity_SHC" };
        var constants = new Vector4[7];
        for (int k = 0; k < 7; ++k) constants[k] = block.GetVectorArray(names[k])[0];
        return constants;
    }

    static void Conversions()
    {
        var random = new System.Random(3);
        Vector3[] normals = Normals(300, random);

        // The stubs themselves, against what Unity documents: a flat ambient colour C renders as C, and
        // AddDirectionalLight(d, C, I) facing d renders as 2 I C (Sloan's normalisation, Unity's doubling).
        var ambientUnity = new UnitySH();
        ambientUnity.AddAmbientLight(new Color(0.2f, 0.5f, 1.0f));
        Vector3 flat = UnityCG.ShadeSH9(UnityPacked(ambientUnity), new Vector3(0.6f, 0, 0.8f));
        Check(Math.Abs(flat.x - 0.2f) < 1e-6 && Math.Abs(flat.y - 0.5f) < 1e-6 && Math.Abs(flat.z - 1.0f) < 1e-6,
              "stub: Unity's ambient C renders as C (" + flat + ")");
        var towards = new Vector3(0.48f, 0.6f, 0.64f);
        var sunUnity = new UnitySH();
        sunUnity.AddDirectionalLight(towards, new Color(1, 0.5f, 0.25f), 1.5f);
        Vector3 facing = UnityCG.ShadeSH9(UnityPacked(sunUnity), towards);
        Check(Math.Abs(facing.x - 3) < 1e-5 && Math.Abs(facing.y - 1.5) < 1e-5 && Math.Abs(facing.z - 0.75) < 1e-5,
              "stub: Unity's directional light facing it renders as 2 I C (" + facing + ")");

        // Golden coefficients, derived by hand from Unity's published formulas and not from the stubs or the conversion
        // (no capture from a real editor is available here). AddDirectionalLight(Vector3.up, Color.white, 1): Unity's C#
        // doubles the intensity (color * (2 * intensity)), so the radiance delta from +y has weight 2; the native part
        // projects it as Sloan's SHEvalDirectionalLight9: basis Y_i(up) (Condon-Shortley: Y00 = 1/(2 sqrt(pi)),
        // Y1-1 = -sqrt(3)/(2 sqrt(pi)) y, Y20 = sqrt(5)/(4 sqrt(pi)) (3z^2 - 1), Y22 = sqrt(15)/(4 sqrt(pi)) (x^2 - y^2),
        // the rest 0 at up) times 16pi/17, and stores each times the reconstruction constant of appendix A10 (1/(2 sqrt(pi)),
        // -sqrt(3)/(3 sqrt(pi)), sqrt(5)/(16 sqrt(pi)), sqrt(15)/(16 sqrt(pi))). In Unity's order L00, L1-1, L10, L11, L2-2,
        // L2-1, L20, L21, L22: u0 = 2 (16pi/17) (1/(2 sqrt(pi))) (1/(2 sqrt(pi))) = 8/17; u1 = 2 (16pi/17) (-sqrt(3)/(2 sqrt(pi)))
        // (-sqrt(3)/(3 sqrt(pi))) = 16/17; u6 = 2 (16pi/17) (-sqrt(5)/(4 sqrt(pi))) (sqrt(5)/(16 sqrt(pi))) = -5/34;
        // u8 = 2 (16pi/17) (-sqrt(15)/(4 sqrt(pi))) (sqrt(15)/(16 sqrt(pi))) = -15/34; the others 0. Check: ShadeSH9 facing up
        // is u0 + u1 - u6 - u8 = 2 = 2 I C, Unity's documented doubling.
        float[] golden = { 8f / 17, 16f / 17, 0, 0, 0, 0, -5f / 34, 0, -15f / 34 };
        var goldenOurs = new ProbeSH();
        float weightUp = (float)(2 * 16 * Math.PI / 17);
        goldenOurs.AddDirectionalLight(new Vector3(0, -1, 0), weightUp, weightUp, weightUp);  // travelling down: from up
        UnitySH goldenConverted = UnitySphericalHarmonics.ToUnity(goldenOurs);
        var goldenStub = new UnitySH();
        goldenStub.AddDirectionalLight(Vector3.up, Color.white, 1);
        double goldenWorst = 0, stubWorst = 0;
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i)
            {
                goldenWorst = Math.Max(goldenWorst, Math.Abs(goldenConverted[c, i] - golden[i]));
                stubWorst = Math.Max(stubWorst, Math.Abs(goldenStub[c, i] - golden[i]));
            }
        Check(goldenWorst < 1e-6, "ToUnity(our directional light from up, 2 * 16pi/17) = the hand-derived coefficients of Unity's " +
              "AddDirectionalLight(up, white, 1) (8/17, 16/17, -5/34, -15/34; worst " + goldenWorst + ")");
        Check(stubWorst < 1e-6, "the stub's AddDirectionalLight gives the hand-derived coefficients (worst " + stubWorst + ")");

        // Unity -> ours: the same light, coefficient by coefficient and by irradiance.
        var ambientOurs = new ProbeSH();
        ambientOurs.AddAmbientLight(0.2f, 0.5f, 1.0f);
        ProbeSH ambientConverted = UnitySphericalHarmonics.FromUnity(ambientUnity);
        Check(MaxDifference(ambientConverted, ambientOurs) < 1e-6, "Unity AddAmbientLight converts to our AddAmbientLight");
        Check(ShaderVersusIrradiance(UnityPacked(ambientUnity), ambientConverted, normals) < 1e-5,
              "Unity ambient: pi ShadeSH9 = our irradiance of the converted SH");
        double weight = 2 * 1.5 * 16 * Math.PI / 17;
        var sunOurs = new ProbeSH();
        sunOurs.AddDirectionalLight(-towards, (float)weight, (float)(weight * 0.5), (float)(weight * 0.25));
        ProbeSH sunConverted = UnitySphericalHarmonics.FromUnity(sunUnity);
        Check(MaxDifference(sunConverted, sunOurs) < 1e-5, "Unity AddDirectionalLight(d, C, I) converts to our " +
              "AddDirectionalLight(-d, 2 I C 16pi/17) (" + MaxDifference(sunConverted, sunOurs) + ")");
        double unityWorst = ShaderVersusIrradiance(UnityPacked(sunUnity), sunConverted, normals);
        Check(unityWorst < 1e-5, "Unity directional: pi ShadeSH9 = our irradiance of the converted SH (" + unityWorst + ")");

        // Ours -> Unity: any SH (lights and random coefficients) evaluates the same in ShadeSH9 as in the library.
        for (int trial = 0; trial < 20; ++trial)
        {
            var ours = new ProbeSH();
            ours.AddAmbientLight((float)random.NextDouble(), (float)random.NextDouble(), (float)random.NextDouble());
            ours.AddDirectionalLight(normals[trial + 2], 2, 1, 0.5f);
            for (int c = 0; c < 3; ++c)
                for (int i = 0; i < 9; ++i) ours[c, i] += (float)(random.NextDouble() - 0.5);
            Vector4[] constants = Constants(ours);
            double worst = ShaderVersusIrradiance(constants, ours, normals);
            Vector4[] viaUnity = UnityPacked(UnitySphericalHarmonics.ToUnity(ours));
            bool samePacking = true;
            for (int k = 0; k < 7; ++k)
                samePacking &= constants[k].x == viaUnity[k].x && constants[k].y == viaUnity[k].y &&
                               constants[k].z == viaUnity[k].z && constants[k].w == viaUnity[k].w;
            double roundTrip = MaxDifference(UnitySphericalHarmonics.FromUnity(UnitySphericalHarmonics.ToUnity(ours)), ours);
            if (trial == 0 || worst >= 1e-5 || !samePacking || roundTrip >= 1e-6)
                Check(worst < 1e-5 && samePacking && roundTrip < 1e-6, "ours -> constants: pi ShadeSH9 = tp_sh_eval_irradiance over " +
                      normals.Length + " normals (worst " + worst + "), the same constants as Unity's packing, round trip " + roundTrip);
        }
        try
        {
            UnitySphericalHarmonics.ToShaderConstants(new ProbeSH(), new Vector4[6]);
            Check(false, "6 constants refused");
        }
        catch (ArgumentException) { Check(true, "6 constants refused"); }
    }

    static void BakeAndLight(string scratch)
    {
        UnityEngine.Object.ResetStubScene();
        var group = new GameObject("probes").AddComponent<LightProbeGroup>();
        group.transform.position = new Vector3(10, 0, 0);
        var local = new System.Collections.Generic.List<Vector3>();
        for (int x = 0; x < 3; ++x)
            for (int y = 0; y < 3; ++y)
                for (int z = 0; z < 3; ++z) local.Add(new Vector3(x * 2, 0.5f + y, z * 2));
        group.probePositions = local.ToArray();

        var floor = new GameObject("floor");
        var mesh = new Mesh();
        mesh.vertices = new[] { new Vector3(-5, 0, -5), new Vector3(20, 0, -5), new Vector3(20, 0, 20), new Vector3(-5, 0, 20) };
        mesh.triangles = new[] { 0, 2, 1, 0, 3, 2 };
        floor.AddComponent<MeshFilter>().sharedMesh = mesh;
        var floorMaterial = new UnityEngine.Material();
        floorMaterial.color = new Color(0.5f, 0.5f, 0.5f);
        floor.AddComponent<MeshRenderer>().sharedMaterial = floorMaterial;
        UnityEditor.GameObjectUtility.SetStaticEditorFlags(floor, UnityEditor.StaticEditorFlags.ContributeGI);

        // A dynamic object over the probes (batching-static only): Unity's bake ignores it, so must ours (else it shades
        // every probe from the sun).
        var roof = new GameObject("character roof");
        var roofMesh = new Mesh();
        roofMesh.vertices = new[] { new Vector3(-5, 6, -5), new Vector3(20, 6, -5), new Vector3(20, 6, 20), new Vector3(-5, 6, 20) };
        roofMesh.triangles = new[] { 0, 1, 2, 0, 2, 3 };
        roof.AddComponent<MeshFilter>().sharedMesh = roofMesh;
        roof.AddComponent<MeshRenderer>().sharedMaterial = floorMaterial;
        UnityEditor.GameObjectUtility.SetStaticEditorFlags(roof, UnityEditor.StaticEditorFlags.BatchingStatic);

        var sun = new GameObject("sun").AddComponent<UnityEngine.Light>();
        sun.type = UnityEngine.LightType.Directional;
        sun.transform.forward = new Vector3(0, -1, 0);
        sun.intensity = 1;
        sun.shadows = LightShadows.Soft;
        RenderSettings.ambientProbe = new UnitySH();
        RenderSettings.ambientProbe.AddAmbientLight(new Color(0.1f, 0.1f, 0.1f));

        // A Mixed light (its direct light is drawn in real time: only its bounce is baked) and a Realtime one (not baked).
        var mixed = new GameObject("mixed lamp").AddComponent<UnityEngine.Light>();
        mixed.transform.position = new Vector3(12, 3, 2);
        mixed.lightmapBakeType = LightmapBakeType.Mixed;
        var realtime = new GameObject("realtime lamp").AddComponent<UnityEngine.Light>();
        realtime.transform.position = new Vector3(12, 3, 2);
        realtime.lightmapBakeType = LightmapBakeType.Realtime;

        Vector3[] positions = LightProbeBaker.ProbePositions();
        using (TetProbe.Scene converted = LightProbeBaker.FromOpenScene())
        {
            EffectsPlan seen = Baker.Plan(converted, positions);
            Check(seen.Meshes == 1, "baker: only the ContributeGI mesh is baked, not the dynamic one (" + seen.Meshes + " meshes)");
            Check(seen.Lights == 2 && seen.RealtimeLights == 1, "baker: the Baked sun and the Mixed lamp (bounce only), not the " +
                  "Realtime lamp (" + seen.Lights + " lights, " + seen.RealtimeLights + " realtime)");
        }
        Check(positions.Length == 27 && positions[0].Equals(new Vector3(10, 0.5f, 0)), "baker: LightProbeGroup probes in world space");
        string asset = Path.Combine(scratch, "level_probes.bytes");
        string plan = LightProbeBaker.Bake(asset, new BakeOptions { Rays = 64, Bounces = 1 });
        Check(File.Exists(asset) && UnityEditor.AssetDatabase.Imported.Contains(asset), "baker: wrote and imported " + asset);
        Check(plan.Contains("direct: 1") && UnityEditor.EditorUtility.Shown.Count > 0, "baker: plan '" + plan + "', progress shown");

        UnityEditor.EditorUtility.CancelAt = 0.0f;
        byte[] before = File.ReadAllBytes(asset);
        try
        {
            LightProbeBaker.Bake(asset, new BakeOptions { Rays = 64, Bounces = 1 });
            Check(false, "baker: Cancel in the progress bar stops the bake");
        }
        catch (OperationCanceledException)
        {
            byte[] after = File.ReadAllBytes(asset);
            bool unchanged = after.Length == before.Length;
            for (int i = 0; unchanged && i < after.Length; ++i) unchanged = after[i] == before[i];
            Check(unchanged, "baker: Cancel stops the bake and leaves the asset as it was");
        }
        UnityEditor.EditorUtility.CancelAt = float.PositiveInfinity;

        // TetProbeLighting on a renderer in the probes' cloud: its property block holds what the store interpolates.
        var lit = new GameObject("character");
        var renderer = lit.AddComponent<MeshRenderer>();
        renderer.bounds = new Bounds { center = new Vector3(11.3f, 1.7f, 2.2f) };
        var lighting = lit.AddComponent<TetProbeLighting>();
        lighting.store = new TextAsset(File.ReadAllBytes(asset));
        Invoke(lighting, "OnEnable");
        Invoke(lighting, "Update");
        Check(renderer.lightProbeUsage == UnityEngine.Rendering.LightProbeUsage.CustomProvided, "lighting: CustomProvided probes");
        var block = new MaterialPropertyBlock();
        renderer.GetPropertyBlock(block);
        var pushed = new Vector4[7];
        string[] names = { "unity_SHAr", "unity_SHAg", "unity_SHAb", "unity_SHBr", "unity_SHBg", "unity_SHBb", "unity_SHC" };
        for (int k = 0; k < 7; ++k) pushed[k] = block.GetVectorArray(names[k])[0];
        ProbeSH expected;
        using (ProbeStore store = ProbeStore.Load(asset))
        {
            int hint = -1;
            store.Interpolate(renderer.bounds.center, ref hint, out expected);
        }
        double worst = ShaderVersusIrradiance(pushed, expected, Normals(50, new System.Random(4)));
        Check(worst < 1e-5, "lighting: the renderer's constants evaluate to the interpolated irradiance (" + worst + ")");
        Vector3 up = UnityCG.ShadeSH9(pushed, new Vector3(0, 1, 0)), down = UnityCG.ShadeSH9(pushed, new Vector3(0, -1, 0));
        Check(up.x > 0.9 && up.x > 3 * down.x && down.x > 0.05, "lighting: sunlit from above (" + up.x + "), floor and sky below (" +
              down.x + ")");
        renderer.bounds = new Bounds { center = new Vector3(12.5f, 2.1f, 1.1f) };
        Invoke(lighting, "Update");
        renderer.GetPropertyBlock(block);
        Check(block.GetVectorArray("unity_SHAr")[0].w != pushed[0].w || block.GetVectorArray("unity_SHAr")[0].y != pushed[0].y,
              "lighting: a moved renderer gets new SH the next frame");
        Invoke(lighting, "OnDisable");
        renderer.GetPropertyBlock(block);
        Check(renderer.lightProbeUsage == UnityEngine.Rendering.LightProbeUsage.BlendProbes &&
              block.GetVectorArray("unity_SHAr") == null, "lighting: disabled, the renderer gets back its probe usage and no SH of ours");

        // Re-enabled and disabled again: the usage it had before the first enable, not CustomProvided, comes back.
        renderer.lightProbeUsage = UnityEngine.Rendering.LightProbeUsage.Off;
        Invoke(lighting, "OnEnable");
        Invoke(lighting, "Update");
        Invoke(lighting, "OnDisable");
        Check(renderer.lightProbeUsage == UnityEngine.Rendering.LightProbeUsage.Off, "lighting: each renderer's own usage is restored");
        ProxyVolume(asset);
    }

    /// <summary>TetProbeProxyVolume: the renderer's Light Probe Proxy Volume texture holds, at each grid point's texel, the
    /// L0 + L1 constants of what the store interpolates there, and the unity_ProbeVolume* parameters map each point to
    /// its texel's centre.</summary>
    static void ProxyVolume(string asset)
    {
        var big = new GameObject("big");
        var renderer = big.AddComponent<MeshRenderer>();
        renderer.bounds = new Bounds { center = new Vector3(11.5f, 1.5f, 2.0f), size = new Vector3(3, 2, 3.5f) };
        var proxy = big.AddComponent<TetProbeProxyVolume>();
        proxy.store = new TextAsset(File.ReadAllBytes(asset));
        proxy.resolutionX = 4;
        proxy.resolutionY = 3;
        proxy.resolutionZ = 5;
        proxy.halfFloat = false;
        Invoke(proxy, "OnEnable");
        Invoke(proxy, "Update");
        var block = new MaterialPropertyBlock();
        renderer.GetPropertyBlock(block);
        var texture = block.GetTexture("unity_ProbeVolumeSH") as Texture3D;
        Check(texture != null && texture.width == 16 && texture.height == 3 && texture.depth == 5 &&
              texture.format == TextureFormat.RGBAFloat && texture.Applied == 1, "proxy volume: a 16 x 3 x 5 RGBAFloat texture");
        if (texture == null) return;
        var texels = (float[])texture.PixelData;
        Vector4 parameters = block.GetVector("unity_ProbeVolumeParams"), min = block.GetVector("unity_ProbeVolumeMin"),
                sizeInv = block.GetVector("unity_ProbeVolumeSizeInv");
        Check(parameters.x == 1 && parameters.y == 0 && Math.Abs(parameters.z - 1.0 / 16) < 1e-9, "proxy volume: parameters " + parameters);
        double worst = 0, worstCoordinate = 0;
        bool occlusion = true;
        Vector3[] normals = Normals(20, new System.Random(9));
        using (ProbeStore store = ProbeStore.Load(asset))
        {
            float[] cell = { 3f / 4, 2f / 3, 3.5f / 5 };
            for (int z = 0; z < 5; ++z)
                for (int y = 0; y < 3; ++y)
                    for (int x = 0; x < 4; ++x)
                    {
                        // The grid point at the centre of cell (x, y, z) of the bounds, and its texture coordinate.
                        var point = new Vector3(10.0f + (x + 0.5f) * cell[0], 0.5f + (y + 0.5f) * cell[1], 0.25f + (z + 0.5f) * cell[2]);
                        worstCoordinate = Math.Max(worstCoordinate, Math.Abs((point.x - min.x) * sizeInv.x - (x + 0.5) / 4));
                        worstCoordinate = Math.Max(worstCoordinate, Math.Abs((point.y - min.y) * sizeInv.y - (y + 0.5) / 3));
                        worstCoordinate = Math.Max(worstCoordinate, Math.Abs((point.z - min.z) * sizeInv.z - (z + 0.5) / 5));
                        int hint = -1;
                        ProbeSH sh;
                        store.Interpolate(point, ref hint, out sh);
                        for (int c = 0; c < 3; ++c)
                            for (int i = 4; i < 9; ++i) sh[c, i] = 0;  // the volume holds bands 0 and 1
                        var constants = new Vector4[7];
                        for (int k = 0; k < 3; ++k)
                        {
                            int at = 4 * (((z * 3 + y) * 16) + k * 4 + x);
                            constants[k] = new Vector4(texels[at], texels[at + 1], texels[at + 2], texels[at + 3]);
                        }
                        constants[6] = new Vector4(0, 0, 0, 1);
                        worst = Math.Max(worst, ShaderVersusIrradiance(constants, sh, normals));
                        int o = 4 * (((z * 3 + y) * 16) + 12 + x);
                        occlusion &= texels[o] == 1 && texels[o + 1] == 1 && texels[o + 2] == 1 && texels[o + 3] == 1;
                    }
        }
        Check(worst < 1e-4, "proxy volume: each texel evaluates to the L1 irradiance interpolated at its point (" + worst + ")");
        Check(worstCoordinate < 1e-5, "proxy volume: min and size map each point to its texel's centre (" + worstCoordinate + ")");
        Check(occlusion, "proxy volume: the occlusion block is fully visible");
        Invoke(proxy, "OnDisable");
        renderer.GetPropertyBlock(block);
        Check(block.GetTexture("unity_ProbeVolumeSH") == null, "proxy volume: disabled, the renderer's block is cleared");

        proxy.halfFloat = true;
        Invoke(proxy, "OnEnable");
        Invoke(proxy, "Update");
        Check(proxy.Volume.format == TextureFormat.RGBAHalf && proxy.Volume.PixelData is ushort[] &&
              ((ushort[])proxy.Volume.PixelData)[4 * 12] == 0x3C00, "proxy volume: half floats (occlusion 1.0 = 0x3C00)");
        Invoke(proxy, "OnDisable");
    }

    /// <summary>The editor script's light conversion: which lights Unity's probes hold, and Unity's colour linearisation.
    /// </summary>
    static void LightConversion()
    {
        UnityEngine.Object.ResetStubScene();
        var light = new GameObject("lamp").AddComponent<UnityEngine.Light>();
        light.color = new Color(0.5f, 0.25f, 1);
        light.intensity = 2;
        bool linearIntensity = UnityEngine.Rendering.GraphicsSettings.lightsUseLinearIntensity;
        try
        {
            light.lightmapBakeType = LightmapBakeType.Baked;
            TetProbe.Light? baked = LightProbeBaker.ProbeLightOf(light);
            light.lightmapBakeType = LightmapBakeType.Mixed;
            TetProbe.Light? mixed = LightProbeBaker.ProbeLightOf(light);
            light.lightmapBakeType = LightmapBakeType.Realtime;
            TetProbe.Light? realtime = LightProbeBaker.ProbeLightOf(light);
            Check(baked.HasValue && baked.Value.Mode == LightMode.Baked, "Baked light: direct and bounce baked");
            Check(mixed.HasValue && mixed.Value.Mode == LightMode.Realtime, "Mixed light: bounce only (probes hold no direct light)");
            Check(!realtime.HasValue, "Realtime light: not baked (Unity's baked GI ignores it)");
            light.lightmapBakeType = LightmapBakeType.Baked;

            // Gamma intensity (the built-in default): (0.5, 0.25, 1) * 2 = (1, 0.5, 2) linearised together, times pi.
            // sRGB to linear of 0.5 is ((0.5 + 0.055) / 1.055)^2.4, of 1 is 1, of 2 is ((2 + 0.055) / 1.055)^2.4.
            UnityEngine.Rendering.GraphicsSettings.lightsUseLinearIntensity = false;
            TetProbe.Light gamma = LightProbeBaker.ProbeLightOf(light).Value;
            double[] expectGamma = { Math.PI, Math.PI * Math.Pow(0.555 / 1.055, 2.4), Math.PI * Math.Pow(2.055 / 1.055, 2.4) };
            // Linear intensity: the linear colour times 2 pi.
            UnityEngine.Rendering.GraphicsSettings.lightsUseLinearIntensity = true;
            TetProbe.Light linear = LightProbeBaker.ProbeLightOf(light).Value;
            double[] expectLinear = { 2 * Math.PI * Math.Pow(0.555 / 1.055, 2.4), 2 * Math.PI * Math.Pow(0.305 / 1.055, 2.4), 2 * Math.PI };
            double gammaWorst = 0, linearWorst = 0;
            float[] gammaRgb = { gamma.Color.x, gamma.Color.y, gamma.Color.z }, linearRgb = { linear.Color.x, linear.Color.y, linear.Color.z };
            for (int c = 0; c < 3; ++c)
            {
                gammaWorst = Math.Max(gammaWorst, Math.Abs(gammaRgb[c] * gamma.Intensity / expectGamma[c] - 1));
                linearWorst = Math.Max(linearWorst, Math.Abs(linearRgb[c] * linear.Intensity / expectLinear[c] - 1));
            }
            Check(gammaWorst < 1e-6, "lightsUseLinearIntensity off: (colour * intensity).linear, times pi (worst " + gammaWorst + ")");
            Check(linearWorst < 1e-6, "lightsUseLinearIntensity on: colour.linear * intensity, times pi (worst " + linearWorst + ")");
        }
        finally
        {
            UnityEngine.Rendering.GraphicsSettings.lightsUseLinearIntensity = linearIntensity;
        }
    }

    static void Invoke(object target, string method)
    {
        target.GetType().GetMethod(method, BindingFlags.Instance | BindingFlags.NonPublic | BindingFlags.Public).Invoke(target, null);
    }

    static int Main(string[] args)
    {
        string scratch = args.Length > 0 ? args[0] : Path.GetTempPath();
        Directory.CreateDirectory(scratch);
        foreach (Action test in new Action[] { Conversions, LightConversion, () => BakeAndLight(scratch) })
        {
            try
            {
                test();
            }
            catch (Exception e)
            {
                ++failed;
                Console.WriteLine("FAIL: unexpected " + e.GetType().Name + ": " + e.Message + "\n" + e.StackTrace);
            }
        }
        Console.WriteLine(passed + " passed, " + failed + " failed");
        return failed == 0 ? 0 : 1;
    }
}
