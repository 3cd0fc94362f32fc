// Prints NativeMethods.Library and exits 0 when it is the expected plugin name (run_unity.sh compiles one per target).
using System;

static class LibraryName
{
    static int Main(string[] args)
    {
        string name = TetProbe.NativeMethods.Library;
        bool ok = name == args[0];
        Console.WriteLine((ok ? "" : "FAIL: ") + "plugin name '" + name + "', expected '" + args[0] + "'");
        return ok ? 0 : 1;
    }
}
