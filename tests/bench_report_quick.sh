#!/usr/bin/env bash
# Smoke run of the report's benchmark parts (issue 8, parts 3-5) with --quick, then scipy_locate.py and
# report.py on their output; checks what must hold whatever the machine's speed: every part wrote its
# JSON, culling left the baked SH bit for bit the same, steps and bytes are consistent, and the report
# has every section. Usage: bench_report_quick.sh TETPROBE_BENCH OUT_DIR (from the repository root).
set -euo pipefail
bench=$1
out=$2
rm -rf "$out" && mkdir -p "$out"
for part in locate bake probes; do
  "$bench" "$part" --quick --out "$out" > "$out/$part.txt"
done
/usr/bin/python3 samples/bench/scipy_locate.py "$out"
/usr/bin/python3 samples/bench/report.py "$out"
/usr/bin/python3 - "$out" <<'PY'
import json, math, os, sys
out = sys.argv[1]
load = lambda name: json.load(open(os.path.join(out, name)))
locate = load("locate.json")
for size in locate["sizes"]:
    rows = {(r["method"], r["query"], r["start"]): r for r in size["rows"]}
    ours = [r for r in size["rows"] if r["method"] == "tetprobe"]
    assert len(ours) == 4, ours
    for r in ours:
        assert r["ns_per_query"] > 0 and r["max_steps"] >= r["mean_steps"] >= 0, r
    coherent = rows[("tetprobe", "coherent", "hint of the last frame")]
    teleport = rows[("tetprobe", "teleport", "hint of the previous random point")]
    assert coherent["mean_steps"] < teleport["mean_steps"], (coherent, teleport)
    for key in ("probes", "coherent", "cold"):
        assert os.path.getsize(os.path.join(out, size["files"][key])) > 128
bake = load("bake.json")
assert bake["scenes"] and all(s["rows"] for s in bake["scenes"])
for c in bake["culling"]:
    assert c["identical_bytes"] and c["max_abs_difference"] == 0, c
    assert c["on"]["shadow_casters"] <= c["off"]["shadow_casters"], c
probes = load("probes.json")
levels = probes["levels"]
assert len(levels) >= 2
for a, b in zip(levels, levels[1:]):
    assert b["probes"] > a["probes"] and b["fast_bytes"] > a["fast_bytes"] > a["compact_bytes"], (a, b)
assert all(math.isfinite(l["rms_error"]) for l in levels)
scipy = load("scipy_locate.json")
assert "not_run" in scipy or all(r["outside"] == 0 for s in scipy["sizes"] for r in s["rows"]), scipy
report = open(os.path.join(out, "report.md")).read()
for heading in ("## 3. Locate", "## 4. Bake", "## 5. Probe count", "## 6. Leak control",
                "## 7. Probe placement", "## 8. Headline ratios"):
    assert heading in report, heading
print("bench report smoke run: ok")
PY
