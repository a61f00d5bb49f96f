#!/usr/bin/python3
"""Check a Strand output file (HDF5 + XDMF) and print a one-line JSON summary.

usage: check_output.py FILE.h5 [FILE.h5 ...] [--pvpython] | --compare-final A.h5 B.h5 [A2.h5 B2.h5 ...]

Checks the layout written by strand::io::OutputWriter (include/strand/io/OutputWriter.hpp):
root attributes, /bodies/<body>/connectivity, /frames/time and /frames/<body>/{centerline,
coordinates} (a row per frame for every body, right shapes, finite), /series (one length for all),
/modes, and that every HDF reference in <stem>.xdmf2 and <stem>_modes.xmf names an existing
dataset of the stated dimensions (a HyperSlab's dataset at least as many rows as declared, the
selection inside it). A scene of rigid bodies only has an empty /bodies (its state is in
/series/rigid_*). With --pvpython it also opens the XDMF files in ParaView as a user's
OpenDataFile does (which picks the reader by extension: the XDMF 2 reader for .xdmf2, an Xdmf3
reader for .xmf) when ParaView's Python modules (python3-paraview) or a pvpython executable are
available, and skips that step otherwise.
Several files: one JSON line each.

--compare-final A.h5 B.h5 compares the final states of two dynamic runs of one scene (e.g. an
uninterrupted run and a restarted one): the last frame's nodal coordinates of every body and the
last row of every /series/rigid_* and of /series/kinetic_energy (velocity level), and prints
{"a": A, "b": B, "time": [tA, tB], "max_abs": ..., "max_rel": ..., "rel2": ..., "kinetic_rel": ...}: max_rel =
max_abs / (the largest |value| of A's state: coordinates and rigid coordinates), rel2 = |A - B| / |A|
in the 2-norm (the norm of Strand's Newton test), kinetic_rel the relative difference of the kinetic
energies. More pairs: one line each.

Exit status: 0 all checks passed, 1 some check failed, 2 a file cannot be opened.
Uses the Debian python3-h5py, hence /usr/bin/python3 (not a pyenv python3 without h5py).
"""
import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    import h5py
    import numpy as np
except ImportError as e:  # pragma: no cover
    print(json.dumps({"ok": False, "errors": ["cannot import h5py/numpy (%s); run with /usr/bin/python3" % e]}))
    sys.exit(2)


def attr(obj, name, errors, where):
    if name not in obj.attrs:
        errors.append("%s: missing attribute '%s'" % (where, name))
        return None
    v = obj.attrs[name]
    if isinstance(v, bytes):
        v = v.decode("utf-8")
    if isinstance(v, np.generic):
        v = v.item()
    return v


def check_bodies_group(parent, where, layouts, errors, rows=None):
    """parent: a mode group, or /frames (rows: the frame count, a leading dimension); every body
    needs finite centerline and coordinates."""
    for name, lay in layouts.items():
        for ds, shape in (("centerline", (lay["points"], 3)), ("coordinates", (lay["nodes"], lay["coords_per_node"]))):
            path = "%s/%s/%s" % (where, name, ds)
            if name not in parent or ds not in parent[name]:
                errors.append("%s: missing" % path)
                continue
            d = parent[name][ds]
            if rows is not None:
                shape = (rows,) + shape
            if d.shape != shape:
                errors.append("%s: shape %s, expected %s" % (path, d.shape, shape))
            if not np.all(np.isfinite(d[()])):
                errors.append("%s: non-finite values" % path)


