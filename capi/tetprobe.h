/*
 * tetprobe — light probes interpolated over a tetrahedral tessellation (C ABI).
 *
 * The method is Unity's (R. Cupisz, "Light probe interpolation using tetrahedral tessellations",
 * GDC 2012): probes are tetrahedralized (Delaunay), a query walks from the cell it was in last
 * frame, and the four probes of its cell are blended with barycentric weights. Outside the probes'
 * convex hull, open "outer cells" swept along the hull's vertex normals extrapolate smoothly.
 *
 * Rules of this interface
 * - Every function returns a tp_status (TP_OK = 0). On failure tp_last_error() returns a message
 *   for the calling thread; no exception, abort or exit ever leaves the library.
 * - Handles (tp_store, tp_scene) are opaque, created and released by the library. Buffers are
 *   owned by the caller and come with explicit counts and strides in bytes (0 = tightly packed).
 *   Neither a buffer nor its stride needs any alignment. A count or stride whose buffer would not fit
 *   in the address space (count x stride beyond PTRDIFF_MAX) is refused with
 *   TP_ERROR_INVALID_ARGUMENT naming the parameter, before anything is read or written.
 * - A tp_store is immutable: any number of threads may query one store at once. The cell hint of a
 *   moving object is owned by the caller (int32_t, -1 = none) and updated by each query.
 * - Structs that may grow start with a struct_size field: set it to sizeof(the struct), or call the
 *   matching *_init function, which also fills the defaults.
 * - Positions are float32 in the caller's world units. Queries never allocate and never fail on a
 *   valid store with valid arguments. On a forged or corrupt blob that passes validation (which
 *   cannot prove its tessellation Delaunay) a query stops after a bounded number of cells, about as
 *   many as the store has, and fails with TP_ERROR_INVALID_BLOB.
 *
 * Spherical harmonics contract (shared by every function that takes or returns SH)
 * - Real, orthonormal SH, 3 bands (L2): 9 coefficients per colour channel, 27 floats per probe,
 *   channel-major [r0..r8, g0..g8, b0..b8] (the layout of Unity's SphericalHarmonicsL2).
 * - Coefficient order: L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22, with
 *   Y00 = 0.282095, Y1-1 = 0.488603 y, Y10 = 0.488603 z, Y11 = 0.488603 x,
 *   Y2-2 = 1.092548 xy, Y2-1 = 1.092548 yz, Y20 = 0.315392 (3z^2 - 1), Y21 = 1.092548 xz,
 *   Y22 = 0.546274 (x^2 - y^2), for a unit direction (x, y, z) in the caller's own frame.
 * - A probe holds the projection of incoming radiance L(w) onto these functions (not pre-convolved).
 *   Radiance arriving from direction w is sum_i c_i Y_i(w); irradiance on a surface with normal n
 *   applies the clamped-cosine convolution: E(n) = sum_i A_l(i) c_i Y_i(n), A = (pi, 2pi/3, pi/4).
 */
#ifndef TETPROBE_H
#define TETPROBE_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#  if defined(TETPROBE_BUILDING)
#    define TP_API __declspec(dllexport)
#  else
#    define TP_API __declspec(dllimport)
#  endif
#else
#  define TP_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define TP_VERSION_MAJOR 0
#define TP_VERSION_MINOR 8
#define TP_VERSION_PATCH 0
/** Version as one number, (major << 16) | (minor << 8) | patch; compare with tp_version(). */
#define TP_VERSION ((TP_VERSION_MAJOR << 16) | (TP_VERSION_MINOR << 8) | TP_VERSION_PATCH)

/** Number of floats in one probe's SH coefficients. */
#define TP_SH_FLOATS 27

typedef enum tp_status {
    TP_OK = 0,
    TP_ERROR_INVALID_ARGUMENT = 1, /* a null pointer, a bad count or stride, a non-finite value */
    TP_ERROR_OUT_OF_MEMORY = 2,
    TP_ERROR_IO = 3,               /* a file could not be read or written */
    TP_ERROR_INVALID_BLOB = 4,     /* a store blob failed validation (truncated, corrupt, bad index), or a
                                      query on a forged one gave up (see tp_store_interpolate) */
    TP_ERROR_VERSION = 5,          /* a blob of a format version this library does not read */
    TP_ERROR_DEGENERATE = 6,       /* input the operation cannot use (e.g. no probes) */
    TP_ERROR_TETGEN = 7,           /* TetGen reported a failure */
    TP_ERROR_CANCELLED = 8,        /* a progress callback returned non-zero */
    TP_ERROR_OUTSIDE = 9,          /* a query outside the hull of a store built without extrapolation */
    TP_ERROR_SCENE = 10,           /* a scene or scene file is invalid (the message says what and where) */
    TP_ERROR_UNSUPPORTED = 11,     /* not available in this build (e.g. baking in the run-time library) */
    TP_ERROR_BUFFER_TOO_SMALL = 12,
    TP_ERROR_INTERNAL = 13
} tp_status;

/** Version of the loaded library, in the form of TP_VERSION. */
TP_API uint32_t tp_version(void);

/** Message of the last failure on the calling thread ("" if none); valid until the next tp_ call. */
TP_API const char* tp_last_error(void);

/** Short constant name of a status, e.g. "TP_ERROR_INVALID_BLOB". */
TP_API const char* tp_status_name(tp_status status);

/** Progress callback for long work: fraction in [0, 1], stage a short label. Return non-zero to cancel. */
typedef int (*tp_progress_fn)(void* user, float fraction, const char* stage);

/* ------------------------------------------------------------------------------------------------
 * Probe store: build (bake-time library only), load, save, query.
 * --------------------------------------------------------------------------------------------- */

typedef struct tp_store tp_store;

/** Build flags. */
#define TP_BUILD_NO_EXTRAPOLATION 1u /* no outer cells: queries outside the hull return TP_ERROR_OUTSIDE */
#define TP_BUILD_INDEX32 2u          /* force 32-bit indices even when 16 bits would do */
/** Compact layout: the smallest blob (no neighbour section, rebuilt when the store is loaded; SH not
    padded). Answers are the same as the default fast layout's: the same cell, weights within 1e-6. */
#define TP_BUILD_COMPACT 4u

/** How the SH coefficients are stored (tp_build_options.sh_encoding); queries decode them as they blend.
    HALF: 27 IEEE halves (54 bytes a probe). UNORM8: L0 of each channel as a half, the other 8 coefficients
    as their ratio to it in 8 bits over the range a non-negative radiance can reach (30 bytes): for
    radiance >= 0 each coefficient is within c0 * (step / 2 + max / 1024) of its value (step about
    0.014 to 0.015, max sqrt(3) in band 1, sqrt(5) at most in band 2; docs/store_format.md). The L1
    variants drop band 2 (24 and 15 bytes): queries and tp_store_probe_sh return zeros there. */
