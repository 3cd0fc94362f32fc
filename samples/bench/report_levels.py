"""The real-level part of the benchmark report: levels.json (tetprobe_bench levels) -> markdown tables.

Per level: what was imported and measured, the summary at equal memory (the best grid peer's error over
tetprobe's at the bytes of each tetprobe layout and probe count), and every method's curve as a table;
report_plots.levels_error_vs_bytes draws the curves. The same summary, all levels in one table, leads the
README's section (summary_rows).
"""

GRID_PEERS = ("grid_half", "grid_apv8", "bricks_apv8")
CHOICES = ("tetprobe_placed", "tetprobe_random", "tetprobe_lattice")
PEER_NAMES = {"grid_half": "grid, half", "grid_apv8": "grid, APV 8-bit", "bricks_apv8": "bricks (VLM)"}
CHOICE_NAMES = {"tetprobe_placed": "placed", "tetprobe_random": "random", "tetprobe_lattice": "lattice"}


def _num(value, digits=3):
    if value is None:
        return "-"
    if isinstance(value, int):
        return "{:,}".format(value)
    if value != value:
        return "-"
    if value != 0 and (abs(value) >= 1e5 or abs(value) < 1e-3):
        return "%.*e" % (digits - 1, value)
    return "%.*g" % (digits, value) if abs(value) < 10 ** digits else "%.0f" % value


def _table(header, rows):
    lines = ["| " + " | ".join(t for t, _ in header) + " |",
             "| " + " | ".join("---:" if a == ">" else "---" for _, a in header) + " |"]
    return lines + ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]


def equal_memory(level):
    """Rows per (layout, target): tetprobe placed, the best tetprobe choice, the best grid peer built at
    the placed store's bytes, and their ratios. Each row is a dict."""
    results = level.get("results", [])
    rows = []
    for placed in [r for r in results if r["method"] == "tetprobe_placed"]:
        layout, target = placed["layout"], placed.get("target")
        budget_of = "tetprobe placed %s %s" % (layout, target)
        peers = [r for r in results if r["method"] in GRID_PEERS and r.get("budget_of") == budget_of]
        choices = [r for r in results if r["method"] in CHOICES and r["layout"] == layout and r.get("target") == target]
        best_peer = min(peers, key=lambda r: r["rms_error"]) if peers else None
        best_choice = min(choices, key=lambda r: r["rms_error"]) if choices else placed
        rows.append({
            "level": level["name"], "layout": layout, "target": target, "bytes": placed["bytes"],
            "resident_bytes": placed.get("resident_bytes"), "placed": placed, "best_choice": best_choice,
            "best_peer": best_peer,
            "ratio_placed": best_peer["rms_error"] / placed["rms_error"] if best_peer and placed["rms_error"] else None,
            "ratio_best": (best_peer["rms_error"] / best_choice["rms_error"]
                           if best_peer and best_choice["rms_error"] else None),
            "ratio_p95": (best_peer["p95_error"] / placed["p95_error"]
                          if best_peer and placed.get("p95_error") else None)})
    return rows


def best_layout_rows(level):
    """Rows per compact budget (the bytes of the compact placed store of each count): every layout holding as
    many probes of one placement order as fit (tetprobe_placed_at_bytes), the best of them, the best grid peer
    built at the same bytes and the ratio. Empty for a run without those results. Each row is a dict."""
    results = level.get("results", [])
    rows = []
    for placed in [r for r in results if r["method"] == "tetprobe_placed" and r["layout"] == "compact"]:
        budget_of = "tetprobe placed compact %s" % placed.get("target")
        fits = [r for r in results if r["method"] == "tetprobe_placed_at_bytes" and r.get("budget_of") == budget_of]
        if not fits:
            continue
        peers = [r for r in results if r["method"] in GRID_PEERS and r.get("budget_of") == budget_of]
        best = min(fits, key=lambda r: r["rms_error"])
        best_peer = min(peers, key=lambda r: r["rms_error"]) if peers else None
        rows.append({"level": level["name"], "budget_of": budget_of, "count": placed.get("target"),
                     "bytes": placed["bytes"], "fits": fits, "best": best, "best_peer": best_peer,
                     "ratio": best_peer["rms_error"] / best["rms_error"] if best_peer and best["rms_error"] else None})
    return rows


