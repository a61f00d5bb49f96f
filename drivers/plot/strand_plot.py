#!/usr/bin/python3
"""strand plot: PNG charts from Strand's JSON-lines studies and HDF5 output.

  strand_plot.py lines FILE.jsonl -x KEY -y KEY [--group KEY[,KEY]] [--where KEY=VALUE ...]
                 [--slope P] [--loglog] [--title T] [--xlabel L] [--ylabel L] -o OUT.png

  strand_plot.py campbell SWEEP.h5 [--modes N] [--tracked] [--orders K] [--title T] [-o OUT.png]
  strand_plot.py nodes SWEEP.h5 [--modes N] [-o OUT.png]
  strand_plot.py belt RUN.h5 [--body NAME] [--frame K] [--title T] [-o OUT.png]

`campbell` draws the sorted frequency loci omega_bar(parameter) of a `strand sweep` file and marks
each detected veering (circle, gap and mode shift in the legend) and crossing (cross); in a rotating
sweep it also draws the excitation lines omega = k Omega (k = 1 .. --orders, default 6) that a
Campbell diagram is read against, and marks and prints where they meet a locus; --tracked
colours the loci by tracked shape (MAC) instead of by sorted order, which shows the mode shift.
`nodes` draws the vibration nodes x/L of each mode shape against the parameter.
`belt` draws, from a `strand run` file, the axial force along a belt (its arc length) at frame K
(default: the last), its stretches on the pulleys sticking and slipping shaded, and each pulley's
speed over time (/series/pulley_<name>_speed).
`lines` draws one line per distinct value of the group keys, from the records that match every
--where filter; --slope P adds a dashed reference line of slope P (a convergence rate) on a log-log
chart. Uses Debian's matplotlib (run with /usr/bin/python3).
"""
import argparse
import json
import sys


def fmt(v):
    return f"{v:g}" if isinstance(v, float) else str(v)


def load_records(path, where):
    records = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line.startswith("{"):
                continue
            try:
                r = json.loads(line)
            except json.JSONDecodeError as e:
                sys.exit(f"{path}:{n}: not a JSON record: {e}")
            if all(fmt(r.get(k)) == v or str(r.get(k)) == v for k, v in where):
                records.append(r)
    return records


