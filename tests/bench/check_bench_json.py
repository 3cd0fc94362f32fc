"""Smoke test of `tetprobe_bench methods --quick` and `precision --quick`: runs both into a temporary
directory and checks properties of their JSON that would fail if the benchmark were wrong.

usage: check_bench_json.py TETPROBE_BENCH REPOSITORY_ROOT
"""
import json
import math
import os
import subprocess
import sys
import tempfile

METHODS = ["tetrahedral_fast", "tetrahedral_compact", "grid_equal_count", "grid_equal_memory", "knn4", "knn4_damped"]
# A query at a probe blends that probe alone: only the rounding of the SH to half is left (2^-11 relative
# per coefficient; a bright probe is a few times the scene's mean irradiance).
HALF_AT_PROBES = 0.02

failures = []


def expect(condition, message):
    if not condition:
        failures.append(message)


def finite(value):
    return isinstance(value, (int, float)) and math.isfinite(value)


def check_methods(doc):
    expect(doc["schema"] == "tetprobe-bench-methods/1", "methods schema")
    expect(len(doc["scenes"]) == 3, "methods: all three sample scenes")
    for scene in doc["scenes"]:
        name = scene["name"]
        frames = scene["path"]["frames"]
        expect(len(scene["path"]["points"]) == frames and len(scene["path"]["reference_trace"]) == frames,
               f"{name}: path sizes")
        expect(scene["mean_irradiance"] > 0, f"{name}: mean irradiance")
        by_id = {m["id"]: m for m in scene["methods"]}
        expect(sorted(by_id) == sorted(METHODS), f"{name}: methods {sorted(by_id)}")
        slice_ = scene["slice"]
        cells = slice_["nx"] * slice_["nz"]
        expect(len(slice_["reference"]) == cells, f"{name}: slice reference size")
        for m in scene["methods"]:
            for key in ["rms_error", "max_error", "worst_jump", "ns_per_query", "path_rms_error"]:
                expect(finite(m[key]), f"{name} {m['id']}: {key} = {m[key]}")
            expect(m["ns_per_query"] > 0 and m["bytes"] > 0, f"{name} {m['id']}: ns and bytes positive")
            expect(m["rms_error"] <= m["max_error"], f"{name} {m['id']}: RMS above max")
            expect(len(m["trace"]) == frames, f"{name} {m['id']}: trace size")
            expect(len(slice_["methods"][m["id"]]) == cells, f"{name} {m['id']}: slice size")
        for exact in ["tetrahedral_fast", "tetrahedral_compact", "knn4"]:
            expect(by_id[exact]["at_probes_max_error"] < HALF_AT_PROBES,
                   f"{name} {exact}: at the probes {by_id[exact]['at_probes_max_error']}")
        # The compact layout answers the same cells and weights as the fast one (within 1e-6).
        expect(abs(by_id["tetrahedral_fast"]["rms_error"] - by_id["tetrahedral_compact"]["rms_error"]) < 1e-4,
               f"{name}: fast and compact layouts disagree")
        # Exponential smoothing never jumps further than its input's largest jump (a linear filter with
        # alpha < 1 started on the input: by induction the lag stays below jump / alpha).
        expect(by_id["knn4_damped"]["worst_jump"] <= by_id["knn4"]["worst_jump"] * (1 + 1e-5),
               f"{name}: damping increased the worst jump")
        # Still objects: the damped method's point errors are the undamped ones.
        expect(by_id["knn4_damped"]["rms_error"] == by_id["knn4"]["rms_error"], f"{name}: still-object damping")
        fast_bytes = by_id["tetrahedral_fast"]["bytes"]
        expect(by_id["grid_equal_memory"]["bytes"] <= fast_bytes, f"{name}: equal-memory grid over budget")
        expect(by_id["grid_equal_count"]["probes"] <= scene["probes"], f"{name}: equal-count grid over budget")
        grid = by_id["grid_equal_memory"]["grid"]
        expect(grid[0] * grid[1] * grid[2] == by_id["grid_equal_memory"]["probes"], f"{name}: grid dims")


def check_precision(doc):
    expect(doc["schema"] == "tetprobe-bench-precision/1", "precision schema")
    for scene in doc["scenes"]:
        rows = {r["id"]: r for r in scene["rows"]}
        expect(len(rows) == 72, f"precision: {len(rows)} rows, expected 8 storages x 3 orders x 3 windows")
        for r in rows.values():
            for key in ["rms_error", "max_error", "negative_fraction", "ns_per_query", "bytes_per_probe"]:
                expect(finite(r[key]), f"precision {r['id']}: {key} = {r[key]}")
            expect(0 <= r["negative_fraction"] <= 1, f"precision {r['id']}: negative fraction")
            if r["precision"] == "float32":
                # Weight 1 at a probe on the baked floats: the probe's own bake, bit for bit.
                expect(r["at_probes_max_error"] == 0, f"precision {r['id']}: float32 at probes {r['at_probes_max_error']}")
            elif r["precision"] == "half":
                expect(r["at_probes_max_error"] < HALF_AT_PROBES, f"precision {r['id']}: half at probes")
            if r["window"] == "nonnegative" and r["precision"] in ("float32", "half"):
                # Applied per probe: a blend of probes each non-negative everywhere has fewer negatives (up to
                # the rounding of the stored coefficients) than the blend of the raw probes. (Not for the
                # 8-bit and L1 encodings: they store other coefficients than the window was applied to.)
                plain = rows[r["id"].replace("_nonnegative", "_none")]
                expect(r["negative_fraction"] <= plain["negative_fraction"],
                       f"precision {r['id']}: non-negative window left more negatives than none")
        # The 8-bit and L1 encodings: never more accurate than half at the probes, and smaller.
        for encoding in ["unorm8", "half_l1", "unorm8_l1"]:
            row, half = rows[f"{encoding}_fast_L2_none"], rows["half_fast_L2_none"]
            expect(row["at_probes_max_error"] >= half["at_probes_max_error"], f"precision {encoding}: at probes beats half")
            expect(row["store_bytes_per_probe"] < half["store_bytes_per_probe"], f"precision {encoding}: not smaller")
        smallest = rows["unorm8_compact_quantized_L2_none"]
        expect(smallest["store_bytes_per_probe"] < rows["unorm8_fast_L2_none"]["store_bytes_per_probe"],
               "precision: the smallest L2 store is not smaller than unorm8 fast")
        for order in ["L2", "L1", "ZH3"]:
            fast, compact = rows[f"half_fast_{order}_none"], rows[f"half_compact_{order}_none"]
            expect(abs(fast["rms_error"] - compact["rms_error"]) < 1e-4, f"precision {order}: fast vs compact")
            expect(compact["bytes_per_probe"] < fast["bytes_per_probe"], f"precision {order}: compact not smaller")
        for decision in scene["decisions"]:
            expect(decision["winner"] in decision["candidates"], f"precision: winner of {decision['question']}")
            expect(decision["winner"] in decision["tied"], f"precision: winner of {decision['question']} not tied")


def main():
    bench, root = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as out:
        for command in ["methods", "precision"]:
            subprocess.run([bench, command, "--quick", "--out", out], cwd=root, check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(out, "methods.json")) as f:
            check_methods(json.load(f))
        with open(os.path.join(out, "precision.json")) as f:
            check_precision(json.load(f))
    for failure in failures:
        print("FAILED:", failure)
    print(f"{'failed' if failures else 'passed'}: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