def level_title(level):
    """'aggressor (3,271 triangles, 84 light entities + sun)'."""
    return "%s (%s triangles, %s light entities + sun)" % (level["name"], _num(level.get("triangles")),
                                                          _num(level.get("light_entities")))


def summary_rows(doc, layout="compact"):
    """One table row per level and probe count, for the README: the given layout, and tetprobe's best layout
    at the same bytes."""
    out = []
    for level in doc.get("levels", []):
        if level.get("not_run"):
            out.append([level.get("name", "?"), "not run: %s" % level["not_run"]] + ["-"] * 8)
            continue
        best_at = {row["count"]: row for row in best_layout_rows(level)} if layout == "compact" else {}
        for row in equal_memory(level):
            if row["layout"] != layout:
                continue
            peer, choice, placed = row["best_peer"], row["best_choice"], row["placed"]
            at = best_at.get(row["target"])
            out.append([
                level_title(level),
                _num(row["target"]),
                "%s (%s)" % (_num(row["bytes"]), _num(row["resident_bytes"])),
                "%s / %s" % (_num(placed["rms_error"]), _num(placed["p95_error"])),
                "%s %s" % (CHOICE_NAMES.get(choice["method"], choice["method"]), _num(choice["rms_error"])),
                "%s %s / %s" % (PEER_NAMES.get(peer["method"], peer["method"]), _num(peer["rms_error"]),
                                _num(peer["p95_error"])) if peer else "-",
                _num(row["ratio_placed"]) + "x" if row["ratio_placed"] else "-",
                _num(row["ratio_best"]) + "x" if row["ratio_best"] else "-",
                "%s, %s probes, %s" % (at["best"]["layout"], _num(at["best"]["probes"]), _num(at["best"]["rms_error"]))
                if at else "-",
                _num(at["ratio"]) + "x" if at and at["ratio"] else "-"])
    return out


SUMMARY_HEADER = [("level", "<"), ("probes", ">"), ("bytes (resident)", ">"), ("tetprobe placed RMS / p95", ">"),
                  ("best tetprobe choice, RMS", ">"), ("best grid peer, same bytes, RMS / p95", ">"),
                  ("peer / placed", ">"), ("peer / best choice", ">"),
                  ("tetprobe's best layout at these bytes: probes placed, RMS", ">"), ("peer / best layout", ">")]


