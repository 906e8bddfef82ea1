"""The cost of a reduction through Python against `flexmodes export` on the same body, in the
same run, alternating: the CLI process (read, reduce, write) against `Body.from_file` +
`reduce` + `save` in this process, and against the SciPy route a script takes (matrices read
by SciPy, `flexmodes.Body(K, M, ...)`). Timings are wall-clock on this machine, reported as
ratios to the CLI; nothing is asserted.

    python3 python/benchmarks/export_vs_cli.py --body target/corpus/skfem-eyebar-si/body.toml \\
        --boundary rbe2:eye_a --binary target/release/flexmodes --runs 3
"""

from __future__ import annotations

import argparse
import gzip
import os
import subprocess
import tempfile
import time
import tomllib
from pathlib import Path
from statistics import median

import numpy as np
import scipy.io

import flexmodes


def scipy_body(toml: Path) -> flexmodes.Body:
    """The body as a script holds it: Matrix Market files read by SciPy, nodes by NumPy."""
    spec = tomllib.loads(toml.read_text())
    folder = toml.parent

    def read(name: str):
        path = folder / name
        opener = gzip.open if name.endswith(".gz") else open
        with opener(path, "rb") as f:
            return scipy.io.mmread(f)

    K = read(spec["matrices"]["stiffness"]).tocsr()
    M = read(spec["matrices"]["mass"])
    M = M.tocsr() if hasattr(M, "tocsr") else np.asarray(M).ravel()
    nodes = np.loadtxt(folder / spec["geometry"]["nodes"], delimiter=",", comments="#")
    if nodes.shape[1] == 4:
        nodes = nodes[:, 1:]
    units = spec.get("units", {})
    return flexmodes.Body(
        K, M, nodes=nodes, node_sets=spec.get("node_sets", {}), name=spec["name"],
        units=(units.get("length", "m"), units.get("mass", "kg"), units.get("force", "N")),
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--body", type=Path, required=True)
    parser.add_argument("--boundary", required=True)
    parser.add_argument("--method", default="cb")
    parser.add_argument("--modes", type=int, default=10)
    parser.add_argument("--binary", default="target/release/flexmodes")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    cli, python, via_scipy, scipy_read = [], [], [], []
    # SciPy reads Matrix Market files only (a CalculiX or Nastran body takes the file route).
    fmt = tomllib.loads(args.body.read_text())["matrices"].get("format", "matrix-market")
    with_scipy = fmt == "matrix-market"
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        for _ in range(args.runs):
            started = time.perf_counter()
            subprocess.run(
                [args.binary, "export", "--body", str(args.body), "--method", args.method,
                 "--boundary", args.boundary, "--modes", str(args.modes), "--out",
                 str(out / "cli")], check=True, capture_output=True)
            cli.append(time.perf_counter() - started)

            started = time.perf_counter()
            body = flexmodes.Body.from_file(args.body)
            model = body.reduce(args.method, args.boundary, args.modes)
            model.save(out / "python")
            python.append(time.perf_counter() - started)
            hz = model.hz

            if not with_scipy:
                continue
            started = time.perf_counter()
            held = scipy_body(args.body)
            read = time.perf_counter() - started
            held.reduce(args.method, args.boundary, args.modes).save(out / "scipy")
            via_scipy.append(time.perf_counter() - started)
            scipy_read.append(read)
        same = np.array_equal(np.load(out / "cli" / "psi.npy"), np.load(out / "python" / "psi.npy"))
    c = median(cli)
    print(f"body {args.body} ({body.dofs} DOF), {args.method} on {args.boundary}, "
          f"{args.modes} modes, median of {args.runs}, {os.cpu_count()} cores available")
    print(f"  flexmodes export (CLI process)        {c:7.2f} s  1.00")
    print(f"  Body.from_file + reduce + save         {median(python):7.2f} s  {median(python) / c:.2f}")
    if with_scipy:
        print(f"  SciPy read + Body(K, M) + reduce + save {median(via_scipy):7.2f} s  "
              f"{median(via_scipy) / c:.2f} (SciPy's reading {median(scipy_read):.2f} s of it)")
    print(f"  Ψ identical between CLI and Python: {same}; lowest Hz {hz[:3]}")


if __name__ == "__main__":
    main()
