"""The real-level placement part of the benchmark report: levels_placement.json (tetprobe_bench levels placement)
-> markdown tables, and the requirement checks they show.

Per level and probe count: the placed set's error next to a random subsample's (mean of 3) and the uniform lattice
pick's of the same candidates, with leak control, and the error placement reports for that count; all candidates as
the floor. The checks: placed <= 0.8 x random and <= lattice, reported within +-30 % of measured, leak control's
error <= the error without. report_plots.levels_placement draws the curves.
"""

RANDOM_FACTOR = 0.8      # placed must be at most this times the random subsamples' mean
REPORTED_TOLERANCE = 0.3  # the reported error within this share of the measured one

HEADER = [("probes", ">"), ("placed", ">"), ("random (mean of 3)", ">"), ("lattice", ">"), ("placed / random", ">"),
          ("placed / lattice", ">"), ("reported", ">"), ("reported / measured", ">"), ("placed, leak control", ">"),
          ("misses", "<")]
SUMMARY_HEADER = [("level", "<"), ("candidates", ">"), ("placement s (to 4,000)", ">"), ("counts", ">"),
                  ("placed <= 0.8 x random", ">"), ("placed <= lattice", ">"), ("reported within 30 %", ">"),
                  ("leak control <= without", ">"), ("all candidates (leak control)", ">")]


def _num(value, digits=3):
    if value is None or value != value:
        return "-"
    if isinstance(value, int):
        return "{:,}".format(value)
    return "%.*g" % (digits, value)


def _table(header, rows):
    lines = ["| " + " | ".join(t for t, _ in header) + " |",
             "| " + " | ".join("---:" if a == ">" else "---" for _, a in header) + " |"]
    return lines + ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]


def misses(row):
    """The requirements one count of one level misses, as short words (empty: none)."""
    out = []
    placed = row["placed"]
    if placed > RANDOM_FACTOR * row["random"]:
        out.append("random")
    if placed > row["lattice"]:
        out.append("lattice")
    reported = row.get("reported")
    if reported is None or abs(reported / placed - 1) > REPORTED_TOLERANCE:
        out.append("reported")
    if row["placed_leak"] > placed:
        out.append("leak")
    return out


def count_rows(level):
    rows = []
    for r in level.get("counts", []):
        reported = r.get("reported")
        rows.append([_num(r["probes"]), _num(r["placed"]), _num(r["random"]), _num(r["lattice"]),
                     _num(r["placed"] / r["random"]), _num(r["placed"] / r["lattice"]), _num(reported),
                     _num(reported / r["placed"] if reported is not None else None), _num(r["placed_leak"]),
                     ", ".join(misses(r)) or "none"])
    every = level.get("all", {})
    rows.append(["all %s" % _num(level.get("candidates")), _num(every.get("rms")), "", "", "", "", "", "",
                 _num(every.get("rms_leak")), "leak" if every.get("rms_leak", 0) > every.get("rms", 0) else "none"])
    return rows


def summary_rows(doc):
    rows = []
    for level in doc.get("levels", []):
        if level.get("not_run"):
            rows.append([level.get("name", "?"), "not run: %s" % level["not_run"], "", "", "", "", "", "", ""])
            continue
        counts = level.get("counts", [])
        tally = {"random": 0, "lattice": 0, "reported": 0, "leak": 0}
        for r in counts:
            for m in misses(r):
                tally[m] += 1
        n = len(counts)
        every = level.get("all", {})
        rows.append([level["name"], _num(level.get("candidates")), _num(level.get("placement_seconds")), str(n),
                     "%d of %d" % (n - tally["random"], n), "%d of %d" % (n - tally["lattice"], n),
                     "%d of %d" % (n - tally["reported"], n), "%d of %d" % (n - tally["leak"], n),
                     "%s (%s)" % (_num(every.get("rms")), _num(every.get("rms_leak")))])
    return rows


def level_section(level, plot_lines):
    if level.get("not_run"):
        return ["### %s: not run" % level.get("name", "?"), "", "not run: %s" % level["not_run"], ""]
    out = ["### %s: %s candidates, placement to %s probes in %s s" % (
        level["name"], _num(level.get("candidates")), _num(max([r["probes"] for r in level.get("counts", [])] or [0])),
        _num(level.get("placement_seconds"))), ""]
    out += _table(HEADER, count_rows(level)) + [""]
    return out + plot_lines + [""]
