#!/usr/bin/python3
"""Draws DIR/<case>.png from DIR/<case>.csv (loa-bench's results) with matplotlib.

Per case: (top) grouped horizontal bars of each configuration's median frame time as a ratio to
the case's baseline measured in the same run (one bar per size or group, the baseline's own bar
at 1); (bottom, where the error column varies) frame time against error with the Pareto front
(no other row both faster and more accurate) marked. transitions has its own baseline: the mean
of the two homogeneous styles of the same scene, camera and size.
Usage: scripts/charts.py [DIR] [CASE...]"""
import csv
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FormatStrFormatter  # noqa: E402

SIZE = re.compile(r"\b(\d+x\d+)\b")
NOISE = re.compile(r"\s*\b(frame=\S+|passes=\S+|shared=\S+|fused=\S+|transition=\S+|abuffer_draws=\S+|"
                   r"pingpong_draws=\S+|abuffer_passes=\S+|lost=\S+|\d+(\.\d+)? MiB|truncated)")


def rows_of(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["ms"] = float(r["median_ms"])
        try:
            r["err"] = float(r["error_mean"]) if r["error_mean"] != "" else None
        except ValueError:
            r["err"] = None
    return rows


MEASURED = re.compile(r"^[\w-]*(ms|fps|mib|texels|bytes|draws|passes|tiles|lost|frame)(_\w+)?=|^[\w-]+=-?\d+\.\d+$",
                      re.IGNORECASE)


def key_of(params):
    """The configuration without its size and what was measured (times, counts, sizes in MiB,
    decimal values): rows of one key differ by size."""
    tokens = NOISE.sub("", SIZE.sub("", params)).split()
    return " ".join(t for t in tokens if not MEASURED.search(t))


def short(text, n=70):
    return text if len(text) <= n else text[: n - 1] + "…"


def group_of(params):
    m = SIZE.search(params)
    return m.group(1) if m else "all"


def baseline_ratios(name, rows):
    """{(label, group): ratio} and a description of the baseline."""
    ratios = {}
    if name == "transitions":
        views = {}
        for r in rows:
            p = r["parameters"]
            get = lambda k, d="": (re.search(k + r"=(\S+)", p) or [None, d])[1]
            view = (group_of(p), get("scene", "demo-city"), get("camera"))
            views.setdefault(view, []).append((get("scenario"), get("fuse"), r["ms"]))
        for (size, scene, camera), entries in views.items():
            homog = [ms for sc, fz, ms in entries if sc.startswith("homogeneous-")]
            if len(homog) < 2:
                continue
            h = sum(homog) / len(homog)
            for sc, fz, ms in entries:
                if sc.startswith("homogeneous-"):
                    continue
                label = "%s %s %s%s" % (scene, camera, sc, "" if not fz else " fuse=" + fz)
                ratios[(label, size)] = ms / h
        return ratios, "mean of homogeneous photorealistic and cartographic (same scene, camera, size, run)"
    if name == "cartographic":
        # Each device against flat cartographic of the same scene, camera and size (same run).
        flat = {}
        for r in rows:
            p = r["parameters"]
            get = lambda k: re.search(k + r"=(\S+)", p).group(1)
            view = (group_of(p), get("scene"), get("camera"))
            r["_view"], r["_style"] = view, get("style")
            if r["_style"] == "cartographic":
                flat[view] = r["ms"]
        for r in rows:
            if r["_style"] != "cartographic" and r["_view"] in flat:
                size, scene, camera = r["_view"]
                ratios[("%s %s %s" % (scene, camera, r["_style"]), size)] = r["ms"] / flat[r["_view"]]
        return ratios, "flat cartographic (same scene, camera, size, run)"
    if name == "abuffer":
        # Per depth complexity K: each method against the default (stencil-routed, N=4, 4 passes)
        # at the same K; the scatter uses these ratios too.
        base = "method=stencil-routed N=4 max=4"
        at = {}
        for r in rows:
            p = r["parameters"]
            k = re.search(r"\bK=(\d+)", p).group(1)
            label = " ".join(t for t in key_of(p).split() if not t.startswith("K="))
            at.setdefault(k, {})[label] = r["ms"]
            r["ratio"] = None
            r["_k"], r["_label"] = k, label
        for r in rows:
            if base in at[r["_k"]]:
                r["ratio"] = r["ms"] / at[r["_k"]][base]
            shown = r["_label"].startswith("method=stencil-routed N=4") or not r["_label"].startswith(
                "method=stencil-routed")
            if shown and r["ratio"] is not None:
                ratios[(r["_label"], "K=" + r["_k"])] = r["ratio"]
        return ratios, base + " at the same K (depth complexity)"
    # Generic: the first row of each group (size) is the baseline.
    first = {}
    for r in rows:
        g = group_of(r["parameters"])
        first.setdefault(g, r)
    for r in rows:
        g = group_of(r["parameters"])
        ratios[(key_of(r["parameters"]) or "(baseline)", g)] = r["ms"] / first[g]["ms"]
    base = sorted(set(key_of(r["parameters"]) for r in first.values()))
    return ratios, "first row of each size: " + "; ".join(b or "(baseline)" for b in base)


def method_of(params):
    m = re.match(r"(\w[\w-]*)=(\S+)", params)
    if m and m.group(1) in ("method", "filter", "setup", "style", "scenario", "linkage", "samples", "mode"):
        return m.group(2)
    return key_of(params).split(" ")[0] if key_of(params) else "row"


def pareto(points):
    """Indices of the points no other point dominates (lower time and lower error)."""
    front = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for t2, e2 in points):
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def save(fig, out):
    """Lays the figure out and writes it atomically (a temporary file, then a rename)."""
    with __import__("warnings").catch_warnings():
        __import__("warnings").simplefilter("ignore")
        fig.tight_layout()
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=90)
    plt.close(fig)
    os.replace(tmp, out)
    return True


