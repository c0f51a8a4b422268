#!/usr/bin/env python3
"""LightSkin + BRSM Fig. 3 from `vplgi compare` runs (scripts/lightskin-experiments): the mean
absolute difference between the selected-VAL and the all-VAL indirect images after compare's
fixed-exposure tone map, per RSM size, one line per selection. A selection run over several seeds
(techniques that differ only in `lightskin.seed=S`) is one line: the mean over the seeds with its
95% t-interval. Prints a markdown table and writes an SVG plot of the means.
Usage: lightskin_fig3.py OUT.svg RUN_DIR... (each RUN_DIR holds metrics.csv and metrics.json of one RSM size)"""
import csv
import json
import math
import os
import re
import statistics
import sys

# Two-sided 95% Student t quantiles by degrees of freedom (1..30); normal beyond.
T95 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
       2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]


def config_of(technique):
    """The technique without its seed key: the line a run belongs to."""
    name = re.sub(r";?lightskin\.seed=\d+", "", technique)
    return name.replace("[;", "[").replace("[]", "")


def interval(values):
    """Mean and 95% t-interval half-width (0 for one value)."""
    mean = statistics.mean(values)
    if len(values) < 2:
        return mean, 0.0
    t = T95[len(values) - 2] if len(values) - 1 <= len(T95) else 1.96
    return mean, t * statistics.stdev(values) / math.sqrt(len(values))


def load(run_dir):
    with open(os.path.join(run_dir, "metrics.json")) as f:
        meta = json.load(f)
    rows = list(csv.DictReader(open(os.path.join(run_dir, "metrics.csv"))))
    size = None
    for row in rows:
        for item in row["settings"].split():
            if item.startswith("rsm.size="):
                size = int(item.split("=")[1])
    if size is None:
        sys.exit(f"{run_dir}: no rsm.size in the settings column")
    return size, rows, meta


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out = sys.argv[1]
    runs = sorted(load(d) for d in sys.argv[2:])
    names = []
    for r in runs[0][1]:
        if r["technique"] != "lightskin-full" and config_of(r["technique"]) not in names:
            names.append(config_of(r["technique"]))
    seeds = sum(1 for r in runs[0][1] if config_of(r["technique"]) == names[0])
    print(f"seeds per selection: {seeds} (mean [95% t-interval])")
    print("| RSM | " + " | ".join(names) + " | lightskin-full vs path tracer |")
    print("|---|" + "---|" * (len(names) + 1))
    series = {n: [] for n in names}
    for size, rows, _ in runs:
        by_name = {r["technique"]: r for r in rows}
        cells = []
        for n in names:
            values = [float(r["against_mean_abs_tonemapped"]) for r in rows if config_of(r["technique"]) == n]
            mean, half = interval(values)
            series[n].append((size, mean))
            cells.append(f"{mean:.5f} [{mean - half:.5f}, {mean + half:.5f}]" if half > 0 else f"{mean:.5f}")
        full = by_name["lightskin-full"]
        cells.append(f"{float(full['mean_abs_tonemapped']):.4f} (bias {100 * float(full['mean_luminance_bias']):+.1f}%)"
                     if full["mean_abs_tonemapped"] else "-")
        print(f"| {size}^2 | " + " | ".join(cells) + " |")
    write_svg(out, series, [r[0] for r in runs])
    print(f"plot: {out}")


def write_svg(path, series, sizes):
    width, height, left, bottom, top, right = 640, 320, 70, 50, 20, 230
    ymax = max(v for points in series.values() for _, v in points) * 1.15 or 1.0
    xs = {s: left + i * (width - left - right) / max(len(sizes) - 1, 1) for i, s in enumerate(sizes)}
    def y(v):
        return top + (height - top - bottom) * (1 - v / ymax)
    colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"]
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">',
             f'<rect width="{width}" height="{height}" fill="white"/>',
             f'<line x1="{left}" y1="{height - bottom}" x2="{width - right}" y2="{height - bottom}" stroke="black"/>',
             f'<line x1="{left}" y1="{top}" x2="{left}" y2="{height - bottom}" stroke="black"/>',
             f'<text x="{(left + width - right) / 2}" y="{height - 10}" text-anchor="middle">RSM resolution</text>',
             f'<text x="15" y="{(top + height - bottom) / 2}" transform="rotate(-90 15 {(top + height - bottom) / 2})" '
             f'text-anchor="middle">mean |selected - all| (tone-mapped)</text>']
    for s, x in xs.items():
        parts.append(f'<text x="{x}" y="{height - bottom + 16}" text-anchor="middle">{s}&#178;</text>')
    for i in range(5):
        v = ymax * i / 4
        parts.append(f'<text x="{left - 6}" y="{y(v) + 4}" text-anchor="end">{v:.4f}</text>')
        parts.append(f'<line x1="{left}" y1="{y(v)}" x2="{width - right}" y2="{y(v)}" stroke="#ddd"/>')
    for k, (name, points) in enumerate(series.items()):
        c = colors[k % len(colors)]
        d = " ".join(f"{xs[s]:.1f},{y(v):.1f}" for s, v in points)
        parts.append(f'<polyline points="{d}" fill="none" stroke="{c}" stroke-width="2"/>')
        for s, v in points:
            parts.append(f'<circle cx="{xs[s]:.1f}" cy="{y(v):.1f}" r="3" fill="{c}"/>')
        label = name.replace("lightskin[", "").replace("lightskin.", "").rstrip("]")
        parts.append(f'<text x="{width - right + 10}" y="{top + 16 + 18 * k}" fill="{c}">{label}</text>')
    parts.append("</svg>")
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(parts) + "\n")
    os.replace(tmp, path)


if __name__ == "__main__":
    main()
