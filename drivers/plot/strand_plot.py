#!/usr/bin/python3
"""strand plot: PNG charts from Strand's JSON-lines studies and HDF5 output.

  strand_plot.py lines FILE.jsonl -x KEY -y KEY [--group KEY[,KEY]] [--where KEY=VALUE ...]
                 [--slope P] [--loglog] [--title T] [--xlabel L] [--ylabel L] -o OUT.png

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
    a = p.parse_args(argv)
    a.run(a)


if __name__ == "__main__":
    main()
