// tetprobe_bench methods | precision [--out DIR] [--quick] [--scene PATH]...: parts 1 and 2 of issue 8.
// Every method answers the same query points and the same path, against a reference baked with tp_bake
// directly at each point (the same rays, bounces and seed as the probes: the same estimator). Writes
// DIR/methods.json and DIR/precision.json (DIR defaults to build/bench) for samples/bench/report.py.
//
// JSON schema (stable; "?" marks a field that may be null when a peer cannot run, with "skipped" saying why).
// Irradiance is a scalar: the Rec. 709 luminance 0.2126 R + 0.7152 G + 0.0722 B of E(n) (tp_sh_eval_irradiance).
// An error is |E_method(p, n) - E_reference(p, n)| over every query point p and each of the 6 axis normals n,
// divided by "mean_irradiance" (the mean of E_reference over the same points and normals): rms_error is the
// root mean square of that, max_error its maximum.
//
// methods.json
// {
//   "schema": "tetprobe-bench-methods/1", "quick": bool,
//   "bake": {"rays": int, "bounces": int, "seed": int, "why": str},      // one setting for probes, grids, references
//   "irradiance": str, "error": str, "popping": str, "timing": str,         // the definitions, in words
//   "damping": {"time_constant_frames": float, "frame_seconds": float, "alpha": float, "rule": str},
//   "scenes": [{
//     "name": str, "file": str,
//     "probes": int, "probe_source": "scene file" | "uniform",
//     "probe_bounds": {"min": [3], "max": [3]},
//     "query_box": {"min": [3], "max": [3]},   // probe bounds; an axis thinner than 1% of the diagonal widened to +-0.5
//     "queries": int,                          // uniform random points in query_box (seeded)
//     "reference_noise": float,                // rms_error (as defined above) of a second reference with another seed
//     "mean_irradiance": float,
//     "path": {"frames": int, "points": [[x, y, z], ...], "normal": [3],
//              "reference_trace": [E per frame for "normal", relative to mean_irradiance],
//              "reference_worst_jump": float, // the reference's own worst frame-to-frame jump (see "popping")
//              "reference_note": str},
//     "methods": [{
//       "id": "tetrahedral_fast" | "tetrahedral_compact" | "grid_equal_count" | "grid_equal_memory"
//             | "knn4" | "knn4_damped",
//       "label": str,              // human-readable name for tables and legends
//       "probes": int,             // probes this method blends (grids: nx*ny*nz)
//       "grid": [nx, ny, nz] | null,
//       "bytes": int,              // bytes of the method's run-time data
//       "rms_error": float, "max_error": float,
//       "worst_jump": float,       // popping along the path (same definition as reference_worst_jump)
//       "ns_per_query": float,     // single queries along the path, each with its hint/state, median of 5 runs
//       "at_probes_max_error": float | null,  // max error at the probe positions against the probes' own bake
//       "trace": [E per frame along the path for path.normal, relative to mean_irradiance]
//     }],
//     "slice": {"axis": "y", "height": float, "normal": [3],
//               "x": [min, max], "z": [min, max], "nx": int, "nz": int,   // row-major: row = z index, column = x index
//               "reference": [nx*nz floats, E relative to mean_irradiance],
//               "methods": {"<method id>": [nx*nz floats], ...}}
//   }]
// }
//
// precision.json (one scene, two rooms, unless --scene is given; the same queries, path and reference as methods.json)
// {
//   "schema": "tetprobe-bench-precision/1", "quick": bool, "bake": {...as above}, "error": str,
//   "rule": str,                  // how a winner is chosen: error first (ties within "tie_margin"), then ns, then bytes
//   "scenes": [{
//     "name": str, "file": str, "probes": int, "queries": int, "mean_irradiance": float,
//     "reference_noise": float, "tie_margin": float,
//     "rows": [{
//       "id": str,                 // e.g. "half_fast_L2_none"
//       "precision": "float32" | "half", "layout": "fast" | "compact",
//       "order": "L2" | "L1" | "ZH3", "window": "none" | "sloan" | "nonnegative",
//       "rms_error": float, "max_error": float,
//       "negative_fraction": float, // fraction of query points whose tp_sh_min_irradiance (any channel) < 0
//       "ns_per_query": float,      // interpolate + evaluate one normal, along the path with hints, median of 5
//       "bytes_per_probe": float,   // the store's bytes per probe if its SH section held only what the order reads
//                                   // (L1 and ZH3: 12 coefficients; L2: 27) at this precision
//       "store_bytes_per_probe": float, // the store as built today (27 coefficients)
//       "at_probes_max_error": float    // at the probe positions against their own bake (float32: exactly 0)
//     }],
//     "decisions": [{
//       "question": "precision and layout" | "order and window" | "overall",
//       "candidates": [row ids],
//       "winner": row id,
//       "why": str
//     }]
//   }]
// }
