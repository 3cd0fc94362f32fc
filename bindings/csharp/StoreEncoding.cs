// How a store keeps its data (format 6): the SH encoding and layout chosen at build, and the bytes of each
// part of the blob (ProbeStore.Info).
namespace TetProbe
{
    /// <summary>TP_SH_ENCODING_*: how the SH coefficients are stored; queries decode them as they blend.</summary>
    public enum ShEncoding : uint
    {
        /// <summary>27 half floats.</summary>
        Half = 0,
        /// <summary>L0 of each channel as a half, the other coefficients as 8-bit ratios to it over the range a non-negative
        /// radiance reaches.</summary>
        Unorm8 = 1,
        /// <summary>Half floats of bands 0 and 1; band 2 reads as zero.</summary>
        HalfL1 = 2,
        /// <summary>Unorm8 of bands 0 and 1; band 2 reads as zero.</summary>
        Unorm8L1 = 3,
    }

    /// <summary>TP_LAYOUT_*: how a store keeps its cells.</summary>
    public enum StoreLayout : uint
    {
        Fast = 0,
        Compact = 1,
        /// <summary>No cells stored: rebuilt from the positions when loaded.</summary>
        Rebuilt = 2,
    }

    /// <summary>Bytes of each part of a store's blob (tp_store_info.section_bytes).</summary>
    public struct StoreSectionBytes
    {
        public long Header, Positions, Normals, Sh, ProbeSource, InputRemap, Cells, Grid, Occlusion, LeakOffsets, LeakEdges,
                    Padding;

        internal StoreSectionBytes(NativeSectionBytes n)
        {
            Header = (long)n.header;
            Positions = (long)n.positions;
            Normals = (long)n.normals;
            Sh = (long)n.sh;
            ProbeSource = (long)n.probe_source;
            InputRemap = (long)n.input_remap;
            Cells = (long)n.cells;
            Grid = (long)n.grid;
            Occlusion = (long)n.occlusion;
            LeakOffsets = (long)n.leak_offsets;
            LeakEdges = (long)n.leak_edges;
            Padding = (long)n.padding;
        }

        /// <summary>The blob's size: every part added up.</summary>
        public long Total
        {
            get
            {
                return Header + Positions + Normals + Sh + ProbeSource + InputRemap + Cells + Grid + Occlusion + LeakOffsets +
                       LeakEdges + Padding;
            }
        }
    }
}