def check_xdmf(xmf, h5, errors):
    """Every Format="HDF" DataItem must name a dataset in `h5` with the stated dimensions."""
    info = {"file": os.path.basename(xmf), "references": 0, "grids": 0}
    try:
        root = ET.parse(xmf).getroot()
    except (ET.ParseError, OSError) as e:
        errors.append("%s: not valid XML: %s" % (xmf, e))
        return info
    if root.tag != "Xdmf" or root.get("Version", "").split(".")[0] != "3":
        errors.append("%s: not an XDMF 3 file" % xmf)
    top = root.findall("./Domain/Grid")
    if len(top) != 1 or top[0].get("CollectionType") != "Temporal":
        errors.append("%s: expected one temporal collection under Domain" % xmf)
        return info
    steps = top[0].findall("./Grid")
    info["grids"] = len(steps)
    times = []
    for g in steps:
        t = g.find("./Time")
        if t is None:
            errors.append("%s: grid '%s' has no Time" % (xmf, g.get("Name")))
        else:
            times.append(float(t.get("Value")))
    if len(set(times)) != len(times):
        errors.append("%s: repeated Time values (ParaView shows only one of them)" % xmf)
    h5name = os.path.basename(h5.filename)
    slabs = {}  # the HDF DataItem of a HyperSlab -> its selection (start, stride, count)
    for slab in root.iter("DataItem"):
        if slab.get("ItemType") == "HyperSlab":
            kids = slab.findall("./DataItem")
            if len(kids) != 2 or kids[0].get("Format") != "XML" or kids[1].get("Format") != "HDF":
                errors.append("%s: a HyperSlab needs an XML selection and an HDF DataItem" % xmf)
                continue
            sel = [int(v) for v in kids[0].text.split()]
            n = len(sel) // 3
            slabs[kids[1]] = (sel[:n], sel[n:2 * n], sel[2 * n:], slab.get("Dimensions", ""))
    for item in root.iter("DataItem"):
        if item.get("Format") != "HDF":
            continue
        info["references"] += 1
        ref = (item.text or "").strip()
        fname, _, dpath = ref.partition(":")
        if fname != h5name:
            errors.append("%s: reference '%s' is not to '%s' (must be relative)" % (xmf, ref, h5name))
            continue
        if dpath not in h5 or not isinstance(h5[dpath], h5py.Dataset):
            errors.append("%s: reference '%s': no such dataset" % (xmf, ref))
            continue
        dims = tuple(int(x) for x in item.get("Dimensions", "").split())
        shape = h5[dpath].shape
        if item in slabs:  # declared rows <= the dataset's (it grows); the selection inside them
            start, stride, count, outer = slabs[item]
            if len(dims) != len(shape) or dims[0] > shape[0] or dims[1:] != shape[1:]:
                errors.append("%s: reference '%s': Dimensions %s, dataset has %s" % (xmf, ref, dims, shape))
            elif len(start) != len(dims) or any(s + (c - 1) * st >= d for s, st, c, d in zip(start, stride, count, dims)):
                errors.append("%s: reference '%s': selection %s outside %s" % (xmf, ref, (start, stride, count), dims))
            elif np.prod(count) != np.prod([int(x) for x in outer.split()]):
                errors.append("%s: reference '%s': HyperSlab Dimensions '%s' for a selection of %s" % (xmf, ref, outer, count))
        elif dims != shape:
            errors.append("%s: reference '%s': Dimensions %s, dataset has %s" % (xmf, ref, dims, shape))
    return info


PV_SNIPPET = r"""
import json, sys
from paraview.simple import OpenDataFile, UpdatePipeline
out = {}
for f in sys.argv[1:]:
    r = OpenDataFile(f)  # the reader ParaView picks for the extension, as a user's double click
    times = r.TimestepValues
    times = [] if times is None else (list(times) if hasattr(times, "__len__") else [float(times)])
    UpdatePipeline(time=times[-1] if times else None, proxy=r)
    info = r.GetDataInformation()
    out[f] = {"timesteps": len(times), "last_time": times[-1] if times else None,
              "points": info.GetNumberOfPoints(), "cells": info.GetNumberOfCells(),
              "bounds": list(info.GetBounds())}
print(json.dumps(out))
"""