def level_section(level, settings, plot_lines):
    """Markdown lines of one level."""
    name = level.get("name", "?")
    if level.get("not_run"):
        return ["### %s" % name, "", "**Not run:** %s." % level["not_run"].rstrip("."), ""]
    faces, play, noise = level.get("faces", {}), level.get("playable", {}), level.get("reference_noise", {})
    cand = level.get("candidates", {})
    prep = level.get("prepare_seconds", {})
    out = ["### %s%s" % (name, " (%s)" % level["title"] if level.get("title") else ""), "",
           "%s triangles (%s polygons, %s meshes, %s patches, %s brush-model faces; left out: %s sky, %s nodraw, "
           "%s liquid or fog, %s nonsolid, %s billboards); %s lights (%s light entities, the sun). Playable space: "
           "%s grid points in the walkable band, %s of them free, %s reachable from %s of %s spawn points; box %s to %s. "
           "%s evaluation points, mean irradiance %s, reference noise %s RMS (%s p95) over %s points; %s walking "
           "paths, %s frames. Candidates: %s (spacing %s m), baked in %s s. Space and reference: %s s and %s s%s." % (
               _num(level.get("triangles")), _num(faces.get("polygons")), _num(faces.get("meshes")),
               _num(faces.get("patches")), _num(faces.get("brush_model")), _num(faces.get("sky_left_out")),
               _num(faces.get("nodraw_left_out")), _num(faces.get("liquid_or_fog_left_out")),
               _num(faces.get("nonsolid_left_out")), _num(faces.get("billboards_left_out")), _num(level.get("lights")),
               _num(level.get("light_entities")), _num(play.get("band_points")), _num(play.get("free_points")),
               _num(play.get("reachable_points")), _num(play.get("spawns_used")), _num(play.get("spawns_given")),
               [round(v, 1) for v in play.get("box_min", [])], [round(v, 1) for v in play.get("box_max", [])],
               _num(level.get("points")), _num(level.get("mean_irradiance")), _num(noise.get("rms")),
               _num(noise.get("p95")), _num(noise.get("points")), _num(level.get("paths")),
               _num(level.get("path_frames")), _num(cand.get("count")), _num(cand.get("spacing")),
               _num(cand.get("bake_seconds")), _num(prep.get("space")), _num(prep.get("reference")),
               " (read from the cache of an earlier run)" if prep.get("from_cache") else ""), ""]
    out += ["**At equal memory** (peers built at the bytes of tetprobe's placed store of each layout and count):", ""]
    rows = []
    for row in equal_memory(level):
        peer, choice, placed = row["best_peer"], row["best_choice"], row["placed"]
        rows.append([row["layout"], _num(row["target"]), _num(row["bytes"]), _num(placed["rms_error"]),
                     _num(placed["p95_error"]),
                     "%s %s" % (CHOICE_NAMES.get(choice["method"], choice["method"]), _num(choice["rms_error"])),
                     "%s %s" % (PEER_NAMES.get(peer["method"], peer["method"]), _num(peer["rms_error"])) if peer else "-",
                     _num(peer["p95_error"]) if peer else "-",
                     _num(row["ratio_placed"]) + "x" if row["ratio_placed"] else "-",
                     _num(row["ratio_p95"]) + "x" if row["ratio_p95"] else "-"])
    out += _table([("layout", "<"), ("probes", ">"), ("bytes", ">"), ("placed RMS", ">"), ("placed p95", ">"),
                   ("best choice", ">"), ("best grid peer", ">"), ("peer p95", ">"), ("peer / placed, RMS", ">"),
                   ("peer / placed, p95", ">")], rows) + [""]
    at_bytes = best_layout_rows(level)
    if at_bytes:
        out += ["**At equal memory, each layout at its best** (at the bytes of the compact placed store of each count, "
                "every layout holds as many probes of one placement order as fit; the best grid peer is the one built "
                "at those bytes):", ""]
        rows = []
        for row in at_bytes:
            for r in row["fits"]:
                rows.append([_num(row["bytes"]), "compact %s" % _num(row["count"]), r["layout"], _num(r["probes"]),
                             _num(r["bytes"]), _num(r.get("resident_bytes")), _num(r["rms_error"]), _num(r["p95_error"]),
                             "%s %s" % (PEER_NAMES.get(row["best_peer"]["method"], row["best_peer"]["method"]),
                                        _num(row["best_peer"]["rms_error"])) if row["best_peer"] else "-",
                             _num(row["best_peer"]["rms_error"] / r["rms_error"]) + "x"
                             if row["best_peer"] and r["rms_error"] else "-"])
        out += _table([("budget bytes", ">"), ("budget of", "<"), ("layout", "<"), ("probes", ">"), ("bytes", ">"),
                       ("resident", ">"), ("RMS", ">"), ("p95", ">"), ("best grid peer", ">"), ("peer / this", ">")],
                      rows) + [""]
    out += plot_lines + [""]
    out += ["Every method (bytes: what ships; resident: in memory after loading; s: placement or validity test, bake, "
            "build):", ""]
    rows = []
    for r in level.get("results", []):
        rows.append([r.get("label", r["method"]), _num(r.get("target")), _num(r.get("probes")), _num(r.get("bytes")),
                     _num(r.get("resident_bytes")), _num(r.get("rms_error")), _num(r.get("p95_error")),
                     _num(r.get("worst_jump")), _num(r.get("ns_per_query")),
                     "%s / %s / %s" % (_num(r.get("placement_seconds")), _num(r.get("bake_seconds")),
                                       _num(r.get("build_seconds"))),
                     r.get("note", "")])
    out += _table([("method", "<"), ("count", ">"), ("probes", ">"), ("bytes", ">"), ("resident", ">"), ("RMS", ">"),
                   ("p95", ">"), ("worst jump", ">"), ("ns/query", ">"), ("s", ">"), ("note", "<")], rows) + [""]
    for s in level.get("skipped", []):
        out.append("- not run: %s at %s: %s" % (s.get("method"), _num(s.get("budget_bytes", s.get("target"))), s.get("why")))
    return out + [""]