#define TP_SH_ENCODING_HALF 0u
#define TP_SH_ENCODING_UNORM8 1u
#define TP_SH_ENCODING_HALF_L1 2u
#define TP_SH_ENCODING_UNORM8_L1 3u

/** How a store keeps its cells (tp_build_options.layout, tp_store_info.layout). FAST (the default):
    vertices and neighbours per cell, SH padded; COMPACT: vertices only, neighbours rebuilt when loaded
    (also TP_BUILD_COMPACT); REBUILT: no cells, no neighbours and no start grid: the loader rebuilds them
    from the positions (exact Delaunay in the run-time library, the cells every other layout stores, index
    for index), which costs time at load (docs/store_format.md). A set with more than 16 cells a probe
    cannot be built in REBUILT (TP_ERROR_INVALID_ARGUMENT: use COMPACT). Queries answer the same in every
    layout. */
#define TP_LAYOUT_FAST 0u
#define TP_LAYOUT_COMPACT 1u
#define TP_LAYOUT_REBUILT 2u

typedef struct tp_build_options {
    uint32_t struct_size;
    uint32_t flags;              /* TP_BUILD_* */
    /** Probes closer than this fraction of the set's bounding-box diagonal are merged (default 1e-6). */
    double merge_tolerance;
    /** A set whose thickness is below this fraction of its diagonal is treated as flat (default 1e-4),
        as a line likewise (default the same). */
    double flat_tolerance;
    tp_progress_fn progress;     /* may be NULL */
    void* progress_user;
    /** Occlusion probes (format 4): 4 bytes per input probe at occlusion_stride bytes (0 = 4), byte i the
        quantised visibility of mixed light i (tp_bake_occlusion's output), or NULL for none. A merged
        probe keeps the rounded mean of its group. */
    const uint8_t* occlusion;
    size_t occlusion_stride;
    uint32_t occlusion_lights;   /* mixed lights the bytes cover, 1..4 (ignored without occlusion) */
    /** Leak control: with a scene, probe pairs of a cell that cannot see each other (an Embree ray each way
        between them hits the scene, and so do four segments beside it: a surface separates them) and are at
        most 3 world units (metres) apart are stored, and queries weigh down the probe behind the wall (see
        tp_store_interpolate). NULL = none. Bake-time library only. */
    const struct tp_scene* scene;
    /** Format 5: TP_SH_ENCODING_* (default HALF). */
    uint32_t sh_encoding;
    /** Non-zero: positions in 16 bits per axis (6 bytes a probe in place of 12), on a grid whose step is
        a power of two: the smallest that spans the probes' extent in 65,534 steps, so coordinates on a
        grid of that step or coarser (probes every 0.5 m) are kept exactly. The positions are quantised
        before anything else, so the cells are exactly Delaunay for the stored positions and a query at a
        stored probe weighs it exactly 1; a stored probe lies within half a step
        (tp_store_info.position_step) of its input on each axis. Probes that quantise to the same point
        are merged (tp_store_info.merged_probes). */
    uint32_t quantize_positions;
    /** TP_LAYOUT_* (default FAST). TP_BUILD_COMPACT in flags asks for COMPACT, and contradicts REBUILT. */
    uint32_t layout;
} tp_build_options;

/** Fills defaults and struct_size. */
TP_API tp_status tp_build_options_init(tp_build_options* options);

/** Builds a store from probe_count probes. positions: 3 floats per probe at position_stride bytes
    (0 = 12). sh: 27 floats per probe at sh_stride bytes (0 = 108), or NULL for zero SH. Duplicate and
    near-duplicate probes are merged; 1, 2, collinear, flat and general sets are all accepted.
    options may be NULL for defaults. On success *out_store owns a new store. */
TP_API tp_status tp_store_build(const float* positions, size_t position_stride, const float* sh,
                                size_t sh_stride, size_t probe_count, const tp_build_options* options,
                                tp_store** out_store);

/** Loads a store from a blob (copied; data may be freed afterwards). Validates everything once:
    size, magic, version, section bounds and alignment, every index against its count, finite
    floats, checksum, no trailing bytes; and refuses what the builder never writes: an origin beyond
    1e30 or positions beyond 2e30 from it, bounds other than the probes' bounding box, normals with a
    component outside [-1, 1], a line or flat set whose cells have no length (area) along the axis
    the blob names. Safe for untrusted input: nothing outside the blob is read, and a query on any
    store that loads examines a bounded number of cells (see tp_store_interpolate). */
TP_API tp_status tp_store_load(const void* data, size_t size, tp_store** out_store);

/** Options of tp_store_load_file_ex. */
typedef struct tp_store_load_options {
    uint32_t struct_size;
    /** Files larger than this are refused with TP_ERROR_IO (default 1 GiB, far beyond any real store:
        a store takes about 200 bytes per probe). */
    uint64_t max_file_bytes;
} tp_store_load_options;

/** Fills defaults and struct_size. */
TP_API tp_status tp_store_load_options_init(tp_store_load_options* options);

/** Loads and validates a store file: tp_store_load_file_ex with the default options. */
TP_API tp_status tp_store_load_file(const char* path, tp_store** out_store);

/** Loads and validates a store file. Only a regular file (symbolic links followed) of at most
    options->max_file_bytes is read; a directory, device (such as /dev/zero), FIFO or socket, or a larger
    file, is refused with TP_ERROR_IO and a message that says which. options may be NULL for defaults. */
TP_API tp_status tp_store_load_file_ex(const char* path, const tp_store_load_options* options, tp_store** out_store);

/** Writes the store's blob to path atomically: a temporary file next to the file is written, flushed
    and renamed over it, so path holds either its old contents or the whole new store. A symbolic link
    is written through (its target gets the new contents; the link stays). An existing file keeps its
    permissions (POSIX mode; on Windows its attributes and access control), a new one gets the process's
    default; a path naming a directory, device or FIFO is refused. The temporary file,
    "<file name>.tetprobe-tmp-<process id>-<16 hex digits>", is removed on every failure; a save that
    was killed leaves it behind, and the next save of the same file removes it (only files of that
    pattern, whose process is gone and which no save holds). */
TP_API tp_status tp_store_save_file(const tp_store* store, const char* path);

