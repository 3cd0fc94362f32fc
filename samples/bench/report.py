"""The benchmark report of issue 8: build/bench/*.json -> report.md and PNG plots.

Usage: /usr/bin/python3 samples/bench/report.py DIR

Reads what `tetprobe_bench ... --out DIR` and samples/bench/scipy_locate.py wrote into DIR
(levels.json, methods.json, precision.json, locate.json, scipy_locate.json, bake.json, probes.json, leak.json,
and the store benchmark's markdown store.md) and what samples/bench/placement_vs_uniform.py wrote (placement.json) and writes DIR/report.md and the plots (report_plots.py) beside it,
and DIR/readme_section.md, the README's digest (images under docs/bench/, where `make bench-docs`
copies them).
A part whose file is missing, unreadable or marked "not_run", and a peer a part could not run, is
said in the report ("not run: why"), never dropped. Needs only the standard library; the plots need
matplotlib (without it the report says so).
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_levels  # noqa: E402  (beside this file)
import report_placement_levels  # noqa: E402
import report_plots  # noqa: E402

PARTS = {
    "methods": ("methods.json", "tetprobe_bench methods"),
    "precision": ("precision.json", "tetprobe_bench precision"),
    "locate": ("locate.json", "tetprobe_bench locate"),
    "scipy_locate": ("scipy_locate.json", "samples/bench/scipy_locate.py"),
    "bake": ("bake.json", "tetprobe_bench bake"),
    "probes": ("probes.json", "tetprobe_bench probes"),
    "leak": ("leak.json", "tetprobe_bench leak"),
    "placement": ("placement.json", "samples/bench/placement_vs_uniform.py"),
    "levels": ("levels.json", "tetprobe_bench levels (samples/bench/run_levels.sh)"),
    "levels_placement": ("levels_placement.json", "tetprobe_bench levels placement (samples/bench/run_levels.sh)"),
}


def load_parts(directory):
    """Returns ({part: document}, {part: why it is missing}) for every part of PARTS."""
    docs, missing = {}, {}
    for part, (name, producer) in PARTS.items():
        path = os.path.join(directory, name)
        try:
            with open(path) as f:
                doc = json.load(f)
        except FileNotFoundError:
            missing[part] = "%s is missing (%s did not write it)" % (name, producer)
            continue
        except (OSError, ValueError) as e:
            missing[part] = "%s is unreadable (%s)" % (name, e)
            continue
        if isinstance(doc, dict) and doc.get("not_run"):
            missing[part] = doc["not_run"]
        else:
            docs[part] = doc
    return docs, missing


def num(value, digits=3):
    """A table cell: '-' for a missing value, else a number with `digits` significant digits."""
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return "{:,}".format(value)
    if value != value:  # NaN
        return "-"
    if value != 0 and (abs(value) >= 1e5 or abs(value) < 1e-3):
        return "%.*e" % (digits - 1, value)
    return "%.*g" % (digits, value) if abs(value) < 10 ** digits else "%.0f" % value


def table(header, rows):
    """Markdown table lines: header is a list of (title, align) with align '<' or '>'."""
    lines = ["| " + " | ".join(t for t, _ in header) + " |",
             "| " + " | ".join("---:" if a == ">" else "---" for _, a in header) + " |"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return lines


def not_run(why):
    return ["**Not run:** %s." % why.rstrip(".")]


def image(name, alt):
    return ["![%s](%s)" % (alt, name)]


class Report:
    def __init__(self, directory):
        self.directory = directory
        self.docs, self.missing = load_parts(directory)
        self.not_run = []  # (what, why) for the summary at the end
        for part, why in self.missing.items():
            self.not_run.append((PARTS[part][1], why))
        self.plots = report_plots.Plotter(directory)
        if not self.plots.available:
            self.not_run.append(("plots", self.plots.why))

    def plot(self, method, *args):
        """Draws one plot; returns markdown lines for it, or the reason it is not there."""
        name, why = self.plots.draw(method, *args)
        if name:
            return image(name, os.path.splitext(name)[0].replace("_", " "))
        return not_run("plot %s: %s" % (method, why))

    # ---- real levels (first: the report's answer to "what does accuracy cost")

    def real_levels(self):
        out = ["## Real levels: what accuracy costs against the probe volumes engines ship", ""]
        doc = self.docs.get("levels")
        if doc is None:
            return out + not_run(self.missing["levels"]) + [""]
        st = doc.get("settings", {})
        placement = st.get("placement", {})
        out += ["Levels: %s (`make bench` runs %s by default; `make bench BENCH_LEVELS=all` runs %s)." % (
                    ", ".join(l.get("name", "?") for l in doc.get("levels", [])), ", ".join(doc.get("default_levels", [])),
                    ", ".join(doc.get("all_levels", []))), "",
                "- import: %s" % doc.get("import", "?"),
                "- metric (every part and method): %s" % doc.get("metric", "?"),
                "- bake: every method's probes with %s rays and %s bounces (seed 1); the reference with %s rays at %s "
                "points (its noise: a second seed at %s of them)." % (
                    st.get("probe_rays"), st.get("bounces"), st.get("reference_rays"), st.get("points"),
                    st.get("noise_points")),
                "- tetprobe's probe sets: %s probes chosen among the same candidates (tp_place_probes, %s mode, "
                "spacing %s m, band %s m, no pruning), each chosen probe's SH from the candidates' one bake: placed "
                "(tp_place_probes, target N, %s-ray candidate bake of its own), a random subsample (mean of %s seeds), "
                "a uniform lattice pick, and all candidates; every store layout (%s)." % (
                    " / ".join(str(c) for c in st.get("counts", [])), placement.get("mode"), placement.get("spacing"),
                    placement.get("band"), placement.get("rays"), st.get("random_seeds"),
                    ", ".join(l["id"] for l in st.get("layouts", []))),
                "- peers, at the bytes of each tetprobe layout's placed store: a uniform grid over the playable "
                "space's box (trilinear; probes inside geometry dilated from valid neighbours) in half SH (54 bytes a "
                "probe) and in APV's 8-bit L2 (32); an adaptive brick grid like Unreal's Volumetric Lightmap (4^3-cell "
                "bricks with border samples at cell sizes x16, x4, x1, refined near surfaces where lighting changes, "
                "an indirection grid, 8-bit); 4 nearest probes (inverse distance, without and with damping) on the "
                "placed set.", ""]
        out += ["**Summary** (compact layout; ratio > 1: tetprobe has less error than the best grid peer at equal "
                "memory; the last two columns: at the same bytes, the layout that holds the most placed probes of "
                "one placement order, usually the smallest, against the same peer):", ""]
        out += table(report_levels.SUMMARY_HEADER, report_levels.summary_rows(doc)) + [""]
        for level in doc.get("levels", []):
            if level.get("not_run"):
                self.not_run.append(("real level %s" % level.get("name"), level["not_run"]))
                out += report_levels.level_section(level, st, [])
                continue
            for s in level.get("skipped", []):
                self.not_run.append(("%s on %s at %s" % (s.get("method"), level.get("name"),
                                                         num(s.get("budget_bytes", s.get("target")))), s.get("why")))
            out += report_levels.level_section(level, st, self.plot("levels_error_vs_bytes", level))
        return out

    def levels_placement(self):
        out = ["## Real levels: placement against simpler choices of the same candidates", ""]
        doc = self.docs.get("levels_placement")
        if doc is None:
            return out + not_run(self.missing["levels_placement"]) + [""]
        st = doc.get("settings", {})
        placement = st.get("placement", {})
        out += ["Placement (tp_place_probes, %s mode, spacing %s m, band %s m, %s-ray candidate bake, %s threads) runs "
                "once per count with that target (each set refined at its own target, as a user asking for N probes gets it). Beside it, among the same candidates "
                "(each chosen probe's SH from the candidates' one bake, compact layout): a random subsample (mean of %s "
                "seeds), the uniform lattice pick, all candidates; the error placement reports for each count (the "
                "last point of that count's own curve); and the placed set with leak control. Same metric "
                "as above. Misses: placed above 0.8x random (random), above the lattice pick (lattice), reported more "
                "than 30%% off the measured (reported), leak control above the error without (leak)." % (
                    placement.get("mode"), placement.get("spacing"), placement.get("band"), placement.get("rays"),
                    st.get("threads") or "all", st.get("random_seeds")), ""]
        out += table(report_placement_levels.SUMMARY_HEADER, report_placement_levels.summary_rows(doc)) + [""]
        for level in doc.get("levels", []):
            if level.get("not_run"):
                self.not_run.append(("placement on real level %s" % level.get("name"), level["not_run"]))
                out += report_placement_levels.level_section(level, [])
                continue
            out += report_placement_levels.level_section(level, self.plot("levels_placement", level))
        return out

    # ---- 1. interpolation methods

    def methods(self):
        out = ["## 1. Interpolation methods", ""]
        doc = self.docs.get("methods")
        if doc is None:
            return out + not_run(self.missing["methods"]) + [""]
        bake = doc.get("bake", {})
        out += ["Every method on the same probes, query points and path; the reference is baked directly at "
                "each query point (%s rays, %s bounces)." % (bake.get("rays", "?"), bake.get("bounces", "?")), ""]
        for what in ("irradiance", "error", "popping", "timing"):
            if doc.get(what):
                out.append("- %s: %s" % (what, doc[what]))
        if isinstance(doc.get("damping"), dict) and doc["damping"].get("rule"):
            out.append("- damping: %s" % doc["damping"]["rule"])
        out.append("")
        for scene in doc.get("scenes", []):
            path = scene.get("path") or {}
            out += ["### %s" % scene.get("name", "?"), "",
                    "%s probes (%s); %s query points%s; reference noise (a second reference, another seed): %s; "
                    "path of %s frames%s." % (
                        num(scene.get("probes")), scene.get("probe_source", "?"), num(scene.get("queries")),
                        " (%s)" % scene["query_rule"] if scene.get("query_rule") else "",
                        num(scene.get("reference_noise")), num(path.get("frames")),
                        ", %s of them inside geometry or crossing a surface" % num(path["bad_frames"])
                        if path.get("bad_frames") else ""), ""]
            rows, notes = [], []
            for m in scene.get("methods", []):
                label = m.get("label", m.get("id"))
                rows.append([label, num(m.get("probes")), num(m.get("bytes")), num(m.get("rms_error")),
                             num(m.get("max_error")), num(m.get("path_rms_error")), num(m.get("worst_jump")),
                             num(m.get("ns_per_query"))])
                if m.get("note"):
                    notes.append("- %s: %s" % (label, m["note"]))
                if m.get("skipped"):
                    self.not_run.append(("%s, %s" % (scene.get("name"), label), m["skipped"]))
            rows.append(["reference (baked at each point)", "-", "-", "0", "0", "0",
                         num(path.get("reference_worst_jump")), "-"])
            out += table([("method", "<"), ("probes", ">"), ("bytes", ">"), ("RMS error", ">"),
                          ("max error", ">"), ("RMS error on the path", ">"), ("worst jump along the path", ">"),
                          ("ns/query", ">")], rows)
            out += [""] + notes + ([""] if notes else [])
            out += self.plot("methods_error_vs_time", scene) + [""]
            out += self.plot("slices", scene) + [""]
            out += self.plot("popping", scene) + [""]
        return out

    # ---- 2. precision, layout, SH order

    def precision(self):
        out = ["## 2. Precision, layout and SH order", ""]
        doc = self.docs.get("precision")
        if doc is None:
            return out + not_run(self.missing["precision"]) + [""]
        if doc.get("rule"):
            out += ["Winner rule: %s" % doc["rule"], ""]
        if doc.get("sh_options"):
            out += ["SH evaluation: %s" % doc["sh_options"], ""]
        for scene in doc.get("scenes", []):
            out += ["### %s" % scene.get("name", "?"), ""]
            rows = [[r.get("precision"), r.get("layout"), r.get("order"), r.get("window"), num(r.get("rms_error")),
                     num(r.get("max_error")), num(r.get("negative_fraction")), num(r.get("ns_per_query")),
                     num(r.get("bytes_per_probe"))] for r in scene.get("rows", [])]
            out += table([("SH", "<"), ("layout", "<"), ("order", "<"), ("window", "<"), ("RMS error", ">"),
                          ("max error", ">"), ("negative irradiance (fraction)", ">"), ("ns/query", ">"),
                          ("bytes/probe", ">")], rows)
            out.append("")
            for d in scene.get("decisions", []):
                tied = [t for t in d.get("tied", []) if t != d.get("winner")]
                out.append("- %s: **%s** (%s)%s" % (d.get("question"), d.get("winner"), d.get("why", ""),
                                                    "; tied within the noise: " + ", ".join(tied) if tied else ""))
            out.append("")
        return out

    # ---- 3. locate

    def locate(self):
        out = ["## 3. Locate", ""]
        doc = self.docs.get("locate")
        if doc is None:
            return out + not_run(self.missing["locate"]) + [""]
        for peer, why in (doc.get("peers_not_run") or {}).items():
            self.not_run.append(("locate peer " + peer, why))
            out += not_run("%s: %s" % (peer, why)) + [""]
        scipy = self.docs.get("scipy_locate")
        if scipy is None:
            why = self.missing.get("scipy_locate", "no result")
            self.not_run.append(("locate peer scipy", why))
            out += not_run("scipy find_simplex: " + why) + [""]
        scipy_sizes = {s["probes"]: s for s in (scipy or {}).get("sizes", [])}
        out += ["Random probes in a 10 m box (the 8 corners first); the same probes and points for every method. "
                "coherent: objects moving 0.2%% of the box per frame, each with the hint of its last frame (frame 0 "
                "untimed); cold: uniform random points without a hint, from the start grid (the store's start "
                "structure) or from cell 0 (the inner cell nearest the centre, where a walk without the grid "
                "starts); teleport: the same random points, each with the previous point's cell. tetprobe: "
                "`tp_store_locate` (locate + weights, exact); CGAL: `Delaunay_triangulation_3::locate` (exact "
                "predicates) + weights in double; scipy: `Delaunay.find_simplex` (simplex only, no weights), which "
                "takes no hint: each point's walk starts where the previous point's ended, so its coherent row is "
                "the paths in order (frame 0 included) and its random points are a teleport. Median of %s runs." %
                doc.get("repetitions", "?"), ""]
        for size in doc.get("sizes", []):
            out += ["### %s probes" % num(size["probes"]), ""]
            rows = [[r["method"], r["query"], r["start"], num(r.get("ns_per_query")), num(r.get("mean_steps")),
                     num(r.get("max_steps"))] for r in size["rows"]]
            for r in scipy_sizes.get(size["probes"], {}).get("rows", []):
                rows.append(["scipy", r["query"] + " (one vectorised call)", "the previous point's simplex",
                             num(r["ns_per_query"]), "-", "-"])
                rows.append(["scipy", r["query"] + " (one call per point)", "scipy's own (every call anew)",
                             num(r["ns_per_query_one_call_each"]), "-", "-"])
            out += table([("method", "<"), ("query", "<"), ("start", "<"), ("ns/query", ">"),
                          ("mean steps", ">"), ("max steps", ">")], rows)
            out += ["", "tp_store_interpolate coherent: %s ns; blend-only floor (same probes and weights, no "
                    "search): %s ns." % (num(size.get("interpolate_coherent_ns")), num(size.get("floor_ns"))), ""]
        return out

    # ---- 4. bake

    def bake(self):
        out = ["## 4. Bake", ""]
        doc = self.docs.get("bake")
        if doc is None:
            return out + not_run(self.missing["bake"]) + [""]
        for scene in doc.get("scenes", []):
            ref = scene.get("reference", {})
            out += ["### %s" % scene["scene"], "",
                    "%s probes; plan: %s. Errors are relative RMS against a reference of %s rays and %s bounces; "
                    "noise is the error against a reference of the same bounces." % (
                        num(scene.get("probes")), scene.get("plan", "?"), num(ref.get("rays")),
                        num(ref.get("bounces"))), ""]
            rows = [[num(r["rays"]), num(r["bounces"]),
                     {True: "on", False: "off"}.get(r.get("emitter_sampling"), "-"), num(r["seconds"]),
                     num(r["sh_error"]), num(r["irradiance_error"]), num(r["noise"])] for r in scene["rows"]]
            out += table([("rays/probe", ">"), ("bounces", ">"), ("emitter sampling", ">"),
                          ("bake s (median of 3)", ">"),
                          ("SH error", ">"), ("irradiance error", ">"), ("SH noise", ">")], rows)
            out.append("")
        out += self.plot("bake_error_vs_time", doc) + [""]
        culling = doc.get("culling", [])
        if culling:
            out += ["### Shadow-caster culling (the effects plan's switch), same settings and seed", ""]
            rows = [[c["scene"], "%s / %s" % (num(c["on"]["shadow_casters"]), num(c["off"]["shadow_casters"])),
                     num(c["on"]["seconds"]), num(c["off"]["seconds"]),
                     num(c["off"]["seconds"] / c["on"]["seconds"]) + "x" if c["on"]["seconds"] else "-",
                     num(c["max_abs_difference"]), num(c["identical_bytes"])] for c in culling]
            out += table([("scene", "<"), ("shadow casters on / off", ">"), ("bake s, culling on", ">"),
                          ("bake s, off", ">"), ("off / on", ">"), ("max SH difference", ">"),
                          ("same bytes", ">")], rows)
            same = [c["scene"] for c in culling if c["on"]["shadow_casters"] == c["off"]["shadow_casters"]]
            out += ["", "Wall time of the whole bake, median of %s runs with culling on and off interleaved. "
                    "Culling removes shadow casters from the occlusion sets of the probes' direct shadow rays (one "
                    "per light per probe) and builds one ray-casting scene per shadowing light for them; the "
                    "sampled sphere (sky, emission, bounces) traces the whole scene either way." % (
                        culling[0].get("repetitions", "?"))]
            if same:
                out[-1] += (" Where the plan culls nothing (%s) both bakes do the same work, so their difference "
                            "is this machine's noise." % ", ".join(same))
            out.append("")
        else:
            out += not_run("culling comparison: bake.json has none") + [""]
        return out

    # ---- 5. probe count

    def probe_count(self):
        out = ["## 5. Probe count", ""]
        doc = self.docs.get("probes")
        if doc is None:
            return out + not_run(self.missing["probes"]) + [""]
        noise = doc.get("noise_floor", {})
        out += ["%s: a grid of probes over the bounds of the scene's own probes, the spacing halved per level, "
                "baked (%s rays, %s bounces) and built into a tetrahedral store; error of the interpolated "
                "irradiance (six axis normals, relative RMS) at %s fixed random points against a bake directly "
                "at those points. Noise floor (a second direct bake, another seed): %s." % (
                    doc.get("scene"), num(doc.get("rays")), num(doc.get("bounces")), num(doc.get("query_points")),
                    num(noise.get("rms_error"))), ""]
        rows = [[num(l["probes"]), " x ".join(num(s) for s in l["spacing"]), num(l["rms_error"]),
                 num(l["max_error"]), num(l["fast_bytes"]), num(l["compact_bytes"]), num(l["bake_seconds"])]
                for l in doc.get("levels", [])]
        out += table([("probes", ">"), ("spacing (m)", ">"), ("RMS error", ">"), ("max error / RMS", ">"),
                      ("fast bytes", ">"), ("compact bytes", ">"), ("bake s", ">")], rows)
        out += [""] + self.plot("probe_convergence", doc) + [""]
        return out

    # ---- 6. leak control

    def leak(self):
        out = ["## 6. Leak control", ""]
        doc = self.docs.get("leak")
        if doc is None:
            return out + not_run(self.missing["leak"]) + [""]
        out += ["%s: %s probes baked (%s rays, %s bounces), one store built without and one with the scene "
                "(leak control: %s blocked probe pairs). Irradiance (mean over directions) along paths across the "
                "dividing wall (points inside the wall left out), against a bake at the path points themselves; leak error = sum |store - "
                "reference| / sum reference along the path. Cost: cold batch queries (no hint), the least of "
                "three medians." % (doc.get("scene"), num(doc.get("probes")), num(doc.get("rays")),
                                    num(doc.get("bounces")), num(doc.get("leak_edges"))), ""]
        out += table([("path", "<"), ("leak error without", ">"), ("with leak control", ">")], leak_rows(doc))
        out.append("")
        out += table([("cost per query", "<"), ("ns without", ">"), ("ns with", ">"), ("with / without", ">")],
                     leak_cost_rows(doc))
        bytes_ = doc.get("store_bytes", {})
        out += ["", "Store bytes: %s without, %s with leak control." % (num(bytes_.get("without")),
                                                                         num(bytes_.get("with"))), ""]
        out += self.plot("leak_path", doc) + [""]
        return out

    # ---- 7. placement

    def placement(self):
        out = ["## 7. Probe placement", ""]
        doc = self.docs.get("placement")
        if doc is None:
            return out + not_run(self.missing["placement"]) + [""]
        out += ["%s: `tetprobe.place_probes` from %s candidates (spacing %s m, %s rays), chosen up to a target. "
                "Left of the plot: the placement's own error curve (its estimate of the luminance irradiance's "
                "interpolation error at validation points, low-sample). Table and right: the placed probes, a "
                "uniform subsample of the same candidates and the scene's hand-placed probes, each baked at %s "
                "rays, judged at %s random free points against a bake there (mean relative irradiance "
                "error)." % (doc.get("scene"), num(doc.get("candidates")), num(doc.get("spacing")),
                             num(doc.get("placement_rays")), num(doc.get("reference_rays")),
                             num(doc.get("query_points"))), ""]
        out += table([("probes", ">"), ("placed", ">"), ("uniform subsample", ">"), ("placement s", ">")],
                     placement_rows(doc))
        out += [""] + self.plot("placement_error", doc) + [""]
        return out

    # ---- 8. headline ratios

    def ratios(self):
        """Rows of (ratio, value text, source) computed from the parts that ran."""
        rows = []
        locate = self.docs.get("locate")
        if locate:
            for size in locate.get("sizes", []):
                n = num(size["probes"])
                if size.get("floor_ns"):
                    rows.append(("our query / floor (interpolate coherent / blend only), %s probes" % n,
                                 num(size["interpolate_coherent_ns"] / size["floor_ns"]) + "x", "locate.json"))
                by = {(r["method"], r["query"], r["start"]): r for r in size["rows"]}
                ours = by.get(("tetprobe", "coherent", "hint of the last frame"), {}).get("ns_per_query")
                cgal = by.get(("CGAL", "coherent", "hint of the last frame"), {}).get("ns_per_query")
                if ours and cgal:
                    rows.append(("CGAL / ours, coherent locate, %s probes" % n, num(cgal / ours) + "x", "locate.json"))
                grid = by.get(("tetprobe", "cold", "start grid"), {}).get("ns_per_query")
                no_grid = by.get(("tetprobe", "cold", "cell 0 (no grid)"), {}).get("ns_per_query")
                if grid and no_grid:
                    rows.append(("cold without / with the start grid, %s probes" % n, num(no_grid / grid) + "x",
                                 "locate.json"))
        methods = self.docs.get("methods")
        if methods:
            for scene in methods.get("scenes", []):
                by = {m["id"]: m for m in scene.get("methods", [])}
                ours, grid = by.get("tetrahedral_fast", {}), by.get("grid_equal_memory", {})
                if ours.get("rms_error") and grid.get("rms_error") is not None:
                    rows.append(("grid error / ours at equal memory (RMS), %s" % scene.get("name"),
                                 num(grid["rms_error"] / ours["rms_error"]) + "x", "methods.json"))
        levels = self.docs.get("levels")
        for level in (levels or {}).get("levels", []):
            rows_of_level = [r for r in report_levels.equal_memory(level) if r["layout"] == "compact" and r["ratio_placed"]]
            if rows_of_level:
                r = rows_of_level[-1]
                rows.append(("best grid peer / tetprobe placed at equal memory (RMS), %s, %s probes, compact" % (
                    level["name"], num(r["target"])), num(r["ratio_placed"]) + "x", "levels.json"))
            at_bytes = [r for r in report_levels.best_layout_rows(level) if r["ratio"]]
            if at_bytes:
                r = at_bytes[-1]
                rows.append(("best grid peer / tetprobe's best layout at equal memory (RMS), %s, %s bytes (%s)" % (
                    level["name"], num(r["bytes"]), r["best"]["layout"]), num(r["ratio"]) + "x", "levels.json"))
        bake = self.docs.get("bake")
        if bake:
            for c in bake.get("culling", []):
                # Only where the plan culls something: elsewhere both bakes are the same work.
                if c["on"]["seconds"] and c["on"]["shadow_casters"] < c["off"]["shadow_casters"]:
                    rows.append(("bake time saved by culling (off / on), %s" % c["scene"],
                                 num(c["off"]["seconds"] / c["on"]["seconds"]) + "x, result %s" % (
                                     "identical" if c["identical_bytes"] else
                                     "max difference %s" % num(c["max_abs_difference"])), "bake.json"))
        return rows

    def headline(self):
        out = ["## 8. Headline ratios", ""]
        rows = self.ratios()
        if not rows:
            return out + not_run("no part that the ratios come from ran") + [""]
        out += table([("ratio", "<"), ("this run", ">"), ("from", "<")], rows)
        return out + [""]

    def store(self):
        path = os.path.join(self.directory, "store.md")
        if not os.path.exists(path):
            self.not_run.append(("tetprobe_bench store", "store.md is missing"))
            return ["## Store benchmark", ""] + not_run("store.md is missing (tetprobe_bench store did not run)")
        with open(path) as f:
            text = f.read().strip()
        return ["## Store benchmark (tetprobe_bench store, as printed)", "",
                text.replace("\n## Store benchmark\n", "\n").replace("## Store benchmark\n", "", 1), ""]

    def machine(self):
        for part in ("levels", "methods", "locate", "bake", "probes"):
            m = (self.docs.get(part) or {}).get("machine")
            if m:
                return ["Machine: %s, %s hardware threads; 1-minute load average at the %s part: %s.%s" % (
                    m.get("cpu"), m.get("threads"), part, m.get("load_average"),
                    " **Quick run (smoke sizes): the numbers are not meaningful.**" if m.get("quick") else ""), ""]
        return []

    def markdown(self):
        body = []
        for section in (self.real_levels, self.levels_placement, self.methods, self.precision, self.locate, self.bake, self.probe_count, self.leak,
                        self.placement, self.headline, self.store):
            body += section()
        out = ["# tetprobe benchmark report", "",
               "Written by `samples/bench/report.py` from `make bench`. Ratios within one run are the result; "
               "absolute times move with the machine's load.", ""] + self.machine()
        out += ["Not run in this report:" if self.not_run else "Every part and peer ran.", ""]
        out += ["- %s: %s" % (what, why) for what, why in self.not_run]
        return "\n".join(out + [""] + body).rstrip() + "\n"


def leak_rows(doc):
    return [[p.get("name"), num(p["leak_error"]["without"]), num(p["leak_error"]["with"])]
            for p in doc.get("paths", [])]


def leak_cost_rows(doc):
    rows = []
    for key, label in (("rooms", "uniform in the rooms"), ("wall", "within 0.6 m of the wall")):
        cost = doc.get("cost_ns_per_query", {}).get(key)
        if cost:
            rows.append([label, num(cost["without"]), num(cost["with"]),
                         num(cost["with"] / cost["without"]) + "x" if cost["without"] else "-"])
    return rows


def placement_rows(doc):
    rows = [["%s of %s" % (num(c["probes"]), num(doc.get("candidates"))), num(c["placed"]), num(c["uniform"]),
             num(c.get("placement_seconds"))] for c in doc.get("comparison", [])]
    hand = doc.get("hand_placed")
    if hand:
        rows.append(["%s hand-placed" % num(hand["probes"]), "-", "-", "-"] if hand.get("error") is None else
                    ["%s hand-placed" % num(hand["probes"]), num(hand["error"]), "-", "-"])
    return rows


def readme_section(report, images="docs/bench/"):
    """The README's digest of a report: the headline ratios and the key tables, images from `images`."""
    out = ["Machine: " + report.machine()[0].split("Machine: ", 1)[1] if report.machine() else "", ""]
    levels = report.docs.get("levels")
    if levels:
        out += ["**Real levels** (Quake 3 arenas of Debian's openarena-081-maps; RMS and 95th-percentile luminance "
                "irradiance error over 6 normals at free points of the playable space against a %s-ray reference, "
                "relative to the level's mean; peers built at the same bytes as tetprobe's compact store; ratio > 1: "
                "tetprobe has less error)" % levels.get("settings", {}).get("reference_rays", "?"), ""]
        out += table(report_levels.SUMMARY_HEADER, report_levels.summary_rows(levels)) + [""]
        out += ["![%s](%slevels_error_vs_bytes_%s.png)" % (l["name"], images, report_plots._slug(l["name"]))
                for l in levels.get("levels", []) if not l.get("not_run")] + [""]
    placed = report.docs.get("levels_placement")
    if placed:
        out += ["**Placement on the real levels** (placed against a random subsample and the uniform lattice pick of "
                "the same candidates at %s probes, compact layout; counts of the level's budgets that meet each "
                "requirement; in brackets the error of all candidates without and with leak control)" %
                " / ".join(str(c) for c in placed.get("settings", {}).get("counts", [])), ""]
        out += table(report_placement_levels.SUMMARY_HEADER, report_placement_levels.summary_rows(placed)) + [""]
        out += ["![%s](%slevels_placement_%s.png)" % (l["name"], images, report_plots._slug(l["name"]))
                for l in placed.get("levels", []) if not l.get("not_run")] + [""]
    ratios = report.ratios()
    if ratios:
        out += ["**Headline ratios**", ""] + table([("ratio", "<"), ("this run", ">")],
                                                  [(r, v) for r, v, _ in ratios]) + [""]
    methods = report.docs.get("methods")
    for scene in (methods or {}).get("scenes", [])[:1]:
        out += ["**Interpolation methods, %s** (error against a bake at every query point, relative to the mean "
                "irradiance; popping: worst frame-to-frame jump along a path)" % scene.get("name"), ""]
        rows = [[m.get("label", m.get("id")), num(m.get("bytes")), num(m.get("rms_error")), num(m.get("max_error")),
                 num(m.get("worst_jump")), num(m.get("ns_per_query"))] for m in scene.get("methods", [])]
        out += table([("method", "<"), ("bytes", ">"), ("RMS error", ">"), ("max error", ">"),
                      ("worst jump", ">"), ("ns/query", ">")], rows) + [""]
        slug = report_plots._slug(scene.get("name"))
        out += ["![error vs time](%smethods_error_vs_time_%s.png) ![popping](%spopping_%s.png)" % (
            images, slug, images, slug), "", "![slices](%sslices_%s.png)" % (images, slug), ""]
    locate = report.docs.get("locate")
    if locate:
        sizes = locate.get("sizes", [])
        scipy = {s["probes"]: s for s in (report.docs.get("scipy_locate") or {}).get("sizes", [])}
        keys = []
        for size in sizes:
            for r in size["rows"]:
                if (r["method"], r["query"], r["start"]) not in keys:
                    keys.append((r["method"], r["query"], r["start"]))
        rows = []
        for key in keys:
            cells = []
            for size in sizes:
                match = [r for r in size["rows"] if (r["method"], r["query"], r["start"]) == key]
                cells.append("%s (%s steps)" % (num(match[0]["ns_per_query"]), num(match[0]["mean_steps"]))
                             if match and match[0].get("mean_steps") is not None
                             else num(match[0]["ns_per_query"]) if match else "-")
            rows.append(["%s %s, start: %s" % key] + cells)
        for query in ("coherent", "teleport"):
            cells = []
            for size in sizes:
                match = [r for r in scipy.get(size["probes"], {}).get("rows", []) if r["query"] == query]
                cells.append(num(match[0]["ns_per_query"]) if match else "-")
            rows.append(["scipy find_simplex %s, one vectorised call" % query] + cells)
        out += ["**Locate** (ns per query, mean walk steps; random probes in a 10 m box)", ""]
        out += table([("method, query", "<")] + [("%s probes" % num(s["probes"]), ">") for s in sizes], rows) + [""]
    bake = report.docs.get("bake")
    if bake:
        out += ["**Bake**: SH error against a high-sample reference vs bake time, one curve per bounce count "
                "(dashed: emitter sampling off)", "", "![bake](%sbake_error_vs_time.png)" % images, ""]
        rows = [[os.path.basename(c["scene"]), "%s / %s" % (num(c["on"]["shadow_casters"]),
                                                            num(c["off"]["shadow_casters"])),
                 num(c["on"]["seconds"]), num(c["off"]["seconds"]), num(c["max_abs_difference"]),
                 num(c["identical_bytes"])] for c in bake.get("culling", [])]
        out += table([("culling", "<"), ("shadow casters on / off", ">"), ("bake s, on", ">"), ("bake s, off", ">"),
                      ("max SH difference", ">"), ("same bytes", ">")], rows) + [""]
    probes = report.docs.get("probes")
    if probes:
        out += ["**Probe count** (%s, grid of probes, spacing halved; noise floor %s)" % (
            os.path.basename(str(probes.get("scene"))), num(probes.get("noise_floor", {}).get("rms_error"))), ""]
        rows = [[num(l["probes"]), num(l["spacing"][0]), num(l["rms_error"]), num(l["fast_bytes"]),
                 num(l["compact_bytes"])] for l in probes.get("levels", [])]
        out += table([("probes", ">"), ("spacing x (m)", ">"), ("RMS error", ">"), ("fast bytes", ">"),
                      ("compact bytes", ">")], rows)
        out += ["", "![probe count](%sprobe_convergence.png)" % images, ""]
    out += readme_leak_and_placement(report, images)
    if report.not_run:
        out += ["Not run in this report: " + "; ".join("%s (%s)" % (w, y) for w, y in report.not_run) + ".", ""]
    return "\n".join(out).rstrip() + "\n"