def check_paraview(xmfs, expected, errors):
    """Open the XDMF files in ParaView (OpenDataFile); 'skipped' when ParaView is absent.

    expected[xmf] = (steps, points, cells, bounds of the last step): what the reader must show."""
    if not xmfs:
        return "skipped (no XDMF file)"
    if importlib.util.find_spec("paraview") is not None:  # Debian python3-paraview
        interpreter = sys.executable
    else:
        interpreter = shutil.which("pvpython")
    if interpreter is None:
        return "skipped (no paraview)"
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as script:
        script.write(PV_SNIPPET)
    try:
        # A separate process: ParaView may abort on a bad file, which must not take this script down.
        # Absolute paths: the Xdmf3 reader resolves "run.h5" against a bare "run.xmf" wrongly.
        res = subprocess.run([interpreter, script.name] + [os.path.abspath(x) for x in xmfs], capture_output=True, text=True, timeout=300)
    except (OSError, subprocess.TimeoutExpired) as e:
        errors.append("paraview: %s" % e)
        return "failed"
    finally:
        os.unlink(script.name)
    lines = [l for l in res.stdout.splitlines() if l.startswith("{")]
    if res.returncode != 0 or not lines:
        errors.append("paraview: exit %d: %s" % (res.returncode, res.stderr.strip()[-500:]))
        return "failed"
    result = json.loads(lines[-1])
    for xmf in xmfs:
        r = result.get(os.path.abspath(xmf))
        if r is None:
            errors.append("paraview: %s: not read" % xmf)
            continue
        steps, points, cells, bounds = expected[xmf]
        if (r["timesteps"], r["points"], r["cells"]) != (steps, points, cells):
            errors.append("paraview: %s: %d steps, %d points, %d cells; expected %d, %d, %d" %
                          (xmf, r["timesteps"], r["points"], r["cells"], steps, points, cells))
        if bounds is not None and np.all(np.isfinite(bounds)) and not np.allclose(r["bounds"], bounds, rtol=1e-12, atol=1e-12):
            errors.append("paraview: %s: last step bounds %s, expected %s" % (xmf, r["bounds"], bounds))
    return result


def expected_steps(h5, modes):
    if not modes:
        return int(h5["frames/time"].shape[0]) if "frames/time" in h5 else 0
    g = h5.get("modes", {})
    return len([k for k in g.keys() if k != "frequencies_hz"])


def last_bounds(h5, modes):
    """[xmin, xmax, ymin, ymax, zmin, zmax] over all bodies' centerlines of the last frame or mode."""
    if modes:
        g = h5.get("modes")
        names = sorted(k for k in g.keys() if k != "frequencies_hz") if g is not None else []
        if not names:
            return None
        parts = [b["centerline"][()] for b in g[names[-1]].values() if isinstance(b, h5py.Group) and "centerline" in b]
    else:
        if expected_steps(h5, False) == 0:
            return None
        parts = [b["centerline"][-1] for b in h5["frames"].values() if isinstance(b, h5py.Group) and "centerline" in b]
    if not parts:  # rigid bodies only: nothing drawn
        return None
    pts = np.concatenate(parts)
    return [float(v) for pair in zip(pts.min(axis=0), pts.max(axis=0)) for v in pair]