/** Read-only view of the store's blob, valid while the store lives. */
TP_API tp_status tp_store_blob(const tp_store* store, const void** out_data, size_t* out_size);

/** Releases a store (NULL is allowed). */
TP_API tp_status tp_store_release(tp_store* store);

/** The parts of a blob (indices of tp_store_info.section_bytes): the header with its section table,
    each section, and the alignment padding between them; together they make tp_store_info.bytes. */
#define TP_STORE_SECTION_HEADER 0u
#define TP_STORE_SECTION_POSITIONS 1u
#define TP_STORE_SECTION_NORMALS 2u      /* the hull probes' normals (32 bits each) */
#define TP_STORE_SECTION_SH 3u
#define TP_STORE_SECTION_PROBE_SOURCE 4u /* stored probe -> input probe */
#define TP_STORE_SECTION_INPUT_REMAP 5u  /* input probe -> stored probe (empty when nothing was merged) */
#define TP_STORE_SECTION_CELLS 6u
#define TP_STORE_SECTION_GRID 7u         /* the start cells of queries without a hint */
#define TP_STORE_SECTION_OCCLUSION 8u
#define TP_STORE_SECTION_LEAK_OFFSETS 9u
#define TP_STORE_SECTION_LEAK_EDGES 10u
#define TP_STORE_SECTION_PADDING 11u
#define TP_STORE_SECTION_COUNT 12u

typedef struct tp_store_info {
    uint32_t struct_size;
    uint32_t format_version;
    uint32_t dimension;          /* of the probe set: 0 point, 1 line, 2 flat, 3 general */
    uint32_t probes;             /* probes kept in the store */
    uint32_t input_probes;       /* probes given to the build */
    uint32_t merged_probes;      /* input_probes - probes */
    uint32_t cells;
    uint32_t inner_cells;
    uint32_t outer_cells;
    uint32_t index_bits;         /* 16 or 32 */
    uint32_t flags;              /* the blob's flags, TP_BUILD_* bits: NO_EXTRAPOLATION and COMPACT as built,
                                    INDEX32 whenever the store uses 32-bit indices */
    uint32_t grid[3];            /* cells of the cold-start grid along x, y, z */
    uint64_t bytes;              /* size of the blob */
    double origin[3];            /* local origin of the store, world units */
    float bounds_min[3];         /* world-space bounds of the probes (quantised positions: the quantisation box) */
    float bounds_max[3];
    uint32_t occlusion_lights;   /* mixed lights with occlusion per probe (0 = none) */
    uint32_t leak_edges;         /* probe pairs that cannot see each other (0 = no leak control) */
    /* Format 5. */
    uint32_t layout;             /* TP_LAYOUT_* */
    uint32_t sh_encoding;        /* TP_SH_ENCODING_* */
    uint32_t quantized_positions; /* 1: 16 bits per axis over the bounds, 0: float32 */
    uint32_t hull_probes;        /* probes on the hull (those whose normals the store keeps) */
    double position_step[3];     /* quantised positions: the gap between neighbouring stored values on each
                                    axis (world units; the largest, should rounding vary it); 0 for float32 */
    uint64_t section_bytes[16];  /* bytes of each part, indexed by TP_STORE_SECTION_* (the rest 0) */
} tp_store_info;

/** Fills info (set info->struct_size first; fields beyond it are left untouched). */
TP_API tp_status tp_store_get_info(const tp_store* store, tp_store_info* info);

/** Reads the stored SH of input probe `probe` into out_sh[27], decoded (what a query at the probe
    returns; zeros in band 2 for the L1 encodings). A merged probe reads its survivor. */
TP_API tp_status tp_store_probe_sh(const tp_store* store, uint32_t probe, float out_sh[27]);

/** Interpolated SH at position. cell_hint: in, the cell of the last query (-1 = none); out, the cell
    found. May be NULL (no hint). In a store built with a scene (leak control), a cell whose probes
    include a pair that cannot see each other scales each probe's weight by its visibility from the
    query (a smoothstep over the wall's crossing of the edge, along the query's barycentric projection
    onto it) and renormalises: continuous everywhere, exact at probes, and cells without such a pair
    answer bit for bit as without leak control. Fails with TP_ERROR_OUTSIDE (a store built without
    extrapolation, outside the hull) or TP_ERROR_INVALID_BLOB (a query that gave up at its cap of cells:
    only a forged or corrupt store's cells make one), with zero SH. */
TP_API tp_status tp_store_interpolate(const tp_store* store, const float position[3], int32_t* cell_hint,
                                      float out_sh[27]);

/** Options of the batch queries. */
typedef struct tp_batch_options {
    uint32_t struct_size;
    uint32_t flags;              /* TP_BATCH_* */
    /** Deprecated and ignored: a batch runs on the calling thread only, and the library
        never starts a thread (values above 1 used to start threads inside each call, which cost
        more than they gained on a frame's batch). Kept so that older callers still compile and run. */
    uint32_t threads;
} tp_batch_options;

/* Splitting a frame over threads: the engine's own workers (a pool started once, or its job system)
   each call a batch function on a disjoint range of the frame's objects, with that range's own hints:

       worker w of W, every frame:
           size_t begin = count * w / W, end = count * (w + 1) / W;
           tp_store_interpolate_batch(store, end - begin, positions + 3 * begin, 0,
                                      hints + begin, 0, sh + 27 * begin, 0, NULL);

   A store is immutable, so any number of such calls run at once; each range's answers are the same
   bits as single queries. Ranges of a few hundred queries or more keep the per-call cost negligible
   (samples/bench: "tetprobe_bench store" times two persistent workers against one). */

/** Without hints (hints == NULL), start each query from the cell the previous query of the same
    range ended in (objects given in a spatially coherent order); by default each starts cold. */
#define TP_BATCH_CHAIN_HINTS 1u

/** Fills defaults (no flags, threads 1) and struct_size. */
TP_API tp_status tp_batch_options_init(tp_batch_options* options);

/** Batch of count queries. positions at position_stride bytes (0 = 12); hints at hint_stride (0 = 4),
    or NULL; out_sh at sh_stride (0 = 108); options may be NULL for defaults. Returns TP_OK, or the
    status of the first query that failed (TP_ERROR_OUTSIDE or TP_ERROR_INVALID_BLOB, as
    tp_store_interpolate), named in the message, with zero SH for every query that failed. */
TP_API tp_status tp_store_interpolate_batch(const tp_store* store, size_t count, const float* positions,
                                            size_t position_stride, int32_t* hints, size_t hint_stride,
                                            float* out_sh, size_t sh_stride, const tp_batch_options* options);

