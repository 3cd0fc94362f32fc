"""The report's plots (matplotlib, Agg backend), one method per picture; report.py decides where they go.

Each drawing method takes the part's JSON (or one scene of it), writes DIR/<name>.png and returns
its file name; Plotter.draw turns a missing matplotlib or missing data into a reason instead.
"""
import os
import re
import textwrap


def _slug(text):
    return re.sub(r"[^a-z0-9]+", "_", str(text).lower()).strip("_") or "scene"


class Plotter:
    def __init__(self, directory):
        self.directory = directory
        self.written = []
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError as e:
            self.available, self.why, self.plt = False, "matplotlib not installed (%s)" % e, None
            return
        self.available, self.why, self.plt = True, "", plt

    def draw(self, method, *args):
        """Returns (file name, '') or (None, why not)."""
        if not self.available:
            return None, self.why
        try:
            fig, name = getattr(self, method)(*args)
        except (KeyError, TypeError, ValueError, IndexError) as e:
            return None, "the data for it is incomplete (%s: %s)" % (type(e).__name__, e)
        path = os.path.join(self.directory, name)
        fig.savefig(path, dpi=110, bbox_inches="tight")
        self.plt.close(fig)
        self.written.append(name)
        return name, ""

    # ---- part 1

    def methods_error_vs_time(self, scene):
        plt = self.plt
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        markers = "osD^vP*Xh<>"
        for i, m in enumerate(scene["methods"]):
            if m.get("ns_per_query") is None or m.get("rms_error") is None:
                continue
            ax.scatter(m["ns_per_query"], m["rms_error"], s=48, marker=markers[i % len(markers)],
                       label=m.get("label", m["id"]), zorder=3)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("ns per query (single queries along the path)")
        ax.set_ylabel("RMS irradiance error (relative)")
        ax.set_title("%s: error vs time per query" % scene["name"])
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
        return fig, "methods_error_vs_time_%s.png" % _slug(scene["name"])

    def slices(self, scene):
        plt = self.plt
        import numpy as np
        s = scene["slice"]
        nx, nz = s["nx"], s["nz"]
        images = [("reference (baked at each point)", s["reference"])]
        labels = {m["id"]: m.get("label", m["id"]) for m in scene.get("methods", [])}
        images += [(labels.get(k, k), v) for k, v in s["methods"].items()]
        arrays = [np.asarray(v, dtype=float).reshape(nz, nx) for _, v in images]
        lo = min(float(np.nanmin(a)) for a in arrays)
        hi = max(float(np.nanmax(a)) for a in arrays)
        cols = min(3, len(images))
        rows = (len(images) + cols - 1) // cols
        aspect = (s["z"][1] - s["z"][0]) / max(s["x"][1] - s["x"][0], 1e-9)
        # A long thin slice (a race track) is stretched across to stay readable, and says so.
        stretched = not 0.25 <= aspect <= 4.0
        aspect = min(max(aspect, 0.25), 4.0)
        fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, (4.2 * aspect + 1.2) * rows), squeeze=False,
                                 constrained_layout=True)
        extent = [s["x"][0], s["x"][1], s["z"][0], s["z"][1]]
        shown = None
        for index, (ax, (label, _), a) in enumerate(zip(axes.flat, images, arrays)):
            shown = ax.imshow(a, origin="lower", extent=extent, vmin=lo, vmax=hi, cmap="inferno",
                              aspect="auto" if stretched else "equal")
            ax.set_title(textwrap.fill(label, 34), fontsize=9)
            ax.set_xlabel("x (m)")
            if index % cols == 0:
                ax.set_ylabel("z (m, stretched)" if stretched else "z (m)")
        for ax in list(axes.flat)[len(images):]:
            ax.axis("off")
        bar = fig.colorbar(shown, ax=axes.ravel().tolist(), shrink=0.8)
        bar.set_label("irradiance / scene mean (normal %s)" % (s.get("normal"),))
        fig.suptitle("%s: slice at %s = %.2f m" % (scene["name"], s.get("axis", "y"), s["height"]))
        return fig, "slices_%s.png" % _slug(scene["name"])

    def popping(self, scene):
        plt = self.plt
        fig, ax = plt.subplots(figsize=(7.2, 3.8))
        path = scene["path"]
        ax.plot(path["reference_trace"], color="black", linewidth=2.2, label="reference", zorder=5)
        for m in scene["methods"]:
            if m.get("trace"):
                ax.plot(m["trace"], linewidth=1.1, label=m.get("label", m["id"]))
        ax.set_xlabel("frame along the path")
        ax.set_ylabel("irradiance / scene mean (normal %s)" % (path.get("normal"),))
        ax.set_title("%s: irradiance along a moving object's path (popping)" % scene["name"])
        ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.16))
        ax.grid(True, alpha=0.3)
        return fig, "popping_%s.png" % _slug(scene["name"])

    # ---- part 4

    def bake_error_vs_time(self, doc):
        plt = self.plt
        scenes = doc["scenes"]
        fig, axes = plt.subplots(1, len(scenes), figsize=(5.6 * len(scenes), 4.2), squeeze=False)
        for ax, scene in zip(axes[0], scenes):
            curves = {}
            for r in scene["rows"]:
                curves.setdefault((r["bounces"], r.get("emitter_sampling")), []).append(r)
            colours = {b: "C%d" % i for i, b in enumerate(sorted({b for b, _ in curves}))}
            for (bounces, sampled), rows in sorted(curves.items(), key=lambda kv: (kv[0][0], str(kv[0][1]))):
                rows.sort(key=lambda r: r["rays"])
                label = "%d bounces" % bounces + ("" if sampled is None else
                                                  ", emitter sampling %s" % ("on" if sampled else "off"))
                ax.plot([max(r["seconds"], 1e-4) for r in rows], [r["sh_error"] for r in rows], marker="o",
                        color=colours[bounces], linestyle="--" if sampled is False else "-", label=label)
                for r in rows:
                    ax.annotate(str(r["rays"]), (max(r["seconds"], 1e-4), r["sh_error"]), fontsize=6,
                                textcoords="offset points", xytext=(3, 2))
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("bake time (s); points labelled with rays per probe")
            ax.set_ylabel("SH error vs high-sample reference (relative RMS)")
            ax.set_title(os.path.basename(scene["scene"]))
            ax.legend(fontsize=7)
            ax.grid(True, which="both", alpha=0.3)
        return fig, "bake_error_vs_time.png"

    # ---- part 5

    def probe_convergence(self, doc):
        plt = self.plt
        levels = doc["levels"]
        spacing = [l["spacing"][0] for l in levels]
        fig, (left, right) = plt.subplots(1, 2, figsize=(10.5, 4.0))
        fig.subplots_adjust(wspace=0.3)
        left.plot(spacing, [l["rms_error"] for l in levels], marker="o", label="tetrahedral store (grid of probes)")
        noise = doc.get("noise_floor", {}).get("rms_error")
        if noise is not None:
            left.axhline(noise, color="grey", linestyle=":", label="noise floor (second direct bake)")
        for l, x in zip(levels, spacing):
            left.annotate("%d probes" % l["probes"], (x, l["rms_error"]), fontsize=7, textcoords="offset points",
                          xytext=(4, 3))
        left.set_xscale("log")
        left.set_yscale("log")
        left.invert_xaxis()
        left.set_xlabel("probe spacing along x (m), halved per level")
        left.set_ylabel("RMS irradiance error (relative)")
        left.set_title("%s: error as the spacing halves" % os.path.basename(str(doc.get("scene"))))
        left.legend(fontsize=7, loc="lower left")
        left.grid(True, which="both", alpha=0.3)
        probes = [l["probes"] for l in levels]
        right.plot(probes, [l["fast_bytes"] for l in levels], marker="o", label="fast layout")
        right.plot(probes, [l["compact_bytes"] for l in levels], marker="s", label="compact layout")
        right.set_xscale("log")
        right.set_yscale("log")
        right.set_xlabel("probes")
        right.set_ylabel("store bytes")
        right.set_title("memory")
        right.legend(fontsize=7)
        right.grid(True, which="both", alpha=0.3)
        return fig, "probe_convergence.png"

    # ---- part 6

    def leak_path(self, doc):
        plt = self.plt
        path = doc["paths"][0]
        samples = path["samples"]
        x = [s["x"] for s in samples]
        fig, ax = plt.subplots(figsize=(7.2, 3.8))
        ax.plot(x, [s["reference"] for s in samples], color="black", linewidth=2.2, label="reference (baked there)")
        ax.plot(x, [s["without"] for s in samples], linewidth=1.3,
                label="without leak control (error %.3f)" % path["leak_error"]["without"])
        ax.plot(x, [s["with"] for s in samples], linewidth=1.3,
                label="with leak control (error %.3f)" % path["leak_error"]["with"])
        # The widest gap between samples is the wall, whose inside points the part leaves out.
        gap = max(zip(x, x[1:]), key=lambda pair: pair[1] - pair[0])
        ax.axvspan(gap[0], gap[1], color="grey", alpha=0.4, label="wall (points inside left out)")
        ax.set_xlabel("x (m) along the path %s" % path["name"])
        ax.set_ylabel("irradiance (mean over directions)")
        ax.set_title("%s: irradiance across the wall" % os.path.basename(str(doc.get("scene"))))
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
        ax.grid(True, alpha=0.3)
        return fig, "leak_path.png"

    # ---- part 7

    def placement_error(self, doc):
        plt = self.plt
        curve = doc["error_curve"]
        fig, (left, right) = plt.subplots(1, 2, figsize=(10.5, 4.0))
        fig.subplots_adjust(wspace=0.3)
        left.plot([c[0] for c in curve], [c[1] for c in curve], marker="o", markersize=3)
        left.set_xlabel("probes (chosen among %d candidates)" % doc["candidates"])
        left.set_ylabel("estimated error at validation points (relative)")
        left.set_title("placement's own error curve")
        left.grid(True, alpha=0.3)
        rows = doc["comparison"]
        n = [r["probes"] for r in rows]
        right.plot(n, [r["placed"] for r in rows], marker="o", label="placed")
        right.plot(n, [r["uniform"] for r in rows], marker="s", label="uniform subsample of the candidates")
        hand = doc.get("hand_placed")
        if hand and hand.get("error") is not None:
            right.scatter([hand["probes"]], [hand["error"]], marker="*", s=90, color="black", zorder=3,
                          label="hand-placed")
        right.set_xlabel("probes")
        right.set_ylabel("mean relative irradiance error vs a bake there")
        right.set_title("error against a reference (%d points)" % doc["query_points"])
        right.legend(fontsize=7, loc="lower left")
        right.grid(True, alpha=0.3)
        return fig, "placement_error.png"

    # ---- real levels

    def levels_error_vs_bytes(self, level):
        """Error (RMS, and the 95th percentile) against bytes for every method on one real level."""
        plt = self.plt
        fig, axes = plt.subplots(1, 2, figsize=(11.5, 4.6), sharex=True)
        styles = [  # (method, layout or None, label, line style, marker)
            ("tetprobe_placed", "fast", "tetprobe placed, fast layout", "-", "o"),
            ("tetprobe_placed", "compact", "tetprobe placed, compact layout", "-", "s"),
            ("tetprobe_random", "compact", "tetprobe random subsample, compact (mean of 3)", "--", "v"),
            ("tetprobe_lattice", "compact", "tetprobe lattice pick, compact", "--", "^"),
            ("tetprobe_all", None, "tetprobe all candidates", "", "*"),
            ("grid_half", None, "uniform grid, dilated, half SH", "-", "D"),
            ("grid_apv8", None, "uniform grid, dilated, APV 8-bit L2", "-", "P"),
            ("bricks_apv8", None, "brick grid (Volumetric Lightmap), 8-bit", "-", "X"),
            ("knn4", None, "4 nearest, inverse distance", ":", "<"),
            ("knn4_damped", None, "4 nearest, damped", ":", ">"),
        ]
        results = level["results"]
        for ax, key, title in ((axes[0], "rms_error", "RMS"), (axes[1], "p95_error", "95th percentile")):
            for method, layout, label, line, marker in styles:
                points = sorted((r["bytes"], r[key]) for r in results
                                if r["method"] == method and (layout is None or r["layout"] == layout)
                                and r.get(key) is not None)
                if points:
                    ax.plot([p[0] for p in points], [p[1] for p in points], linestyle=line or "none", marker=marker,
                            markersize=5, label=label)
            noise = level.get("reference_noise", {}).get("rms" if key == "rms_error" else "p95")
            if noise:
                ax.axhline(noise, color="grey", linestyle=":", linewidth=1, label="reference noise")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("bytes (what ships)")
            ax.set_ylabel("%s luminance irradiance error / level mean" % title)
            ax.set_title("%s: %s error vs memory" % (level["name"], title))
            ax.grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=7, loc="upper center", bbox_to_anchor=(1.1, -0.14), ncol=4)
        return fig, "levels_error_vs_bytes_%s.png" % _slug(level["name"])

    def levels_placement(self, level):
        """Error against probe count on one real level: placed, random, lattice and all candidates, and the
        error placement reports (its curve)."""
        plt = self.plt
        fig, ax = plt.subplots(figsize=(7.5, 4.6))
        counts = level["counts"]
        probes = [r["probes"] for r in counts]
        for key, label, line, marker in (("placed", "placed", "-", "o"), ("placed_leak", "placed, leak control", "-", "."),
                                         ("random", "random subsample (mean of 3)", "--", "v"),
                                         ("lattice", "uniform lattice pick", "--", "^")):
            ax.plot(probes, [r[key] for r in counts], linestyle=line, marker=marker, markersize=5, label=label)
        curve = level.get("curve", [])
        if curve:
            ax.plot([c[0] for c in curve], [c[1] for c in curve], color="grey", linestyle=":", linewidth=1.2,
                    label="error placement reports (its curve)")
        every = level.get("all", {})
        if every.get("rms") is not None:
            ax.axhline(every["rms"], color="black", linestyle="-.", linewidth=1,
                       label="all %s candidates" % "{:,}".format(level.get("candidates", 0)))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("probes")
        ax.set_ylabel("RMS luminance irradiance error / level mean")
        ax.set_title("%s: placement against simpler choices of the same candidates" % level["name"])
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        return fig, "levels_placement_%s.png" % _slug(level["name"])