def check_file(h5, path, summary, errors):
    """All checks on the open file; returns (xmf files, what ParaView must show for each)."""
    for key in ("strand_version", "scene_file", "analysis", "dimension"):
        summary[key] = attr(h5, key, errors, "/")

    # bodies
    layouts = {}
    rigid_only = any(k.startswith("rigid_") for k in h5.get("series", {}).keys())
    if "bodies" not in h5 or (len(h5["bodies"]) == 0 and not rigid_only):
        errors.append("/bodies: missing or empty")
    else:
        for name, g in h5["bodies"].items():
            where = "/bodies/" + name
            lay = {k: attr(g, k, errors, where) for k in ("element_type", "elements", "nodes", "coords_per_node")}
            conn = g.get("connectivity")
            if conn is None or conn.ndim != 2 or conn.shape[1] != 2 or conn.shape[0] < 1:
                errors.append(where + "/connectivity: missing or not (n, 2)")
                lay["points"] = None
            else:
                n = conn.shape[0]
                segments = np.stack([np.arange(n), np.arange(1, n + 1)], axis=1)
                if not np.array_equal(conn[()], segments):
                    errors.append(where + "/connectivity: not consecutive segments")
                lay["points"] = n + 1
            if "points_per_body" in g.attrs and lay["points"] is not None and int(g.attrs["points_per_body"]) != lay["points"]:
                errors.append(where + ": points_per_body does not match connectivity")
            layouts[name] = lay
    summary["bodies"] = {n: {"element_type": l["element_type"], "elements": l["elements"],
                             "nodes": l["nodes"], "points": l["points"]} for n, l in layouts.items()}
    valid_layouts = {n: l for n, l in layouts.items()
                     if None not in (l["points"], l["nodes"], l["coords_per_node"])}

    # frames: /frames/time and a row per frame in every body's datasets
    times = []
    n_frames = 0
    if "frames" not in h5:
        errors.append("/frames: missing")
    elif "time" not in h5["frames"] or not isinstance(h5["frames"]["time"], h5py.Dataset):
        errors.append("/frames/time: missing")
    else:
        frames = h5["frames"]
        n_frames = int(frames["time"].shape[0])
        count = attr(frames, "count", errors, "/frames")
        if count is not None and count != n_frames:
            errors.append("/frames: count attribute %s but %d rows in /frames/time" % (count, n_frames))
        times = [float(t) for t in frames["time"][()]]
        if not all(math.isfinite(t) for t in times):
            errors.append("/frames/time: not finite")
        extra = sorted(k for k in frames.keys() if k != "time" and k not in valid_layouts)
        if extra:
            errors.append("/frames: %s are not bodies" % extra)
        check_bodies_group(frames, "/frames", valid_layouts, errors, rows=n_frames)
    if n_frames == 0:
        errors.append("/frames: no frames")
    summary["frames"] = n_frames
    summary["time_range"] = [min(times), max(times)] if times else None

    # series (values may legitimately be inf/nan on a diverged run: only the shape is checked)
    series = {}
    for name, d in h5.get("series", {}).items():
        if not isinstance(d, h5py.Dataset) or d.ndim != 1:
            errors.append("/series/%s: not a 1-D dataset" % name)
            continue
        series[name] = int(d.shape[0])
    summary["series"] = series
    if len(set(series.values())) > 1:  # every series gets one value per step
        errors.append("/series: datasets of different lengths %s" % sorted(set(series.values())))
    if "time" in h5.get("series", {}):  # one row per step: the times increase
        times = [float(v) for v in h5["series"]["time"][:]]
        if any(not b > a for a, b in zip(times, times[1:])):
            errors.append("/series/time: not increasing (a step written twice?)")

    # modes
    if "modes" in h5:
        m = h5["modes"]
        f = m.get("frequencies_hz")
        groups = sorted(k for k in m.keys() if k != "frequencies_hz")
        if f is None:
            errors.append("/modes/frequencies_hz: missing")
            summary["modes"] = None
        else:
            freqs = f[()]
            if len(freqs) != len(groups) or groups != ["%05d" % i for i in range(len(groups))]:
                errors.append("/modes: %d frequencies but mode groups %s" % (len(freqs), groups))
            if not np.all(np.isfinite(freqs)):
                errors.append("/modes/frequencies_hz: non-finite values")
            summary["modes"] = [float(x) for x in freqs]
        for g in groups:
            check_bodies_group(m[g], "/modes/" + g, valid_layouts, errors)

    # XDMF next to the file: <stem>.xdmf2 always, <stem>_modes.xmf when there are modes
    stem = os.path.splitext(path)[0]
    xmfs = []
    expected = {}
    summary["xdmf"] = []
    n_modes = len(summary["modes"]) if summary.get("modes") else 0
    for xmf, want, required in ((stem + ".xdmf2", n_frames, True),
                                (stem + "_modes.xmf", n_modes, "modes" in h5)):
        if not os.path.exists(xmf):
            if required:
                errors.append("%s: missing" % xmf)
            continue
        xmfs.append(xmf)
        info = check_xdmf(xmf, h5, errors)
        if info["grids"] != want:
            errors.append("%s: %d grids, expected %d" % (xmf, info["grids"], want))
        summary["xdmf"].append(info)
        is_modes = xmf.endswith("_modes.xmf")
        expected[xmf] = (expected_steps(h5, is_modes), sum(l["points"] for l in valid_layouts.values()),
                         sum(l["points"] - 1 for l in valid_layouts.values()), last_bounds(h5, is_modes))

    return xmfs, expected