/** The probes and weights a query blends: out_probes are input probe indices (survivors of merges),
    unused slots have weight 0 and repeat a used probe. */
TP_API tp_status tp_store_weights(const tp_store* store, const float position[3], int32_t* cell_hint,
                                  uint32_t out_probes[4], float out_weights[4]);

/** Batch form of tp_store_weights (strides in bytes, 0 = packed: 16 for probes and weights); options as
    tp_store_interpolate_batch. */
TP_API tp_status tp_store_weights_batch(const tp_store* store, size_t count, const float* positions,
                                        size_t position_stride, int32_t* hints, size_t hint_stride,
                                        uint32_t* out_probes, size_t probes_stride, float* out_weights,
                                        size_t weights_stride, const tp_batch_options* options);

/** Kind of the cell a query ended in. */
#define TP_CELL_INNER 0u
#define TP_CELL_OUTER 1u

/** Diagnostics of one query. */
typedef struct tp_location {
    uint32_t struct_size;
    int32_t cell;
    uint32_t cell_kind;          /* TP_CELL_* */
    uint32_t steps;              /* cells visited by the walk after the start cell */
    uint32_t fallback;           /* 1 if the walk handed the decision to the exhaustive search (outside the hull,
                                    where neighbouring outer cells disagree; never inside the hull) */
    uint32_t probes[4];          /* as tp_store_weights */
    float weights[4];
    float t;                     /* outer cells: the ray parameter of the point (0 on the hull) */
} tp_location;

/** Locates position and reports everything the query used (set location->struct_size first). */
TP_API tp_status tp_store_locate(const tp_store* store, const float position[3], int32_t* cell_hint,
                                 tp_location* location);

/** Interpolated SH and occlusion at position (Unity's CalculateInterpolatedLightAndOcclusionProbes):
    out_occlusion[i] in [0, 1] is the visibility of mixed light i blended with the query's weights from
    the probes' quantised bytes (tp_build_options.occlusion); 1 for channels without a mixed light and
    for a store built without occlusion. Outside (TP_ERROR_OUTSIDE) both are zero. */
TP_API tp_status tp_store_interpolate_occlusion(const tp_store* store, const float position[3], int32_t* cell_hint,
                                                float out_sh[27], float out_occlusion[4]);

/** Batch form of tp_store_interpolate_occlusion: as tp_store_interpolate_batch, plus out_occlusion at
    occlusion_stride bytes (0 = 16), 4 floats per query. */
TP_API tp_status tp_store_interpolate_occlusion_batch(const tp_store* store, size_t count, const float* positions,
                                                      size_t position_stride, int32_t* hints, size_t hint_stride,
                                                      float* out_sh, size_t sh_stride, float* out_occlusion,
                                                      size_t occlusion_stride, const tp_batch_options* options);

/* Probe volumes for large objects (what Unity's Light Probe Proxy Volume does): the interpolated SH on a grid of
   up to 32 x 32 x 32 points around an object, for a renderer to upload as a 3D texture and sample per pixel. */

/** The most points along each side of a volume. */
#define TP_VOLUME_MAX_SIDE 32

/** What tp_store_sample_volume writes per point. The Unity formats are the shader constants of Unity's built-in
    pipeline, which ShadeSH9 evaluates to the irradiance divided by pi: with Unity's coefficients u_i = c_i s_i
    (c our SH of one channel; s, each rounded to float: 1/(2 sqrt(pi)); sqrt(3)/(3 sqrt(pi)) for band 1;
    sqrt(15)/(8 sqrt(pi)) for L2-2, L2-1 and L21; sqrt(5)/(16 sqrt(pi)) for L20; sqrt(15)/(16 sqrt(pi)) for L22),
    unity_SHAc = (u3, u1, u2, u0 - u6), unity_SHBc = (u4, u5, 3 u6, u7), unity_SHC = (u8 of r, g, b, 1), each
    product and difference rounded to float. */
#define TP_VOLUME_SH_L2 0u     /* 27 floats: the SH contract */
#define TP_VOLUME_SH_L1 1u     /* 12 floats: bands 0 and 1, [r0..r3, g0..g3, b0..b3] (the first 4 of each channel) */
/** 3 float4: unity_SHAr, unity_SHAg, unity_SHAb of the SH without band 2 (so w = u0), the L0 + L1 terms a Light
    Probe Proxy Volume texture holds: its RGBAFloat (or RGBAHalf) 3D texture of 4 x dims[0] by dims[1] by
    dims[2] texels holds SHAr in x block 0, SHAg in block 1, SHAb in block 2 (and probe occlusion, not written
    here, in block 3): vector_stride 16 x dims[0], point_stride 16, row_stride 64 x dims[0], slice_stride
    64 x dims[0] x dims[1] write it directly. */
#define TP_VOLUME_UNITY_L1 2u
#define TP_VOLUME_UNITY_L2 3u  /* 7 float4: unity_SHAr, SHAg, SHAb, SHBr, SHBg, SHBb, SHC */

/** Layout of a volume's output (set struct_size, or call tp_volume_layout_init). Point (x, y, z) starts at
    x point_stride + y row_stride + z slice_stride bytes; a Unity format's float4 k of the point k vector_stride
    bytes after that. 0 = packed: point_stride one point's floats (4 x 27, 4 x 12, 16 x 3 or 16 x 7 bytes),
    row_stride dims[0] point strides, slice_stride dims[1] row strides, vector_stride 16. A stride below the
    bytes written at once (a point's floats; one float4 in a Unity format) is refused, as is a layout whose
    last byte would lie beyond PTRDIFF_MAX bytes from out or wrap the address space. */
typedef struct tp_volume_layout {
    uint32_t struct_size;
    uint32_t format;             /* TP_VOLUME_* (default TP_VOLUME_SH_L2) */
    size_t point_stride;
    size_t row_stride;
    size_t slice_stride;
    size_t vector_stride;        /* Unity formats only (ignored by the others) */
} tp_volume_layout;

/** Fills defaults (TP_VOLUME_SH_L2, packed) and struct_size. */
TP_API tp_status tp_volume_layout_init(tp_volume_layout* layout);

