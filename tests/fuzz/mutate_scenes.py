#!/usr/bin/python3
"""End-to-end mutation fuzzing of `strand run` on the shipped scenes (issue 32).

usage: mutate_scenes.py STRAND_BINARY MESHES_DIR [--mutants N] [--seconds S] [--seed K] [--keep DIR]

Each mutant is a scene of MESHES_DIR/*.yaml with 1 to 3 random edits: a number replaced by an
extreme one (0, -1, 1e308, 1e-300, 2147483647, NaN, ...), a line deleted, duplicated or moved, a
key or a value replaced by another one of the scene format, bytes inserted (invalid UTF-8, control
characters, YAML punctuation), the text cut short. Dynamic scenes run at most 5 steps (their t_end is
rewritten to 5 dt before mutating; a mutant may change that again). Each mutant runs with a 30 s
timeout, 4 GB of address space and -max_memory 2G, and must
  - exit with 0 (done), 2 (bad input: then no output file) or 3 (diverged or failed: then the output
    is readable and has a status attribute),
  - never print a PETSc error stack or an internal error, never die by a signal.
Anything else is a finding: the mutant is kept in --keep with its output. Prints a summary; exit
status 1 if there were findings. The libFuzzer target (fuzz_scene_reader.cpp) covers the reader
alone at thousands of inputs per second; this covers everything a scene reaches, at a few per second.
"""
import argparse
import glob
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

EXTREME = ["0", "-1", "-0", "1e308", "-1e308", "1e-300", "2147483647", "2147483648", "-2147483648", ".nan", ".inf",
           "-.inf", "1e999", "010", "0x10", "1.5", "3", "100000", "1e9", "~", "last", "''", "[]", "{}", "[1, 2]",
           "[0, 0, 0, 0]", "{a: 1}", "true", "nan"]
INSERTS = ["\xff", "\x01", "\x00", "\t", ": ", "- ", "[", "]", "{", "}", "&a ", "*a", "---\n", "...\n", "!!binary ",
           "%YAML 1.2\n", "? ", "|\n", ">\n", "#", "\"", "'", "\\", "\u00e9", "\ud800".encode("utf-8", "surrogatepass").decode("latin-1")]
NUMBER = re.compile(r"(?<![\w.])[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?(?![\w.])")
KEY = re.compile(r"([A-Za-z_][A-Za-z0-9_]*):")


def five_steps(text):
    """Dynamic scenes: t_end = 5 dt, so that a mutant that keeps running is still short."""
    dt = re.search(r"\bdt:\s*([0-9.eE+-]+)", text)
    if "analysis: dynamic" in text and dt:
        text = re.sub(r"\bt_end:\s*[0-9.eE+-]+", "t_end: %.17g" % (5 * float(dt.group(1))), text)
    return text


def mutate(text, keys, rng):
    for _ in range(rng.randint(1, 3)):
        lines = text.split("\n")
        kind = rng.randrange(8)
        if kind == 0:  # a number
            nums = list(NUMBER.finditer(text))
            if nums:
                m = rng.choice(nums)
                text = text[:m.start()] + rng.choice(EXTREME) + text[m.end():]
        elif kind == 1 and len(lines) > 1:  # delete a line
            del lines[rng.randrange(len(lines))]
            text = "\n".join(lines)
        elif kind == 2:  # duplicate a line
            i = rng.randrange(len(lines))
            lines.insert(i, lines[i])
            text = "\n".join(lines)
        elif kind == 3 and len(lines) > 1:  # move a line
            line = lines.pop(rng.randrange(len(lines)))
            lines.insert(rng.randrange(len(lines) + 1), line)
            text = "\n".join(lines)
        elif kind == 4:  # a key replaced by another key of the format
            ks = list(KEY.finditer(text))
            if ks:
                m = rng.choice(ks)
                text = text[:m.start(1)] + rng.choice(keys) + text[m.end(1):]
        elif kind == 5:  # a value replaced by a key word or an extreme value
            ks = list(KEY.finditer(text))
            if ks:
                m = rng.choice(ks)
                end = text.find("\n", m.end())
                end = len(text) if end < 0 else end
                text = text[:m.end()] + " " + rng.choice(keys + EXTREME) + text[end:]
        elif kind == 6:  # bytes inserted
            i = rng.randrange(len(text) + 1)
            text = text[:i] + rng.choice(INSERTS) + text[i:]
        else:  # cut short
            text = text[:rng.randrange(len(text) + 1)]
    return text


