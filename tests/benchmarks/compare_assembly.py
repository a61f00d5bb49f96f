#!/usr/bin/python3
"""The cable's assembly time, two builds interleaved (issue 33: the element-kind refactor may not
make the cable's assembly slower; target: median ratio new/old <= 1.05).

  compare_assembly.py OLD_BENCH NEW_BENCH [--rounds 7] [--elements 10000 100000]

OLD_BENCH and NEW_BENCH are bench_assembly binaries of the two builds (build the old one from a
worktree of the commit before: git worktree add --detach ../base <commit>; cmake --build
../base/build --target bench_assembly). Each round runs old then new (alternating which goes
first) at each size; per round the ratio new/old of the AncfCable3d residual + tangent time per
element (builds older than -min_elements run every size from 1e3 up: the record of size n is taken). Prints one JSON line per size with the median ratio, the range of the ratios, and each
build's own spread (max/min over rounds): when the spread is wider than the gap, noise decides.
"""
import argparse
import json
import statistics
import subprocess


def run(binary, n):
    out = subprocess.run([binary, "-min_elements", str(n), "-max_elements", str(n)], check=True,
                         capture_output=True, text=True).stdout
    for line in out.splitlines():
        if line.startswith("{"):
            r = json.loads(line)
            if r.get("element") == "AncfCable3d" and r.get("elements") == n:
                return r["residual_plus_tangent_us_per_element"]
    raise SystemExit(f"{binary}: no AncfCable3d record with {n} elements")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--elements", type=int, nargs="+", default=[10000, 100000])
    a = p.parse_args()
    for n in a.elements:
        old, new, ratio = [], [], []
        for k in range(a.rounds):
            if k % 2 == 0:
                o = run(a.old, n)
                w = run(a.new, n)
            else:
                w = run(a.new, n)
                o = run(a.old, n)
            old.append(o)
            new.append(w)
            ratio.append(w / o)
        print(json.dumps({"bench": "compare_assembly", "element": "AncfCable3d", "elements": n, "rounds": a.rounds,
                          "median_ratio_new_over_old": round(statistics.median(ratio), 4),
                          "ratio_range": [round(min(ratio), 4), round(max(ratio), 4)],
                          "old_us_per_element": [round(x, 4) for x in old],
                          "new_us_per_element": [round(x, 4) for x in new],
                          "old_spread": round(max(old) / min(old), 4), "new_spread": round(max(new) / min(new), 4),
                          "target_met": statistics.median(ratio) <= 1.05}), flush=True)


if __name__ == "__main__":
    main()