/** Fills a probe volume: the SH at every point origin + (x, y, z) * cell_size (per axis, computed as
    float(double(origin) + double(index) x double(cell_size))) for x < dims[0], y < dims[1], z < dims[2], each
    dimension 1..TP_VOLUME_MAX_SIDE, cell_size finite and positive. The grid is walked neighbour to neighbour:
    slices z = 0, 1, ...; in slice z the rows y ascending when z is even, descending when odd; in the r-th row
    walked (r counted from 0 over the whole walk) x ascending when r is even, descending when odd; one cell hint
    is carried from point to point, so each point's SH is bit for bit what tp_store_interpolate returns there
    when called in that order with that hint (leak control included). cell_hint (may be NULL: start cold): in,
    the cell to start from; out, the cell of point (0, 0, 0), where the next frame's volume starts. layout may be
    NULL (TP_VOLUME_SH_L2, packed). Never allocates. Fails as tp_store_interpolate does (TP_ERROR_OUTSIDE or
    TP_ERROR_INVALID_BLOB) naming the first point that failed, after filling the whole volume (zero SH, or its
    Unity constants, at the points that failed). */
TP_API tp_status tp_store_sample_volume(const tp_store* store, const float origin[3], const float cell_size[3],
                                        const uint32_t dims[3], int32_t* cell_hint, const tp_volume_layout* layout,
                                        float* out);

/* ------------------------------------------------------------------------------------------------
 * SH helpers (see the SH contract above).
 * --------------------------------------------------------------------------------------------- */

/** Radiance arriving from unit direction `direction` (pointing away from the probe). */
TP_API tp_status tp_sh_eval_radiance(const float sh[27], const float direction[3], float out_rgb[3]);

/** Irradiance on a surface with unit normal `normal` (clamped-cosine convolution). */
TP_API tp_status tp_sh_eval_irradiance(const float sh[27], const float normal[3], float out_rgb[3]);

/** Adds uniform incoming radiance rgb from every direction. */
TP_API tp_status tp_sh_add_ambient(float sh[27], const float rgb[3]);

/** Adds a directional light travelling along `direction` whose irradiance on a surface facing it is
    rgb (a delta of radiance arriving from -direction). */
TP_API tp_status tp_sh_add_directional(float sh[27], const float direction[3], const float rgb[3]);

/* SH evaluation choices. The order says which bands an evaluation uses; the window (Sloan's deringing)
   then scales band l by w_l = 1 / (1 + s (l (l + 1))^2), the least-squares fit penalised by s times the
   squared Laplacian (P.-P. Sloan, "Deringing Spherical Harmonics", SIGGRAPH Asia 2017 technical briefs):
   band 0 is never changed and s = 0 is the identity. Every choice is a rewrite of the 27 coefficients
   (tp_sh_apply_options) followed by the plain L2 evaluation. Only the linear rewrites, L1 and the Sloan
   window of a fixed strength (and the two together), commute with interpolation: applied once to every
   probe before the store is built, the interpolated SH is the same (to float rounding) as applying
   them per query. ZH3 (its axis and zonal term depend on the SH) and TP_SH_WINDOW_NONNEGATIVE (its
   strength is chosen per SH) do not: applied per probe they give a different interpolant (still
   continuous), so apply them to the interpolated SH when the per-query result is wanted. */
#define TP_SH_ORDER_L2  0u  /* all 27 floats (the default) */
#define TP_SH_ORDER_L1  1u  /* bands 0 and 1 only: 12 floats (4 per channel) */
/** L1 plus a zonal L2 term estimated from the L1 data (T. Roughton, P.-P. Sloan et al., "ZH3: Quadratic
    Zonal Harmonics", I3D 2024, the "hallucinated" variant): the axis a is the L1 direction of Rec. 709
    luminance (0.2126 r + 0.7152 g + 0.0722 b), shared by the channels; each channel's zonal coefficient
    is z = L0 q (0.08 + 0.6 q) with q = |L1 . a| / L0 clamped to sqrt(3) (the paper's curve fit; sqrt(3)
    is q's largest value for non-negative radiance), adding radiance z Y20(a . w). A channel with L0 <= 0,
    or SH with no luminance L1 direction, gets no zonal term. Band 2 of the input is not read. */
#define TP_SH_ORDER_ZH3 2u
#define TP_SH_WINDOW_NONE        0u
#define TP_SH_WINDOW_SLOAN       1u  /* Sloan's deringing window of strength window_strength */
/** The smallest window under which tp_sh_eval_irradiance (this library's float evaluation, in its
    operation order) is provably >= 0 at every unit normal: a channel passes when the proven lower
    bound of its minimum (see tp_sh_min_irradiance) clears a proven bound of the float evaluation's
    rounding (21 * 2^-24 times the sum of band factor * |coefficient| * basis magnitude); s is bisected
    over the floats until it is adjacent to one that fails, s being one that passes in every channel
    with a positive L0 (no window can lift a channel whose L0 <= 0, so those are left out). 0 if
    already passing; it may be +infinity (only band 0 kept) when no finite float strength suffices.
    Costs tens of minimum searches: apply it once with tp_sh_apply_options rather than per query. */
#define TP_SH_WINDOW_NONNEGATIVE 2u

typedef struct tp_sh_eval_options {
    uint32_t struct_size;
    uint32_t order;              /* TP_SH_ORDER_* */
    uint32_t window;             /* TP_SH_WINDOW_*, applied after the order */
    float window_strength;       /* s >= 0, finite; read for TP_SH_WINDOW_SLOAN only */
} tp_sh_eval_options;

/** Fills defaults (L2, no window, strength 0) and struct_size. */
TP_API tp_status tp_sh_eval_options_init(tp_sh_eval_options* options);

/** Irradiance for unit normal `normal` under the options' order and window; bit for bit
    tp_sh_eval_irradiance of tp_sh_apply_options(sh). options NULL is the same as tp_sh_eval_irradiance.
    L1 without a window reads only the first 4 floats of each channel. */
TP_API tp_status tp_sh_eval_irradiance_ex(const float sh[27], const float normal[3],
                                          const tp_sh_eval_options* options, float out_rgb[3]);

/** Rewrites sh in place so that its plain L2 evaluation (tp_sh_eval_irradiance) is the evaluation the
    options choose: L1 zeroes band 2; ZH3 writes its zonal term into band 2 as z sqrt(4pi/5) Y2m(a) (the
    addition theorem: a zonal function about any axis is expressible in L2); the window then scales
    bands 1 and 2, each product rounded once to float. options NULL leaves sh unchanged. */
TP_API tp_status tp_sh_apply_options(float sh[27], const tp_sh_eval_options* options);

/** Smallest irradiance over all unit normals per channel, under the options (NULL = L2, no window),
    and the unit normal where the smallest of the three occurs: the "negative irradiance" metric. Each
    channel's irradiance is a quadratic c + b.n + n^T A n on the sphere; its global minimum is the
    trust-region solution (A - mu I) n = -b/2 with mu at most A's smallest eigenvalue, found in double
    by bisection of the monotone secular equation (or that eigenvalue, in the "hard case"), and the
    Lagrange dual at mu bounds it from below, so the answer is exact to double rounding, not sampled. */