def readme_leak_and_placement(report, images="docs/bench/"):
    """The README's short tables of leak control and placement (each only when its part ran)."""
    out = []
    leak = report.docs.get("leak")
    if leak:
        out += ["**Leak control** (two rooms: irradiance along paths across the wall against a bake there; "
                "leak error = sum |store - reference| / sum reference)", ""]
        out += table([("path", "<"), ("leak error without", ">"), ("with leak control", ">")], leak_rows(leak))
        out += [""] + table([("cost per query (cold)", "<"), ("ns without", ">"), ("ns with", ">"),
                             ("with / without", ">")], leak_cost_rows(leak))
        out += ["", "![leak control](%sleak_path.png)" % images, ""]
    placement = report.docs.get("placement")
    if placement:
        out += ["**Probe placement** (two rooms, %s candidates; mean relative irradiance error against a bake "
                "at %s free points)" % (num(placement.get("candidates")), num(placement.get("query_points"))), ""]
        out += table([("probes", ">"), ("placed", ">"), ("uniform subsample", ">"), ("placement s", ">")],
                     placement_rows(placement))
        out += ["", "![placement](%splacement_error.png)" % images, ""]
    return out


def main(argv):
    if len(argv) != 2:
        print("usage: report.py DIR", file=sys.stderr)
        return 2
    report = Report(argv[1])
    text = report.markdown()
    path = os.path.join(argv[1], "report.md")
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    with open(os.path.join(argv[1], "readme_section.md"), "w") as f:
        f.write(readme_section(report))
    print("report: %s (%d plots; not run: %d)" % (path, len(report.plots.written), len(report.not_run)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