def check_output(path):
    """'' when the file is readable with a status attribute, else the reason."""
    code = ("import sys, h5py\nf = h5py.File(sys.argv[1], 'r')\nassert 'status' in f.attrs, 'no status'\n"
            "n = int(f['frames'].attrs['count']); assert f['frames/time'].shape[0] == n\n"
            "for b in f['bodies']: assert f['frames/%s/centerline' % b][()].shape[0] == n\n")
    r = subprocess.run(["/usr/bin/python3", "-c", code, path], capture_output=True, text=True)
    return "" if r.returncode == 0 else (r.stderr.strip().splitlines() or ["unreadable"])[-1]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("binary")
    p.add_argument("meshes")
    p.add_argument("--mutants", type=int, default=200)
    p.add_argument("--seconds", type=float, default=0.0, help="stop after this long (0: no limit)")
    p.add_argument("--seed", type=int, default=None)
    p.add_argument("--keep", default=None)
    a = p.parse_args()
    rng = random.Random(a.seed)
    seeds = {os.path.basename(f): five_steps(open(f, encoding="utf-8").read())
             for f in sorted(glob.glob(os.path.join(a.meshes, "*.yaml")))}
    keys = sorted({m.group(1) for t in seeds.values() for m in KEY.finditer(t)})
    work = tempfile.mkdtemp(prefix="strand-mutants-")
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    codes, findings, start = {}, 0, time.time()
    n = 0
    while n < a.mutants and (a.seconds <= 0 or time.time() - start < a.seconds):
        name = rng.choice(sorted(seeds))
        text = mutate(seeds[name], keys, rng)
        scene, out = os.path.join(work, "mutant.yaml"), os.path.join(work, "mutant.h5")
        for f in glob.glob(os.path.join(work, "mutant*")) + glob.glob(os.path.join(work, ".mutant*")):
            os.remove(f)
        with open(scene, "w", encoding="latin-1", errors="replace") as f:
            f.write(text)
        cmd = "ulimit -v 4000000; exec timeout -s KILL 30 %s run %s -o %s -overwrite -max_memory 2G" % (a.binary, scene, out)
        r = subprocess.run(["/bin/sh", "-c", cmd], capture_output=True, env=env, cwd=work)
        output = (r.stdout + r.stderr).decode("latin-1")
        code = r.returncode
        codes[code] = codes.get(code, 0) + 1
        problem = ""
        if code not in (0, 2, 3):
            problem = "exit code %d" % code
        elif "PETSC ERROR" in output or "internal error" in output:
            problem = "PETSc error stack or internal error"
        elif code == 2 and os.path.exists(out):
            problem = "bad input, but an output file was written"
        elif code in (0, 3) and os.path.exists(out):
            problem = check_output(out)
        elif code in (0, 3):
            problem = "no output file"
        n += 1
        if problem:
            findings += 1
            print("mutant %d (%s): %s\n  %s" % (n, name, problem, output.strip().splitlines()[-1:] if output else ""))
            if a.keep:
                os.makedirs(a.keep, exist_ok=True)
                shutil.copy(scene, os.path.join(a.keep, "finding%d-%s" % (n, name)))
    shutil.rmtree(work)
    print("mutate_scenes: %d mutants in %.0f s, exit codes %s, %d findings" %
          (n, time.time() - start, dict(sorted(codes.items())), findings))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