TP_API tp_status tp_sh_min_irradiance(const float sh[27], const tp_sh_eval_options* options,
                                      float out_min_rgb[3], float out_normal[3]);

/** The strength TP_SH_WINDOW_NONNEGATIVE picks for sh under options->order (options NULL = L2; the
    window fields are not read). */
TP_API tp_status tp_sh_nonnegative_window_strength(const float sh[27], const tp_sh_eval_options* options,
                                                   float* out_strength);

/* ------------------------------------------------------------------------------------------------
 * Shadow caster volumes (run time): cull potential shadow casters of a light into a convex region.
 * Planes are 4 floats (nx, ny, nz, d), inward: a point x is inside when n.x + d >= 0.
 * --------------------------------------------------------------------------------------------- */

#define TP_LIGHT_DIRECTIONAL 0u
#define TP_LIGHT_POINT 1u
#define TP_LIGHT_SPOT 2u

/** Upper bound of the planes a volume built from plane_count planes may have (SIZE_MAX when that bound
    does not fit in a size_t). */
TP_API size_t tp_shadow_caster_volume_bound(size_t plane_count);

/** Builds the volume of everything that can cast a shadow from a light into the convex polyhedron
    `planes` (bounded; e.g. a view frustum or the probes' bounding box). light_type is
    TP_LIGHT_DIRECTIONAL (light_vector = direction the light travels) or TP_LIGHT_POINT / SPOT
    (light_vector = position). out_planes holds capacity planes; *out_count receives the count. */
TP_API tp_status tp_shadow_caster_volume(const float* planes, size_t plane_count, uint32_t light_type,
                                         const float light_vector[3], float* out_planes, size_t capacity,
                                         size_t* out_count);

/** *out_intersects = 1 if the box may intersect the volume (conservative: never a false 0). */
TP_API tp_status tp_volume_test_aabb(const float* planes, size_t plane_count, const float box_min[3],
                                     const float box_max[3], int* out_intersects);

/** *out_intersects = 1 if the sphere may intersect the volume (conservative). */
TP_API tp_status tp_volume_test_sphere(const float* planes, size_t plane_count, const float center[3],
                                       float radius, int* out_intersects);

/* ------------------------------------------------------------------------------------------------
 * Scenes and the lighting bake (bake-time library only; the run-time library returns
 * TP_ERROR_UNSUPPORTED).
 * --------------------------------------------------------------------------------------------- */

typedef struct tp_scene tp_scene;

typedef struct tp_material {
    uint32_t struct_size;
    float albedo[3];             /* diffuse reflectance, each in [0, 1] */
    float emission[3];           /* emitted radiance, >= 0 */
    int32_t two_sided;           /* non-zero: both faces reflect and emit */
} tp_material;

#define TP_LIGHT_MODE_BAKED 0u    /* direct and bounced light go into the probes */
#define TP_LIGHT_MODE_REALTIME 1u /* the engine draws direct light; only its bounced light is baked */
/** Mixed (Unity's Shadowmask): the engine draws the direct light in real time, the probes bake its
    bounced light (as REALTIME) and, per probe, its visibility (tp_bake_occlusion, occlusion probes).
    At most 4 mixed lights per scene: a fifth is refused with TP_ERROR_SCENE. */
#define TP_LIGHT_MODE_MIXED 2u

typedef struct tp_light {
    uint32_t struct_size;
    uint32_t type;               /* TP_LIGHT_* */
    uint32_t mode;               /* TP_LIGHT_MODE_* */
    int32_t shadows;             /* non-zero: the light casts shadows */
    float color[3];
    /** Directional: irradiance on a surface facing the light. Point, spot: radiant intensity
        (irradiance intensity/d^2 at distance d, facing the light). */
    float intensity;
    float position[3];           /* point, spot */
    float direction[3];          /* directional, spot: the direction the light travels */
    float range;                 /* point, spot: no light beyond (INFINITY = unlimited) */
    float inner_angle;           /* spot: full cone angle in degrees with full intensity */
    float outer_angle;           /* spot: full cone angle in degrees beyond which there is no light */
    /** Point, spot: closer than this the irradiance stays at its value at this distance instead of growing
        without bound (0 = pure inverse square; q3map2 clamps at 16 units). Added in 0.8: a struct_size that
        ends before it (a struct filled by a caller built with the 0.7 header) reads as 0. */
    float near_distance;
} tp_light;

TP_API tp_status tp_material_init(tp_material* material);
TP_API tp_status tp_light_init(tp_light* light);

TP_API tp_status tp_scene_create(tp_scene** out_scene);
TP_API tp_status tp_scene_release(tp_scene* scene);

/** Loads a scene file with the default options (tp_scene_load_file_ex). */
TP_API tp_status tp_scene_load_file(const char* path, tp_scene** out_scene);

/** Which way is up: tp_scene_load_options.up, tp_scene_up, tp_scene_set_up. */
#define TP_UP_FILE 0u  /* load options only: what the file says */
#define TP_UP_POS_X 1u
#define TP_UP_NEG_X 2u
#define TP_UP_POS_Y 3u
#define TP_UP_NEG_Y 4u
#define TP_UP_POS_Z 5u
#define TP_UP_NEG_Z 6u

typedef struct tp_scene_load_options {
    uint32_t struct_size;
    /** Which way is up in the file (TP_UP_*; default TP_UP_FILE: glTF and OBJ +y, FBX its UpAxis, a JSON
        scene its "up", +y by default). Coordinates are not turned: the scene records it (tp_scene_up). */
    uint32_t up;
    /** World units per file unit (default 0: the file's own unit in metres, glTF and OBJ 1, FBX its
        UnitScaleFactor / 100; a JSON scene is in world units, 0 or 1). Positions and ranges scale; point
        and spot intensities scale by the square of world units per metre, so irradiance stays the same. */
    float scale;
} tp_scene_load_options;

/** Fills defaults and struct_size. */
TP_API tp_status tp_scene_load_options_init(tp_scene_load_options* options);

