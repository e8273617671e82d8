"""The error-against-time plot of `shellmarch bench accuracy`, drawn with matplotlib: one log-log
panel per mesh and rank count, every rung a dot with its tag, the Pareto front (no other rung both
faster and more accurate) ringed and joined, the tags explained in a legend under each panel.

Run by the benchmark (pareto_plot.cpp) with
    pareto_plot.py --panels PANELS.json --out PLOT.png --columns N --json RESULT.json
PANELS.json: [{"title": ..., "points": [{"tag", "label", "ms", "error"}, ...], "front": [i, ...]}].
Where Python or matplotlib is missing the benchmark draws its own plot instead.
"""
import argparse
import json
import math

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402


def decades_apart(values):
    positive = [v for v in values if v > 0]
    return len(positive) > 1 and math.log10(max(positive) / min(positive)) >= 1


def draw_panel(ax, panel):
    pts = panel["points"]
    front = set(panel.get("front", []))
    ms = [p["ms"] for p in pts]
    err = [max(p["error"], 1e-12) for p in pts]  # zero error has no place on a log axis
    ax.scatter(ms, err, s=28, color="#2b5fbf", zorder=3, label="rung")
    if front:
        order = sorted(front, key=lambda i: ms[i])
        ax.plot([ms[i] for i in order], [err[i] for i in order], color="#d9401a", lw=1.5,
                zorder=2, label="Pareto front")
        ax.scatter([ms[i] for i in order], [err[i] for i in order], s=110, facecolors="none",
                   edgecolors="#d9401a", lw=1.5, zorder=4)
    for p, x, y in zip(pts, ms, err):
        ax.annotate(p["tag"], (x, y), xytext=(5, 4), textcoords="offset points", fontsize=8)
    ax.set_xscale("log" if decades_apart(ms) else "linear")
    ax.set_yscale("log" if decades_apart(err) else "linear")
    ax.set_xlabel("time per frame [ms]")
    ax.set_ylabel("RMSE against the reference [0-1 colour]")
    ax.set_title(panel["title"], fontsize=10)
    ax.grid(True, which="major", color="#dddddd", lw=0.6)
    ax.legend(loc="best", fontsize=8)
    tags = "\n".join(f"{p['tag']}: {p['label']}" for p in pts)
    ax.text(0.0, -0.2, tags, transform=ax.transAxes, fontsize=7, va="top", family="monospace")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--panels", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--columns", type=int, default=2)
    ap.add_argument("--json", required=True)
    a = ap.parse_args()
    with open(a.panels) as f:
        panels = json.load(f)
    cols = max(1, min(a.columns, len(panels)))
    rows = max(1, math.ceil(len(panels) / cols))
    most = max([len(p["points"]) for p in panels] + [1])
    fig, axes = plt.subplots(rows, cols, figsize=(6.4 * cols, (4.2 + 0.13 * most) * rows),
                             squeeze=False)
    for i, ax in enumerate(axes.flat):
        if i < len(panels):
            draw_panel(ax, panels[i])
        else:
            ax.axis("off")
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    with open(a.json, "w") as f:
        json.dump({"drawn_by": "matplotlib", "matplotlib": matplotlib.__version__}, f)


if __name__ == "__main__":
    main()
