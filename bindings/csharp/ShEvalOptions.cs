// ShEvalOptions: tp_sh_eval_options as a blittable struct, the SH order and deringing window an evaluation uses.
using System.Runtime.InteropServices;

namespace TetProbe
{
    /// <summary>Which SH bands an evaluation uses (TP_SH_ORDER_*).</summary>
    public enum ShOrder
    {
        /// <summary>All 27 coefficients (the default).</summary>
        L2 = 0,
        /// <summary>Bands 0 and 1 only.</summary>
        L1 = 1,
        /// <summary>L1 plus a zonal L2 term estimated from the L1 data (ZH3, "hallucinated"; see capi/tetprobe.h).</summary>
        ZH3 = 2,
    }

    /// <summary>The deringing window applied after the order (TP_SH_WINDOW_*).</summary>
    public enum ShWindow
    {
        None = 0,
        /// <summary>Sloan's window: band l scaled by 1 / (1 + s (l (l + 1))^2), s = WindowStrength.</summary>
        Sloan = 1,
        /// <summary>The smallest Sloan window that keeps the irradiance non-negative (costly: apply it once per probe).
        /// </summary>
        NonNegative = 2,
    }

    /// <summary>How an SH is evaluated: order, then window. default(ShEvalOptions) is L2 without a window, the plain
    /// evaluation.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ShEvalOptions
    {
        uint structSize;
        uint order;
        uint window;
        /// <summary>s >= 0 and finite; read for ShWindow.Sloan only.</summary>
        public float WindowStrength;

        public ShOrder Order { get { return (ShOrder)order; } set { order = (uint)value; } }
        public ShWindow Window { get { return (ShWindow)window; } set { window = (uint)value; } }

        /// <summary>The library's defaults (tp_sh_eval_options_init) with the given order and window.</summary>
        public static ShEvalOptions Create(ShOrder order = ShOrder.L2, ShWindow window = ShWindow.None, float windowStrength = 0)
        {
            NativeProxy.EnsureVersion();
            ShEvalOptions options;
            NativeProxy.Check(NativeMethods.tp_sh_eval_options_init(out options));
            options.Order = order;
            options.Window = window;
            options.WindowStrength = windowStrength;
            return options;
        }

        internal ShEvalOptions Sized()
        {
            ShEvalOptions copy = this;
            copy.structSize = (uint)Marshal.SizeOf(typeof(ShEvalOptions));
            return copy;
        }
    }
}