/** Loads a scene file, told by its magic bytes, then its extension: glTF 2.0 (.gltf, .glb; meshes,
    KHR_lights_punctual lights, emissive materials), FBX (.fbx), OBJ (.obj with its .mtl: albedo from Kd,
    emission from Ke), all read through Assimp with node transforms applied, a Quake 3 level (.bsp, IBSP
    version 46, read in y-up metres; conventions in the README), or a JSON scene (.json,
    docs/scene-format.md: a sky, light modes, probes, and files of the other formats). Units (glTF's
    candela and lux taken one to one as radiant intensity and irradiance) are in that document. options may
    be NULL (defaults). An unreadable file gives TP_ERROR_IO; a malformed or truncated one, an unknown light
    type, a referenced file that cannot be read or no mesh TP_ERROR_SCENE naming the file and what is wrong.
    What a bake cannot use (cameras, textures, animations, area lights) is left out and noted
    (tp_scene_notes). */
TP_API tp_status tp_scene_load_file_ex(const char* path, const tp_scene_load_options* options, tp_scene** out_scene);

/** What loading the scene left out or converted, one note a line ("" for none). text (may be NULL
    to ask for the size) receives it if text_capacity bytes hold it and its terminating zero;
    *out_size (may be NULL) receives the bytes needed, also with TP_ERROR_BUFFER_TOO_SMALL. */
TP_API tp_status tp_scene_notes(const tp_scene* scene, char* text, size_t text_capacity, size_t* out_size);

/** The scene's up (TP_UP_POS_X ... TP_UP_NEG_Z; +y unless loaded or set otherwise). Placement's walkable
    mode stands probes along it. */
TP_API tp_status tp_scene_up(const tp_scene* scene, uint32_t* out_up);
TP_API tp_status tp_scene_set_up(tp_scene* scene, uint32_t up);

/** Adds a triangle mesh. vertices: 3 floats each; indices: 3 per triangle. materials: material_count
    materials; triangle_materials: one index into materials per triangle, or NULL (all use the first). */
TP_API tp_status tp_scene_add_mesh(tp_scene* scene, const float* vertices, size_t vertex_count,
                                   const uint32_t* indices, size_t triangle_count,
                                   const tp_material* materials, size_t material_count,
                                   const uint32_t* triangle_materials, uint32_t* out_mesh);

TP_API tp_status tp_scene_add_light(tp_scene* scene, const tp_light* light, uint32_t* out_light);

/** Sky of constant radiance rgb. */
TP_API tp_status tp_scene_set_sky_color(tp_scene* scene, const float rgb[3]);

/** Sky radiance given as SH (27 floats, the contract above). */
TP_API tp_status tp_scene_set_sky_sh(tp_scene* scene, const float sh[27]);

/** Probe positions listed in the scene (from its file or added), view valid while the scene lives. */
TP_API tp_status tp_scene_probes(const tp_scene* scene, const float** out_positions, size_t* out_count);

/** Sets the scene's probe positions (copied). */
TP_API tp_status tp_scene_set_probes(tp_scene* scene, const float* positions, size_t count);

/** Sets the scene's playable seeds (copied; count 0 clears them): points known to be where objects go,
    such as spawn points. Automatic placement then keeps only candidates connected to a seed (see
    tp_place_probes). A Quake 3 level loaded with tp_scene_load_file has its spawn points as seeds. */
TP_API tp_status tp_scene_set_playable_seeds(tp_scene* scene, const float* positions, size_t count);

#define TP_BAKE_NO_CULLING 1u     /* test aid: every mesh occludes every light (no shadow caster culling) */

typedef struct tp_bake_options {
    uint32_t struct_size;
    uint32_t flags;              /* TP_BAKE_* */
    uint32_t rays;               /* rays per probe (default 256) */
    uint32_t bounces;            /* surface reflections between emitter and probe (default 2) */
    uint64_t seed;               /* the same seed gives the same bytes whatever the thread count */
    uint32_t threads;            /* 0 = all cores */
    tp_progress_fn progress;     /* may be NULL */
    void* progress_user;
} tp_bake_options;

TP_API tp_status tp_bake_options_init(tp_bake_options* options);

/** What a bake of this scene will simulate. */
typedef struct tp_effects_plan {
    uint32_t struct_size;
    uint32_t lights;             /* lights in the scene */
    uint32_t direct_lights;      /* baked lights whose direct light reaches the probes */
    uint32_t realtime_lights;    /* lights baked for their bounced light only */
    uint32_t out_of_range_lights;/* lights dropped: their range reaches no probe */
    int32_t sky;                 /* 1 if the scene has a non-black sky */
    uint32_t emissive_meshes;
    uint32_t bounces;            /* bounces that will be simulated (0 if there is nothing to bounce) */
    int32_t shadows;             /* 1 if any simulated light casts shadows */
    uint32_t meshes;
    uint32_t shadow_casters;     /* sum over shadowing lights of meshes kept in its occlusion set */
    uint32_t shadow_caster_candidates; /* sum over shadowing lights of meshes considered */
    /** Probes inside geometry (see tp_find_inside_probes, which lists them; tp_fix_inside_probes drops
        or moves them); 0 also when no mesh has an inside (the summary then says so). */
    uint32_t inside_probes;
} tp_effects_plan;

/** Derives the effects plan; text (may be NULL) receives a one-line summary such as
    "direct: 2 lights (1 out of range); sky: off; emissive: 3 meshes; bounces: 2; shadow casters: 41/120 meshes",
    followed by "; inside geometry: 2 probes (4, 17)" when some probes are inside geometry. */
TP_API tp_status tp_bake_plan(const tp_scene* scene, const float* positions, size_t position_stride,
                              size_t count, const tp_bake_options* options, tp_effects_plan* plan,
                              char* text, size_t text_capacity);

/** Bakes the SH of incoming radiance at count positions into out_sh (27 floats each at sh_stride bytes,
    0 = 108). */
TP_API tp_status tp_bake(const tp_scene* scene, const float* positions, size_t position_stride, size_t count,
                         const tp_bake_options* options, float* out_sh, size_t sh_stride);

/** Occlusion probes: per position 4 bytes at occlusion_stride (0 = 4), byte i = round(255 x the fraction of
    the scene's i-th mixed light (in the order added) seen from the position), 255 for channels without a
    light; *out_mixed_lights (may be NULL) receives the mixed light count (0 to 4). One shadow ray per
    position and light (lights are points, so the fraction is 0 or 1; a light without shadows is always
    seen; range and spot cone are the real-time light's own). Pass the bytes to tp_build_options. options:
    progress only (may be NULL). */
TP_API tp_status tp_bake_occlusion(const tp_scene* scene, const float* positions, size_t position_stride,
                                   size_t count, const tp_bake_options* options, uint8_t* out_occlusion,
                                   size_t occlusion_stride, uint32_t* out_mixed_lights);