def draw_saliency(rows, out):
    """Paper 004 Figure 10 as a number: per scene and size, each scenario's share of the saliency
    mass inside its region of interest, photorealistic against the scenario, and the region's area."""
    machine = rows[0]["machine"]
    get = lambda p, k: re.search(k + r"=(\S+)", p).group(1)
    panels = list(dict.fromkeys((get(r["parameters"], "scene"), group_of(r["parameters"])) for r in rows))
    fig, axes = plt.subplots(len(panels), 1, figsize=(11, 3.2 * len(panels)), squeeze=False)
    for ax, (scene, size) in zip(axes[:, 0], panels):
        sel = [r for r in rows if get(r["parameters"], "scene") == scene and group_of(r["parameters"]) == size]
        names = [get(r["parameters"], "scenario") for r in sel]
        ys = range(len(sel))
        area = [float(get(r["parameters"], "roi_area")) for r in sel]
        photo = [float(get(r["parameters"], "share_photorealistic")) for r in sel]
        loa = [float(get(r["parameters"], "share_scenario")) for r in sel]
        ax.barh([y - 0.27 for y in ys], area, height=0.25, color="#d9d9d9", label="region's share of the frame")
        ax.barh([y for y in ys], photo, height=0.25, color="#80b1d3", label="saliency inside, photorealistic")
        ax.barh([y + 0.27 for y in ys], loa, height=0.25, color="#fb8072", label="saliency inside, the scenario")
        for y, a, b in zip(ys, photo, loa):
            ax.text(max(a, b), y + 0.27, "  x%.2f" % (b / a if a > 0 else 0), va="center", fontsize=7)
        ax.set_yticks(list(ys))
        ax.set_yticklabels(names, fontsize=8)
        ax.invert_yaxis()
        ax.set_xlim(0, 1)
        ax.set_title("%s %s" % (scene, size), fontsize=9)
        ax.grid(axis="x", alpha=0.3)
    axes[0, 0].legend(fontsize=7, loc="lower right")
    axes[-1, 0].set_xlabel("share (spectral-residual saliency mass inside the region of interest; x = scenario / photorealistic)")
    fig.suptitle("saliency: paper 004 Figure 10 as a number\n%s" % machine, fontsize=9)
    return save(fig, out)