def cmd_lines(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    where = []
    for w in a.where:
        if "=" not in w:
            sys.exit(f"--where expects KEY=VALUE, got '{w}'")
        k, v = w.split("=", 1)
        where.append((k, v))
    records = []
    for path in a.files:
        records += load_records(path, where)
    if not records:
        sys.exit(f"no records in {', '.join(a.files)} match {a.where}")
    for key in (a.x, a.y):
        if not any(key in r for r in records):
            sys.exit(f"key '{key}' is in no record")
    groups = {}
    keys = [k for k in a.group.split(",") if k] if a.group else []
    for r in records:
        if a.x not in r or a.y not in r or r[a.y] is None:
            continue
        if a.loglog and not (r[a.x] > 0 and r[a.y] > 0):  # a reference run (error 0) has no place on log axes
            continue
        label = ", ".join(f"{k}={fmt(r.get(k))}" for k in keys) if keys else a.y
        groups.setdefault(label, []).append((r[a.x], r[a.y]))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, pts in groups.items():
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, label=label)
    if a.loglog:
        ax.set_xscale("log")
        ax.set_yscale("log")
    if a.slope is not None:
        xs = sorted({p[0] for pts in groups.values() for p in pts})
        ys = [p[1] for pts in groups.values() for p in pts if p[0] == xs[0]]
        y0 = max(ys)
        ax.plot([xs[0], xs[-1]], [y0, y0 * (xs[-1] / xs[0]) ** a.slope], "k--", lw=1,
                label=f"slope {a.slope:g}")
    ax.set_xlabel(a.xlabel or a.x)
    ax.set_ylabel(a.ylabel or a.y)
    if a.title:
        ax.set_title(a.title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    print(a.output)


PARAMETER_LABELS = {"gamma": r"$\gamma = \Omega\sqrt{\rho A L^4/EI}$", "omega": r"$\Omega$ (rad/s)",
                    "mass_ratio": r"mass ratio $\alpha$", "mass_location": r"mass location $\beta = x/L$"}


def read_sweep(path):
    import h5py
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        sys.exit(f"cannot open sweep file '{path}': {e}")
    with f:
        if "sweep" not in f:
            sys.exit(f"'{path}' has no /sweep group: is it the output of `strand sweep`?")
        g = f["sweep"]
        d = {k: g[k][()] for k in ("parameter", "gamma", "omega_bar", "label", "loci_omega_bar", "node_count", "nodes")}
        d["events"] = {k: g["events"][k][()] for k in g["events"]}
        names = g.attrs.get("kind_names", "")
        names = names.decode() if isinstance(names, bytes) else str(names)
        d["kind"] = [[names.split(",")[c] if c >= 0 else "" for c in row] for row in g["kind"][()]] if "kind" in g else []
        d["name"] = f.attrs["parameter"]
        d["name"] = d["name"].decode() if isinstance(d["name"], bytes) else str(d["name"])
        d["status"] = f.attrs["status"]
    return d


def default_output(a, suffix):
    import os
    return a.output or os.path.splitext(a.file)[0] + suffix


def cmd_campbell(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = read_sweep(a.file)
    p, w = d["parameter"], d["omega_bar"]
    n = w.shape[1] if w.ndim == 2 else 0
    if len(p) == 0 or n == 0:
        sys.exit(f"'{a.file}' holds no sweep points")
    n = min(n, a.modes) if a.modes else n
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    if a.tracked and d["loci_omega_bar"].size:
        for l in range(n):
            ax.plot(p, d["loci_omega_bar"][l], "-", lw=1.5, label=f"tracked mode {l + 1}")
    else:
        for k in range(n):  # each locus named by what its mode is at the first point (ModeLabels)
            kind = d["kind"][0][k] if d["kind"] and k < len(d["kind"][0]) and d["kind"][0][k] else ""
            ax.plot(p, w[:, k], "-", lw=1.5, label=f"locus {k + 1}" + (f" ({kind})" if kind else ""))
    # excitation lines omega = k Omega (k = 1 .. --orders), i.e. omega_bar = k gamma, and their
    # crossings with the loci: the resonance candidates (printed, and marked with triangles)
    gamma = d["gamma"]
    if a.orders > 0 and len(gamma) == len(p) and max(abs(x) for x in gamma) > 0.0:
        top = max(float(w[:, :n].max()), 1e-300)
        marked = False
        for k in range(1, a.orders + 1):
            line = [k * x for x in gamma]
            ax.plot(p, line, ":", color="0.45", lw=0.9)
            i = max(0, min(len(p) - 1, next((j for j in range(len(p)) if line[j] > top), len(p) - 1)))
            ax.annotate(f"{k}$\\Omega$", (p[i], min(line[i], top)), fontsize=7, color="0.35")
            for l in range(n):
                for j in range(len(p) - 1):
                    f0, f1 = w[j, l] - line[j], w[j + 1, l] - line[j + 1]
                    if f0 == 0.0 or f0 * f1 < 0.0:
                        t = f0 / (f0 - f1) if f0 != f1 else 0.0
                        x = p[j] + t * (p[j + 1] - p[j])
                        y = w[j, l] + t * (w[j + 1, l] - w[j, l])
                        ax.plot([x], [y], "^", ms=6, mfc="none", mec="tab:purple", mew=1.2,
                                label=None if marked else "resonance candidate (k $\\Omega$ meets a locus)")
                        marked = True
                        print(f"resonance candidate: locus {l + 1} meets {k} Omega at {d['name']} {x:.6g}, omega_bar {y:.6g}")
        ax.set_ylim(0.0, 1.05 * top)
    ev = d["events"]
    shown = set()
    for i in range(len(ev.get("kind", []))):
        if ev["lower"][i] + 1 >= n:
            continue
        veer = ev["kind"][i] == 0
        label = None
        key = "veering" if veer else "crossing"
        if key not in shown:
            label = ("veering (mode shift)" if veer else "crossing")
            shown.add(key)
        ax.plot([ev["parameter"][i]], [ev["omega_bar"][i]], "o" if veer else "x", ms=14 if veer else 10,
                mfc="none", mec="k" if veer else "r", mew=1.5, label=label)
        ax.annotate(f"gap {ev['gap'][i]:.3g}", (ev["parameter"][i], ev["omega_bar"][i]), textcoords="offset points",
                    xytext=(8, -12), fontsize=7)
    ax.set_xlabel(PARAMETER_LABELS.get(d["name"], d["name"]))
    ax.set_ylabel(r"$\bar\omega = \omega\sqrt{\rho A L^4/EI}$")
    ax.set_title(a.title or f"Campbell diagram: {a.file}", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    out = default_output(a, "_campbell.png")
    fig.savefig(out, dpi=110)
    print(out)


def cmd_nodes(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = read_sweep(a.file)
    p, nodes, count = d["parameter"], d["nodes"], d["node_count"]
    if len(p) == 0:
        sys.exit(f"'{a.file}' holds no sweep points")
    n = min(count.shape[1], a.modes) if a.modes else count.shape[1]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for k in range(n):
        xs, ys = [], []
        for i in range(len(p)):
            for j in range(count[i, k]):
                xs.append(p[i])
                ys.append(nodes[i, k, j])
        ax.plot(xs, ys, ".", ms=3, label=f"mode {k + 1}")
    ax.set_xlabel(PARAMETER_LABELS.get(d["name"], d["name"]))
    ax.set_ylabel("vibration node x / L")
    ax.set_ylim(0, 1)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(a.title or f"vibration nodes: {a.file}", fontsize=9)
    fig.tight_layout()
    out = default_output(a, "_nodes.png")
    fig.savefig(out, dpi=110)
    print(out)


def cmd_belt(a):
    import h5py
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = h5py.File(a.file, "r")
    frames = f.get("frames")
    n = int(frames["time"].shape[0]) if frames is not None and "time" in frames else 0
    if n == 0:
        sys.exit(f"'{a.file}' holds no frames")
    k = a.frame if a.frame is not None else n - 1
    if not -n <= k < n:
        sys.exit(f"'{a.file}' holds {n} frames: --frame {a.frame} is not one of them")
    k %= n
    time = float(frames["time"][k])
    bodies = [b for b in frames.keys() if isinstance(frames[b], h5py.Group) and "axial_force" in frames[b]]
    if not bodies:
        sys.exit(f"'{a.file}': no body with an axial_force field (cables write it)")
    body = a.body or bodies[0]
    if body not in bodies:
        sys.exit(f"'{a.file}': no body '{body}' with an axial_force field; bodies: {', '.join(bodies)}")
    g = frames[body]  # a row per frame
    c = g["centerline"][k]
    seg = np.linalg.norm(np.diff(c, axis=0), axis=1)
    s = np.concatenate(([0.0], np.cumsum(seg)))
    mid = 0.5 * (s[:-1] + s[1:])
    T = g["axial_force"][k]
    speeds = sorted(n for n in f["series"].keys() if n.startswith("pulley_") and n.endswith("_speed")) if "series" in f else []
    fig, axes = plt.subplots(2 if speeds else 1, 1, figsize=(6.4, 7.2 if speeds else 4.0), squeeze=False)
    ax = axes[0][0]
    ax.plot(mid, T, "-", color="k", lw=1.2, label="axial force")
    if "contact_state" in g:
        state = g["contact_state"][k]
        for value, color, label in ((1, "tab:blue", "on a pulley, sticking"), (2, "tab:red", "on a pulley, slipping")):
            on = state == value
            if on.any():
                ax.fill_between(mid, 0, T, where=on, color=color, alpha=0.25, step="mid", label=label)
    ax.set_xlabel("arc length along the belt [m]")
    ax.set_ylabel("axial force [N]")
    ax.set_title(a.title or f"{body} at t = {time:g} s: {a.file}", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    if speeds:
        ax = axes[1][0]
        t = f["series"]["time"][:] if "time" in f["series"] else np.arange(len(f["series"][speeds[0]]))
        for n in speeds:
            ax.plot(t, f["series"][n][:], "-", lw=1.2, label=n[len("pulley_"):-len("_speed")])
        ax.set_xlabel("time [s]")
        ax.set_ylabel("pulley speed [rad/s]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    out = default_output(a, "_belt.png")
    fig.savefig(out, dpi=110)
    print(out)


def main(argv=None):
    p = argparse.ArgumentParser(prog="strand plot", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    ln = sub.add_parser("lines", help="y against x from JSON lines, one line per group")
    ln.add_argument("files", nargs="+")
    ln.add_argument("-x", required=True)
    ln.add_argument("-y", required=True)
    ln.add_argument("--group", default="")
    ln.add_argument("--where", action="append", default=[])
    ln.add_argument("--slope", type=float)
    ln.add_argument("--loglog", action="store_true")
    ln.add_argument("--title")
    ln.add_argument("--xlabel")
    ln.add_argument("--ylabel")
    ln.add_argument("-o", "--output", required=True)
    ln.set_defaults(run=cmd_lines)
    for name, fn, what in (("campbell", cmd_campbell, "Campbell diagram of a sweep, veering marked"),
                           ("nodes", cmd_nodes, "vibration nodes of each mode against the parameter")):
        c = sub.add_parser(name, help=what)
        c.add_argument("file")
        c.add_argument("--modes", type=int, default=0)
        c.add_argument("--title")
        c.add_argument("-o", "--output")
        if name == "campbell":
            c.add_argument("--tracked", action="store_true")
            c.add_argument("--orders", type=int, default=6, help="excitation lines k Omega, k = 1 .. ORDERS (0: none)")
        c.set_defaults(run=fn)
    bt = sub.add_parser("belt", help="axial force along a belt (stick/slip shaded) and pulley speeds over time")
    bt.add_argument("file")
    bt.add_argument("--body")
    bt.add_argument("--frame", type=int, help="frame index (default: the last; negative counts from the end)")
    bt.add_argument("--title")
    bt.add_argument("-o", "--output")
    bt.set_defaults(run=cmd_belt)
    a = p.parse_args(argv)
    a.run(a)


if __name__ == "__main__":
    main()
