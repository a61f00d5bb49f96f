#!/usr/bin/python3
"""Kill `strand run` with SIGKILL at random moments and check that its output stays readable.

usage: kill_test.py STRAND_BINARY [--kills N] [--max-delay S] [--seed K] [--keep DIR]

Requirement (issue 32 item 4): a run killed at any instant leaves its HDF5 file readable up to its
last complete frame: h5py opens it, /frames has `count` frames, every frame that the .xdmf2 names
exists and reads back whole (centerline and coordinates of every body), and every /series dataset
reads. A kill before the first commit leaves no file at all, which is fine too.

The scene writes a frame at every step (64 elements, so a frame is a few kB of data and metadata),
and the runs commit their buffered frames every 0.02 s (-output_commit_interval; the default, 2 s,
would leave most kills before the second commit), so that kills land in block writes, flushes and
commits alike. Each kill waits a
uniformly random time in [0, --max-delay] after the start (start-up included). Prints one line
per kill and a summary; exit status 0 when every file was readable, 1 otherwise, 77 (ctest: skipped)
without python3-h5py. Default ctest runs a short version (regression_kill); `cmake --build build
--target kill_test_long` runs 400 kills.
"""
import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

try:
    import h5py
except ImportError:
    print("kill_test: python3-h5py is not installed; skipped")
    sys.exit(77)

SCENE = """analysis: dynamic
dimension: 2
bodies:
  - name: rope
    element: AncfCable2d
    elements: 64
    geometry: {kind: line, start: [0, 0], end: [1, 0]}
    section: {E: 1e8, A: 1e-4, I: 1e-8, rho: 7850}
supports:
  - {body: rope, node: 0, type: pinned}
loads:
  gravity: [0, -9.81]
dynamics: {integrator: generalized_alpha, rho_inf: 1.0, dt: 1e-3, t_end: 100.0, output_every: 1}
"""


def check(h5, xmf):
    """Raises when the killed run's file is not readable up to its last frame; returns the frames."""
    listed = len(re.findall(r'Name="frame_', open(xmf).read())) if os.path.exists(xmf) else 0
    with h5py.File(h5, "r") as f:
        count = int(f["frames"].attrs["count"])
        if listed > count:
            raise RuntimeError("the .xdmf2 names %d frames, /frames has %d" % (listed, count))
        if f["frames/time"].shape[0] != count:
            raise RuntimeError("/frames has count %d but %d times" % (count, f["frames/time"].shape[0]))
        for body in f["bodies"]:
            g = f["frames/%s" % body]
            for ds in ("centerline", "coordinates"):
                if g[ds].shape[0] != count:
                    raise RuntimeError("/frames/%s/%s has %d rows, count is %d" % (body, ds, g[ds].shape[0], count))
                g[ds][()]
        for name in f["series"]:
            f["series"][name][()]
    return count


def main():
    p = argparse.ArgumentParser()
    p.add_argument("binary")
    p.add_argument("--kills", type=int, default=30)
    p.add_argument("--max-delay", type=float, default=1.5)
    p.add_argument("--seed", type=int, default=None)
    p.add_argument("--keep", default=None, help="copy unreadable files here")
    p.add_argument("--commit-interval", type=float, default=0.02,
                   help="-output_commit_interval of the runs: short, so that kills land in block commits")
    a = p.parse_args()
    rng = random.Random(a.seed)
    work = tempfile.mkdtemp(prefix="strand-kill-")
    scene = os.path.join(work, "kill.yaml")
    with open(scene, "w") as f:
        f.write(SCENE)
    h5, xmf = os.path.join(work, "kill.h5"), os.path.join(work, "kill.xdmf2")
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    bad = none = 0
    frames = []
    for i in range(a.kills):
        delay = rng.uniform(0.0, a.max_delay)
        run = subprocess.Popen([a.binary, "run", scene, "-o", h5, "-overwrite", "-output_commit_interval",
                                str(a.commit_interval)], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, env=env)
        time.sleep(delay)
        run.send_signal(signal.SIGKILL)
        run.wait()
        if not os.path.exists(h5):
            none += 1
            print("kill %d at %.3f s: no output yet" % (i, delay))
            continue
        try:
            n = check(h5, xmf)
            frames.append(n)
            print("kill %d at %.3f s: readable, %d frames" % (i, delay, n))
        except Exception as e:  # h5py raises OSError, KeyError, ... for a damaged file
            bad += 1
            print("kill %d at %.3f s: UNREADABLE: %s" % (i, delay, e))
            if a.keep:
                os.makedirs(a.keep, exist_ok=True)
                shutil.copy(h5, os.path.join(a.keep, "unreadable%d.h5" % i))
        for path in (h5, xmf):
            if os.path.exists(path):
                os.remove(path)
    shutil.rmtree(work)
    print("kill_test: %d kills, %d unreadable files, %d before the first frame, frames per file %d..%d" %
          (a.kills, bad, none, min(frames, default=0), max(frames, default=0)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