def draw_viewer(rows, out):
    """loa-viewer's edit-to-frame latency against the scene's feature count, one line per edit,
    and the same latency as a ratio to a full re-bind of the same fade edit (same run)."""
    machine = rows[0]["machine"]
    get = lambda p, k: re.search(k + r"=(\S+)", p).group(1)
    edits = list(dict.fromkeys(get(r["parameters"], "edit") for r in rows))
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(11, 9))
    for e in edits:
        sel = sorted((int(get(r["parameters"], "features")), r["ms"], get(r["parameters"], "scene"))
                     for r in rows if get(r["parameters"], "edit") == e)
        label = "frame alone (no edit)" if e == "none" else e
        ax.plot([p[0] for p in sel], [p[1] for p in sel], marker="o", label=label,
                ls="--" if e in ("none", "full-rebind") else "-")
    scenes = sorted(set((int(get(r["parameters"], "features")), get(r["parameters"], "scene")) for r in rows))
    for n, sc in scenes:
        ax.annotate(sc, (n, ax.get_ylim()[0]), fontsize=6, rotation=90, va="bottom", ha="right")
    ax.set_xscale("log")
    ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.set_xlabel("features in the scene (log)")
    ax.set_ylabel("edit + one finished frame, median (ms)")
    errs = [r["err"] for r in rows if r["err"] is not None]
    ax.set_title("viewer: edit-to-frame latency at 1280x720 against scene size\n"
                 "largest difference of a frame after an edit to the frame after a full re-bind: %g (8-bit units)\n%s"
                 % (max(errs) if errs else 0, machine), fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    names = [sc for _, sc in scenes]
    kinds = [e for e in edits if e not in ("none", "full-rebind")]
    bar = 0.8 / max(1, len(kinds))
    for ki, k in enumerate(kinds):
        xs, ys = [], []
        for si, sc in enumerate(names):
            for r in rows:
                if get(r["parameters"], "scene") == sc and get(r["parameters"], "edit") == k:
                    xs.append(si + ki * bar)
                    ys.append(float(get(r["parameters"], "ratio_to_rebind")))
        ax2.bar(xs, ys, width=bar, label=k)
    ax2.axhline(1.0, color="black", lw=0.8)
    ax2.set_xticks([i + bar * (len(kinds) - 1) / 2 for i in range(len(names))])
    ax2.set_xticklabels(names, fontsize=8)
    ax2.set_ylabel("latency / the fade edit with a full re-bind")
    ax2.set_title("each edit against a full re-bind (same scene, same run)", fontsize=9)
    ax2.legend(fontsize=8)
    ax2.grid(axis="y", alpha=0.3)
    return save(fig, out)


def draw(path, out):
    rows = rows_of(path)
    if not rows:
        return False
    name = os.path.basename(path)[:-4]
    if name == "saliency":
        return draw_saliency(rows, out)
    if name == "viewer":
        return draw_viewer(rows, out)
    machine = rows[0]["machine"]
    ratios, base = baseline_ratios(name, rows)
    labels = list(dict.fromkeys(k[0] for k in ratios))
    groups = list(dict.fromkeys(k[1] for k in ratios))
    errs = [r for r in rows if r["err"] is not None]
    scatter = len(set(r["err"] for r in errs)) > 1
    height = max(3.0, 0.28 * len(labels) * max(1, min(len(groups), 3)) + 1.5)
    fig, axes = plt.subplots(2 if scatter else 1, 1, figsize=(11, height + (5 if scatter else 0)),
                             gridspec_kw={"height_ratios": [height, 5]} if scatter else None)
    ax = axes[0] if scatter else axes
    bar = 0.8 / max(1, len(groups))
    for gi, g in enumerate(groups):
        ys = [li + gi * bar for li, l in enumerate(labels) if (l, g) in ratios]
        xs = [ratios[(l, g)] for l in labels if (l, g) in ratios]
        ax.barh(ys, xs, height=bar, label=g)
        for y, x in zip(ys, xs):
            ax.text(x, y, " %.2f" % x, va="center", fontsize=7)
    ax.set_yticks([li + bar * (len(groups) - 1) / 2 for li in range(len(labels))])
    ax.set_yticklabels([short(l) for l in labels], fontsize=8)
    ax.invert_yaxis()
    ax.axvline(1.0, color="black", lw=0.8)
    if name == "transitions":
        ax.axvline(1.5, color="black", ls="--", lw=0.8, label="goal 1.5x")
    ax.set_xscale("log")
    ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(FormatStrFormatter("%g"))
    ax.tick_params(axis="x", which="minor", labelsize=6)
    ax.set_xlabel("median frame time / baseline (same run; log scale)")
    ax.set_title("%s: ratio to the baseline\nbaseline: %s\n%s" % (name, short(base, 90), machine), fontsize=9)
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(axis="x", which="both", alpha=0.3)
    if scatter:
        ax2 = axes[1]
        methods = list(dict.fromkeys(method_of(r["parameters"]) for r in errs))
        normalised = all(r.get("ratio") is not None for r in errs)
        x = (lambda r: r["ratio"]) if normalised else (lambda r: r["ms"])
        pts = [(x(r), r["err"]) for r in errs]
        for m in methods:
            sel = [(x(r), r["err"]) for r in errs if method_of(r["parameters"]) == m]
            ax2.scatter([p[0] for p in sel], [p[1] for p in sel], s=22, label=m)
        front = pareto(pts)
        ax2.step([pts[i][0] for i in front], [pts[i][1] for i in front], where="post", color="black", lw=1,
                 label="Pareto front")
        ax2.set_xscale("log")
        if min(p[1] for p in pts) > 0:
            ax2.set_yscale("log")
        else:
            ax2.set_yscale("symlog", linthresh=0.1)
            ax2.set_ylim(bottom=0)
        for a in (ax2.xaxis, ax2.yaxis):
            a.set_major_formatter(FormatStrFormatter("%g"))
        ax2.set_xlabel("frame time / baseline at the same K (log)" if normalised else "median frame time (ms, log)")
        ax2.set_ylabel("error_mean (see docs/bench/README.md)")
        ax2.set_title("%s: speed against accuracy (every row)" % name, fontsize=9)
        ax2.legend(fontsize=7, ncol=2)
        ax2.grid(alpha=0.3, which="both")
    return save(fig, out)


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "docs/bench"
    only = set(sys.argv[2:])
    for f in sorted(os.listdir(d)):
        if not f.endswith(".csv") or (only and f[:-4] not in only):
            continue
        out = os.path.join(d, f[:-4] + ".png")
        if draw(os.path.join(d, f), out):
            print("charts: wrote " + out)


if __name__ == "__main__":
    main()
