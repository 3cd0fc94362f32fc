"""Python access to the real-level benchmark's prepared levels and evaluator (tetprobe_bench levels).

    import sys; sys.path.insert(0, "samples/bench"); import level_eval
    level = level_eval.load("aggressor")            # numpy arrays of the cached level (prepared on first use)
    level["playable"], level["points"], level["reference"], level["paths"], level["meta"]
    result = level_eval.evaluate("aggressor", positions)   # positions [N,3]: baked, built, measured
    result["results"][0]["rms_error"]                # one row per store layout (see bench_levels.cpp)

The metric is level_metric.h's: luminance irradiance for the 6 axis normals at the level's evaluation
points against a 1,024-ray reference, RMS and 95th percentile relative to the level's mean, worst
frame-to-frame jump along walking paths. The probes are baked with the level's probe settings (256 rays,
2 bounces, seed 1) by the tool itself, so every probe set is judged the same way.
Paths: BUILD (default build/) holds samples/tetprobe_bench, BUILD/levels/maps the .bsp files
(samples/bench/setup_levels.sh) and BUILD/levels/cache the prepared levels.
"""
import json
import os
import subprocess
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def _paths(build):
    build = build or os.path.join(ROOT, "build")
    return (os.path.join(build, "samples", "tetprobe_bench"), os.path.join(build, "levels", "maps"),
            os.path.join(build, "levels", "cache"))


def _run(args, build):
    tool, maps, cache = _paths(build)
    out = subprocess.run([tool, "levels"] + args + ["--maps", maps, "--cache", cache], check=True,
                         stdout=subprocess.PIPE, universal_newlines=True)
    return out.stdout


def load(level, build=None):
    """The prepared level as numpy arrays: playable [P,3] (the playable space's grid points), points [M,3]
    (evaluation points), reference [M,27], paths [F,3] (frames of the walking paths one after another;
    meta["path_frames"] says how many each), meta (the cache's meta.json)."""
    import numpy as np
    _run(["prepare", "--level", level], build)
    directory = os.path.join(_paths(build)[2], level)
    arrays = {name: np.load(os.path.join(directory, name + ".npy")) for name in ("playable", "points", "reference", "paths")}
    with open(os.path.join(directory, "meta.json")) as f:
        arrays["meta"] = json.load(f)
    return arrays


def evaluate(level, positions, layout=None, build=None):
    """Bakes, builds (every store layout, or `layout`) and measures the probe set; returns the JSON of
    `tetprobe_bench levels eval --json`: {"level": {...}, "results": [{"layout", "probes", "bytes",
    "resident_bytes", "rms_error", "p95_error", "max_error", "worst_jump", "ns_per_query", ...}]}."""
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        for p in positions:
            f.write("%.9g,%.9g,%.9g\n" % (float(p[0]), float(p[1]), float(p[2])))
        name = f.name
    try:
        args = ["eval", "--level", level, "--probes", name, "--json"] + (["--layout", layout] if layout else [])
        return json.loads(_run(args, build))
    finally:
        os.remove(name)