/* ------------------------------------------------------------------------------------------------
 * Probe placement (bake-time library only): probes proposed from a scene, and probes of a user's set
 * found inside geometry.
 *
 * Inside geometry: the back of a one-sided triangle is solid (a wall seen from behind), and so is the
 * enclosed volume of a closed two-sided mesh (every edge, by exact vertex positions, shared by two
 * consistently wound triangles: a crate, a pillar); an open two-sided mesh (a sheet) has no inside. A
 * point is inside when more than half of 64 fixed rays from it first hit a triangle from its solid
 * side. A scene where no triangle has a solid side gives TP_ERROR_SCENE (nothing can be decided).
 * --------------------------------------------------------------------------------------------- */

#define TP_PLACEMENT_WHOLE 0u    /* candidates fill the scene's bounds */
#define TP_PLACEMENT_WALKABLE 1u /* candidates stand across a height band above every upward-facing surface (up is
                                    the scene's, tp_scene_up), in columns of the lattice */

typedef struct tp_placement_options {
    uint32_t struct_size;
    uint32_t mode;               /* TP_PLACEMENT_* (default WHOLE) */
    float spacing;               /* candidate lattice spacing, world units (default 1); must be positive */
    float margin;                /* least distance of a probe from every surface (default 0.1) */
    float walk_min_height;       /* walkable: the band above the floor (default 0 to 2) */
    float walk_max_height;
    /** Placement stops at this many probes (0 = no target, the default); set error_bound to 0 as well to
        reach it whatever the error. */
    uint32_t target_count;
    /** Without a target, placement stops at the fewest probes whose estimated error is at most this
        (default 0.25; 0 = no bound). The error: at validation points (free points of the candidates'
        volume, never chosen), the RMS over points and the 6 axis normals of |interpolated - baked|
        luminance irradiance, relative to the mean baked there, with the low-ray bake's noise taken out
        (an estimate of the error against a noise-free bake). Without a target and a bound nothing is
        chosen: every candidate is returned, unbaked. */
    float error_bound;
    uint32_t rays;               /* rays per candidate of the low-sample bake (default 128, at least 2: two halves) */
    uint32_t bounces;            /* as tp_bake_options (default 2) */
    uint64_t seed;               /* the same seed gives the same bytes whatever the thread count */
    uint32_t threads;            /* 0 = all cores */
    tp_progress_fn progress;     /* may be NULL; stages "candidates", "bake", "select", "exchange", "done" */
    void* progress_user;
    /** Points closer than this to a point or spot light do not count in the error and are chosen last
        (world units, default 1; 0 = every point counts): the light's inverse-square peak there is no
        interpolation's to follow. An older caller's struct that ends before it gets the default. */
    float light_clearance;
} tp_placement_options;

/** Fills defaults and struct_size. */
TP_API tp_status tp_placement_options_init(tp_placement_options* options);

/** Upper bound of the probes (and of the error curve's points) tp_place_probes returns for these
    options: the points the inside and margin tests are applied to (the lattice's size; in the walkable
    mode the columns' floors times the band's layers, found with a few rays per column). Fails as
    tp_place_probes does on bad options (spacing, margin larger than the scene, too many points). */
TP_API tp_status tp_place_probes_bound(const tp_scene* scene, const tp_placement_options* options, size_t* out_bound);

/** Places probes. Candidates on a lattice (options->mode), none inside geometry or closer than the margin
    to a surface and, when the scene has playable seeds (tp_scene_set_playable_seeds; a Quake 3 level's
    spawn points), only those connected to a seed; memory grows with the candidates, not with the scene's
    bounds. They are baked with options->rays in two halves (the difference measures the bake's noise),
    then chosen by greedy insertion: from a few far-apart candidates, rounds add, per cell of the current
    probes, the candidate whose insertion lowers the squared error summed over the held-out candidates
    most (noise taken out; where no gain stands out from the noise, the one that takes over the most
    volume), in batches of candidates whose changes do not overlap, until target_count or error_bound.
    A target's set is then refined by exchanges (a probe out, a better candidate in, kept when the
    held-out error drops beyond its noise), so a smaller target's placement need not be a prefix of a
    larger one's; an error_bound result and large targets (about 1,000 probes and more, where exchanges
    are out of the work bound) are the greedy's order. out_positions receives 3 floats per probe in the
    order chosen. out_error_curve (may be NULL) receives 2 floats per point, (probe count, estimated
    error, see error_bound), one per round with counts increasing and the last at the result (the
    refined set's estimate); no points when nothing is chosen. Room: capacity probes and curve_capacity
    points. *out_count and *out_curve_points (may be NULL) receive the counts, also with
    TP_ERROR_BUFFER_TOO_SMALL, when nothing is written; size both with tp_place_probes_bound. Errors
    name the numbers: a target above the candidates or too many candidates for memory
    (TP_ERROR_INVALID_ARGUMENT), fewer than 4 candidates (TP_ERROR_DEGENERATE), no mesh, nothing with
    an inside or no candidate a seed sees (TP_ERROR_SCENE); cancelling writes nothing. */
TP_API tp_status tp_place_probes(const tp_scene* scene, const tp_placement_options* options, float* out_positions,
                                 size_t capacity, size_t* out_count, float* out_error_curve, size_t curve_capacity,
                                 size_t* out_curve_points);

/** Indices (ascending) of the probes inside geometry. out_indices has room for capacity indices (count
    always suffices); *out_count receives how many there are, also with TP_ERROR_BUFFER_TOO_SMALL. */
TP_API tp_status tp_find_inside_probes(const tp_scene* scene, const float* positions, size_t position_stride,
                                       size_t count, uint32_t* out_indices, size_t capacity, size_t* out_count);

#define TP_INSIDE_DROP 0u /* leave probes inside geometry out (the others keep their order) */
#define TP_INSIDE_PUSH 1u /* move each to the nearest free point found at least margin from every surface */

/** Fixes the probes inside geometry: out_positions (3 floats per probe, packed, room for capacity
    probes; count always suffices; may be positions itself when packed) receives the kept probes for
    TP_INSIDE_DROP, or every probe with the inside ones moved for TP_INSIDE_PUSH. A probe that cannot
    be pushed out fails the call with TP_ERROR_SCENE naming it (nothing written). */
TP_API tp_status tp_fix_inside_probes(const tp_scene* scene, const float* positions, size_t position_stride,
                                      size_t count, uint32_t mode, float margin, float* out_positions,
                                      size_t capacity, size_t* out_count);

#ifdef __cplusplus
}
#endif

#endif /* TETPROBE_H */
