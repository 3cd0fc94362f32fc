"""scipy's Delaunay.find_simplex on the locate benchmark's own probes and query points.

Usage: /usr/bin/python3 samples/bench/scipy_locate.py DIR

Reads DIR/locate.json and the .npy files it names (written by `tetprobe_bench locate --out DIR`),
builds scipy's own Delaunay (Qhull) on the same probes, times find_simplex per query, and writes
DIR/scipy_locate.json. find_simplex takes no hint from the caller: within one call, each point's
walk starts in the simplex where the previous point's ended, so the coherent paths (each object's
frames in order) are its best case and the random points are its teleport. Times are for one
vectorised call over all points (median of 3) and for one call per point on the first 2,000 points
(what a per-object caller in Python pays;
each call starts its walk anew). If scipy or the input is missing, the JSON says why.
"""
import json
import os
import sys
import time


def _median_seconds(run, repetitions=5):
    times = []
    for _ in range(repetitions):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    times.sort()
    return times[len(times) // 2]


def measure(directory):
    """Returns the scipy_locate.json document for the locate benchmark's files in directory."""
    try:
        with open(os.path.join(directory, "locate.json")) as f:
            locate = json.load(f)
    except (OSError, ValueError) as e:
        return {"part": "scipy_locate", "not_run": "no locate.json from tetprobe_bench locate (%s)" % e}
    try:
        import numpy as np
        import scipy
        from scipy.spatial import Delaunay
    except ImportError as e:
        return {"part": "scipy_locate", "not_run": "scipy or numpy not installed (%s)" % e}
    result = {"part": "scipy_locate", "scipy": scipy.__version__, "sizes": []}
    for size in locate.get("sizes", []):
        files = size["files"]
        probes = np.load(os.path.join(directory, files["probes"])).astype(np.float64)
        start = time.perf_counter()
        tri = Delaunay(probes)
        build_seconds = time.perf_counter() - start
        rows = []
        for query, name in (("coherent", "coherent"), ("teleport", "cold")):
            points = np.load(os.path.join(directory, files[name])).astype(np.float64)
            found = tri.find_simplex(points)
            vectorised = _median_seconds(lambda: tri.find_simplex(points), repetitions=3)
            few = points[:2000]
            per_point = _median_seconds(lambda: [tri.find_simplex(p) for p in few], repetitions=3)
            rows.append({
                "method": "scipy", "query": query, "queries": int(len(points)),
                "ns_per_query": 1e9 * vectorised / len(points),
                "ns_per_query_one_call_each": 1e9 * per_point / len(few),
                "outside": int(np.count_nonzero(found < 0)),
            })
        result["sizes"].append({"probes": size["probes"], "build_seconds": build_seconds, "rows": rows})
    return result


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    result = measure(argv[1])
    path = os.path.join(argv[1], "scipy_locate.json")
    with open(path + ".tmp", "w") as f:
        json.dump(result, f, indent=1)
    os.replace(path + ".tmp", path)
    print("scipy_locate: " + result.get("not_run", "%d probe sets timed" % len(result["sizes"])))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
