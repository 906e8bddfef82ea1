#!/usr/bin/env python3
"""`flexmodes import` against SciPy's `eigsh` on the same matrices, same run, whole processes.

For each corpus body (assets/generate/corpus.py): the wall time of `flexmodes import BODY`
(parse, checks, the free-free solve with its Sturm check, the summary) and of a Python process
that reads the same Matrix Market files with SciPy and calls `eigsh(K, 18, M, sigma)` (ARPACK
shift-invert on SuperLU, sigma = -1e-9 max Kii/Mii), alternately, the minimum of `--runs`.

    python3 assets/generate/time_imports.py --binary target/release/flexmodes --corpus target/corpus
"""
import argparse
import json
import os
import subprocess
import sys
import time

SCIPY = r"""
import sys, gzip, scipy.io, scipy.sparse.linalg as sla, tomllib, os
body = sys.argv[1]; d = os.path.dirname(body); spec = tomllib.load(open(body, 'rb'))
read = lambda f: scipy.io.mmread(os.path.join(d, f)).tocsc()
K, M = read(spec['matrices']['stiffness']), read(spec['matrices']['mass'])
sigma = -1e-9 * (K.diagonal() / M.diagonal()).max()
sla.eigsh(K, k=18, M=M, sigma=sigma, which='LM')
"""


def wall(cmd):
    started = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{done.stderr[-2000:]}")
    return time.perf_counter() - started


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", default="target/release/flexmodes")
    ap.add_argument("--corpus", default="target/corpus")
    ap.add_argument("--runs", type=int, default=2)
    args = ap.parse_args()
    rows = []
    for name in sorted(os.listdir(args.corpus)):
        folder = os.path.join(args.corpus, name)
        if not os.path.exists(os.path.join(folder, "reference.json")):
            continue
        # SciPy reads Matrix Market: a CalculiX body is timed on its converted twin.
        mtx = os.path.join(folder, "converted", "body.toml")
        mtx = mtx if os.path.exists(mtx) else os.path.join(folder, "body.toml")
        ours, theirs = [], []
        for _ in range(args.runs):
            ours.append(wall([args.binary, "import", os.path.join(folder, "body.toml")]))
            theirs.append(wall([sys.executable, "-c", SCIPY, mtx]))
        dofs = json.load(open(os.path.join(folder, "reference.json")))["dofs"]
        rows.append((name, dofs, min(ours), min(theirs)))
        print(f"{name:24s} {dofs:7d} DOF  flexmodes import {min(ours):7.2f} s  "
              f"SciPy eigsh {min(theirs):7.2f} s  ratio {min(ours) / min(theirs):5.2f}",
              flush=True)
    worst = max(r[2] / r[3] for r in rows)
    print(f"worst ratio flexmodes/SciPy: {worst:.2f} (flexmodes on one thread; SciPy's SuperLU "
          f"on one, its BLAS on OPENBLAS_NUM_THREADS, {os.cpu_count()} cores)")


if __name__ == "__main__":
    main()