def final_state(h5):
    """(series time, last frame's time, state vector, kinetic energy) at the end of a dynamic run's output."""
    frames = h5["frames"]
    bodies = sorted(b for b in frames.keys() if isinstance(frames[b], h5py.Group))
    parts = [frames[b]["coordinates"][-1].ravel() for b in bodies]
    s = h5["series"]
    parts += [np.array([s[k][-1]]) for k in sorted(s.keys()) if k.startswith("rigid_")]
    state = np.concatenate(parts) if parts else np.zeros(0)
    return float(s["time"][-1]), float(frames["time"][-1]), state, float(s["kinetic_energy"][-1])


def compare_final(a, b):
    try:
        fa, fb = h5py.File(a, "r"), h5py.File(b, "r")
    except OSError as e:
        print(json.dumps({"a": a, "b": b, "ok": False, "errors": ["cannot open: %s" % e]}))
        return 2
    with fa, fb:
        ta, tfa, xa, ka = final_state(fa)
        tb, tfb, xb, kb = final_state(fb)
    out = {"a": a, "b": b, "time": [ta, tb], "frame_time": [tfa, tfb], "size": int(xa.size)}
    if xa.shape != xb.shape or xa.size == 0:
        out.update(ok=False, errors=["states of sizes %d and %d" % (xa.size, xb.size)])
        print(json.dumps(out))
        return 1
    scale = float(np.abs(xa).max())
    diff = float(np.abs(xa - xb).max())
    out.update(scale=scale, max_abs=diff, max_rel=diff / scale,
               rel2=float(np.linalg.norm(xa - xb) / np.linalg.norm(xa)),
               kinetic=[ka, kb], kinetic_rel=abs(ka - kb) / max(abs(ka), 1e-300), ok=True)
    print(json.dumps(out))
    return 0


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    flags = {a for a in argv[1:] if a.startswith("--")}
    if flags == {"--compare-final"} and args and len(args) % 2 == 0:
        return max(compare_final(a, b) for a, b in zip(args[::2], args[1::2]))
    if not args or flags - {"--pvpython"}:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    codes = [check_one(path, flags) for path in args]
    return max(codes)


def check_one(path, flags):
    errors = []
    summary = {"file": path}
    try:
        h5 = h5py.File(path, "r")
    except OSError as e:
        summary.update(ok=False, errors=["cannot open: %s" % e])
        print(json.dumps(summary))
        return 2

    xmfs, expected = [], {}
    with h5:
        try:
            xmfs, expected = check_file(h5, path, summary, errors)
        except Exception as e:  # e.g. a file still being written by a run (HDF5_USE_FILE_LOCKING=FALSE)
            errors.append("cannot read: %s: %s" % (type(e).__name__, e))
            xmfs = []

    if "--pvpython" in flags:
        summary["paraview"] = check_paraview(xmfs, expected, errors)

    summary["ok"] = not errors
    summary["errors"] = errors
    print(json.dumps(summary))
    return 0 if not errors else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
