#!/usr/bin/python3
"""Chart of study_hub_beam's JSON lines (seed 001 Tables 1-3 in our terms): error against wall time,
colour by discretization, marker by integrator, and the cheapest run meeting each target.

usage: plot_hub_beam_study.py STUDY.jsonl -o CHART.png [--error history_error|amplitude_error]
Prints, for 1e-2, 1e-3 and 1e-4, the cheapest run meeting it (a Markdown table row each).
"""
import argparse
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"AMM": "tab:red", "FEM": "tab:blue", "RPIM": "tab:green"}
MARKERS = {"Newmark": "o", "alpha0.9": "s", "BDF2": "^", "RK4": "D", "ABM4": "v"}
LABELS = {"history_error": "max |u_y - u_y,ref| / peak", "amplitude_error": "|amplitude / amplitude_ref - 1|"}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("file")
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--error", default="history_error", choices=sorted(LABELS))
    a = p.parse_args()
    head, runs = None, []
    for line in open(a.file):
        line = line.strip()
        if not line.startswith("{"):
            continue
        r = json.loads(line)
        if "method" in r:
            runs.append(r)
        else:
            head = r
    ok = [r for r in runs if not r["failed"] and r[a.error] > 0]
    fig, ax = plt.subplots(figsize=(8.5, 5.5))
    for r in ok:
        ax.loglog(r["wall_s"], r[a.error], MARKERS[r["scheme"]], color=COLOURS[r["method"]], alpha=0.8)
    # label each model once, at its fastest run
    fastest = {}
    for r in ok:
        if r["label"] not in fastest or r["wall_s"] < fastest[r["label"]]["wall_s"]:
            fastest[r["label"]] = r
    for r in fastest.values():
        ax.annotate(r["label"], (r["wall_s"], r[a.error]), xytext=(4, 3), textcoords="offset points", fontsize=7)
    print("| target | cheapest run | error | wall s |")
    print("|---|---|---|---|")
    for target in (1e-2, 1e-3, 1e-4):
        meeting = [r for r in ok if r[a.error] <= target]
        ax.axhline(target, color="grey", lw=0.6, ls="--")
        if not meeting:
            print(f"| {target:g} | none | | |")
            continue
        best = min(meeting, key=lambda r: r["wall_s"])
        ax.plot(best["wall_s"], best[a.error], "o", mfc="none", mec="k", ms=13)
        print(f"| {target:g} | {best['label']}, {best['scheme']} (dt {best['dt']:.2g} s) | {best[a.error]:.2g} | {best['wall_s']:.3g} |")
    for s, m in MARKERS.items():
        ax.plot([], [], m, color="k", label=s)
    for d, c in COLOURS.items():
        ax.plot([], [], "o", color=c, label=d)
    ax.legend(fontsize=8, loc="lower left")
    ax.set_xlabel("wall time [s] (one core)")
    ax.set_ylabel(LABELS[a.error])
    title = "Hub-beam spin-up (seed 001 Tables 1-3)"
    if head:
        title += f", Omega0 = {head['omega0']:g} rad/s, E = {head['E'] / 1e9:g} GPa; ref {head['reference']}"
    ax.set_title(title + "\ncircled: cheapest run meeting each dashed target", fontsize=9)
    fig.tight_layout()
    fig.savefig(a.output, dpi=100)


if __name__ == "__main__":
    main()
