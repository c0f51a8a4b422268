#!/usr/bin/env python3
"""Splits each technique's |E'| (SMCIR eq. 10) at the tracked pixels of a `vplgi compare` run into a
smooth part (E averaged over 5 frames: bias drifting with the scene) and the rest (frame-to-frame
jitter). Reads metrics.json's per-pixel luminance series (`trackedLuminance`, `referenceLuminance`)
and compare's tone map, T(Y) = eY / (1 + eY) at the report's exposure.
Usage: scripts/lib/temporal_split.py out/experiments/vsgl-glossy-temporal/metrics.json"""
import json
import sys


def moving_average(series, half_width=2):
    out = []
    for t in range(len(series)):
        a, b = max(0, t - half_width), min(len(series), t + half_width + 1)
        out.append(sum(series[a:b]) / (b - a))
    return out


def mean_abs_derivative(series):
    return sum(abs(series[t] - series[t - 1]) for t in range(1, len(series)))


def main():
    report = json.load(open(sys.argv[1]))
    exposure = report["exposure"]
    tone = lambda y: exposure * y / (1.0 + exposure * y)
    reference = report["tracked"]["referenceLuminance"]
    frames, pixels = len(reference), len(reference[0])
    if frames < 2:
        sys.exit("temporal_split: needs at least two frames")
    print("technique | |E'| | smooth part | jitter part")
    for technique in report["techniques"]:
        series = technique["trackedLuminance"]
        total = smooth = jitter = 0.0
        for j in range(pixels):
            e = [tone(series[f][j]) - tone(reference[f][j]) for f in range(frames)]
            s = moving_average(e)
            total += mean_abs_derivative(e)
            smooth += mean_abs_derivative(s)
            jitter += mean_abs_derivative([e[f] - s[f] for f in range(frames)])
        n = pixels * (frames - 1)
        name = technique["name"]
        print(f"{name} | {total / n:.3g} | {smooth / n:.3g} | {jitter / n:.3g}")


if __name__ == "__main__":
    main()
