// The version check refuses a library of another major.minor with a clear message, before any other call.
using System;
using TetProbe;

static class VersionTests
{
    public static void Run()
    {
        Func<uint> real = NativeProxy.VersionSource;
        try
        {
            NativeProxy.VersionSource = () => (0u << 16) | (4u << 8) | 2u;
            NativeProxy.ResetVersionCheck();
            Tests.Throws<TetProbeException>(() => ProbeStore.Build(new[] { new Vector3(0, 0, 0) }, null), "0.4.2 library refused by Build",
                e => e.Status == TetProbeStatus.Version && e.Message.Contains("0.4.2") && e.Message.Contains("0.8"));
            Tests.Throws<TetProbeException>(() => ProbeStore.Load(new byte[16]), "refused by Load",
                                            e => e.Status == TetProbeStatus.Version);
            Tests.Throws<TetProbeException>(() => new Scene(), "refused by Scene", e => e.Status == TetProbeStatus.Version);
            var sh = new SphericalHarmonicsL2();
            Tests.Throws<TetProbeException>(() => sh.AddAmbientLight(1, 1, 1), "refused by the SH helpers",
                                            e => e.Status == TetProbeStatus.Version);
            Tests.Throws<TetProbeException>(() => ShadowCasterVolume.TestSphere(new float[0], new Vector3(0, 0, 0), 1),
                                            "refused by the volumes", e => e.Status == TetProbeStatus.Version);
            NativeProxy.VersionSource = () => (1u << 16) | (8u << 8);
            Tests.Throws<TetProbeException>(() => new Scene(), "another major refused", e => e.Status == TetProbeStatus.Version);

            NativeProxy.VersionSource = () => { throw new DllNotFoundException("libtetprobe.so: cannot open shared object file"); };
            Tests.Throws<DllNotFoundException>(() => new Scene(), "a missing library says which plugin to put where",
                                               e => e.Message.Contains("'tetprobe'") && e.InnerException != null);

            // A library named tetprobe without tp_version (an old release or a foreign library) is refused as another release.
            NativeProxy.VersionSource = () => { throw new EntryPointNotFoundException("tp_version"); };
            Tests.Throws<TetProbeException>(() => new Scene(), "a library without tp_version is a plugin of another release",
                                            e => e.Status == TetProbeStatus.Version && e.Message.Contains("tp_version") &&
                                                 e.Message.Contains("same release") && e.InnerException is EntryPointNotFoundException);

            NativeProxy.VersionSource = () => (0u << 16) | (8u << 8) | 9u;
            using (ProbeStore store = ProbeStore.Build(new[] { new Vector3(0, 0, 0) }, null))
                Tests.Check(store.Info.Probes == 1, "another patch of 0.8 is accepted");
        }
        finally
        {
            NativeProxy.VersionSource = real;
            NativeProxy.ResetVersionCheck();
        }
    }
}
