#!/usr/bin/env python3
"""A body spinning about an axis, written by CalculiX 2.20 (Debian `calculix-ccx`) alone.

A steel lever (mm-t-s): a bar of C3D8 bricks along x with its root face (x = 0) clamped on a
hub whose axis is z through the origin. CalculiX runs four decks in OUT:

* `job`: the free-free body, `*FREQUENCY, SOLVER=MATRIXSTORAGE` (K and M: job.sti, job.mas,
  job.dof) -- the body flexmodes imports;
* `spun`: the root held (`*BOUNDARY ROOT, 1, 3`), a `*STATIC` step loaded by `*DLOAD EALL,
  CENTRIF, W0^2, 0, 0, 0, 0, 0, 1`, then `*STEP, PERTURBATION` with `*FREQUENCY,
  SOLVER=MATRIXSTORAGE`: spun.sti holds the stiffness with the stress stiffening and the spin
  softening at W0, spun.dof the DOF left free -- the body file's `[preload]`;
* `rate1`, `rate2`: the same prestressed frequency step with `*FREQUENCY` at W0 and 2 W0:
  CalculiX's own spinning frequencies, the references (reference.json, `spinning_hz`).

Usage: spun_body.py --out DIR [--rate 1000 --elements 12 2 2]
"""

import argparse
import gzip
import json
import os
import shutil
import subprocess


def frequencies(dat):
    """The CYCLES/TIME column of CalculiX's last eigenvalue output (7 printed digits)."""
    with open(dat) as f:
        text = f.read()
    block = text.split("E I G E N V A L U E   O U T P U T")[-1].split("P A R T I C I P")[0]
    out = []
    for line in block.splitlines():
        parts = line.split()
        if len(parts) == 5 and parts[0].isdigit():
            out.append(float(parts[3]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--rate", type=float, default=1000.0, help="W0, rad/s")
    ap.add_argument("--elements", type=int, nargs=3, default=[12, 2, 2])
    ap.add_argument("--size", type=float, nargs=3, default=[100.0, 10.0, 5.0], help="mm")
    args = ap.parse_args()
    out = args.out
    os.makedirs(out, exist_ok=True)
    nx, ny, nz = args.elements
    lx, ly, lz = args.size
    idx, nodes = {}, []
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                idx[i, j, k] = len(nodes) + 1
                nodes.append((i * lx / nx, j * ly / ny - ly / 2, k * lz / nz - lz / 2))
    bricks = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                bricks.append([idx[i, j, k], idx[i + 1, j, k], idx[i + 1, j + 1, k], idx[i, j + 1, k],
                               idx[i, j, k + 1], idx[i + 1, j, k + 1], idx[i + 1, j + 1, k + 1],
                               idx[i, j + 1, k + 1]])
    root = [idx[0, j, k] for k in range(nz + 1) for j in range(ny + 1)]
    tip = [idx[nx, j, k] for k in range(nz + 1) for j in range(ny + 1)]

    def deck(name, step, held):
        s = ["** written by flexmodes' assets/generate/spun_body.py", "*NODE,NSET=NALL"]
        s += [f"{n + 1},{x!r},{y!r},{z!r}" for n, (x, y, z) in enumerate(nodes)]
        s.append("*ELEMENT,TYPE=C3D8,ELSET=EALL")
        s += [f"{e + 1}," + ",".join(map(str, c)) for e, c in enumerate(bricks)]
        s.append("*NSET,NSET=ROOT")
        s += [f"{n}," for n in root]
        s += ["*MATERIAL,NAME=STEEL", "*ELASTIC", "210000.0,0.3", "*DENSITY", "7.85e-09",
              "*SOLID SECTION,ELSET=EALL,MATERIAL=STEEL"]
        if held:
            s += ["*BOUNDARY", "ROOT,1,3"]
        with open(os.path.join(out, name + ".inp"), "w") as f:
            f.write("\n".join(s) + "\n" + step)

    w2 = args.rate**2
    centrif = lambda w2: (f"*STEP\n*STATIC\n*DLOAD\nEALL,CENTRIF,{w2!r},0.,0.,0.,0.,0.,1.\n"
                          "*END STEP\n")
    deck("job", "*STEP\n*FREQUENCY,SOLVER=MATRIXSTORAGE\n*END STEP\n", held=False)
    deck("spun", centrif(w2) + "*STEP,PERTURBATION\n*FREQUENCY,SOLVER=MATRIXSTORAGE\n*END STEP\n",
         held=True)
    deck("rate1", centrif(w2) + "*STEP,PERTURBATION\n*FREQUENCY\n10\n*END STEP\n", held=True)
    deck("rate2", centrif(4 * w2) + "*STEP,PERTURBATION\n*FREQUENCY\n10\n*END STEP\n", held=True)
    for job in ("job", "spun", "rate1", "rate2"):
        done = subprocess.run(["ccx", "-i", job], cwd=out, capture_output=True, text=True)
        if done.returncode != 0 or "Job finished" not in done.stdout:
            raise SystemExit(f"CalculiX failed on {job}.inp:\n{done.stdout[-2000:]}")
    reference = {
        "toolchain": "CalculiX " + subprocess.run(["ccx", "-v"], capture_output=True,
                                                  text=True).stdout.split("Version")[-1].strip(),
        "rates_rad_s": [args.rate, 2 * args.rate],
        "spinning_hz": [frequencies(os.path.join(out, "rate1.dat")),
                        frequencies(os.path.join(out, "rate2.dat"))],
        "drive": "rbe2:root",
        "axis": [0.0, 0.0, 1.0],
    }
    for f in ("job.sti", "job.mas", "job.dof", "spun.sti", "spun.dof"):
        with open(os.path.join(out, f), "rb") as src, gzip.GzipFile(os.path.join(out, f + ".gz"),
                                                                       "wb", mtime=0) as dst:
            shutil.copyfileobj(src, dst)
        os.remove(os.path.join(out, f))
    for f in os.listdir(out):
        if f.split(".")[-1] in ("12d", "cvg", "sta", "frd", "dat", "out") or f == "spooles.out":
            os.remove(os.path.join(out, f))
    for f in ("rate1.inp", "rate2.inp", "spun.mas"):
        os.remove(os.path.join(out, f))
    with open(os.path.join(out, "nodes.csv"), "w") as f:
        f.write("# node, x, y, z\n")
        f.writelines(f"{n + 1},{x!r},{y!r},{z!r}\n" for n, (x, y, z) in enumerate(nodes))
    with open(os.path.join(out, "reference.json"), "w") as f:
        json.dump(reference, f, indent=1)
    with open(os.path.join(out, "body.toml"), "w") as f:
        f.write(f"""# flexmodes body file, written by assets/generate/spun_body.py
name = "spun_lever"
description = "steel lever, {nx}x{ny}x{nz} C3D8 bricks, K, M and the stiffness spun at {args.rate:g} rad/s about z written by CalculiX, mm-t-s"
dofs = ["x", "y", "z"]
default_interface = "root"

[units]
length = "mm"
mass = "t"
force = "N"

[matrices]
format = "calculix"
stiffness = "job.sti.gz"
mass = "job.mas.gz"
dof_map = "job.dof.gz"

# CalculiX's stiffness of the body held at its root and spun about z through the origin
# (spun.inp's CENTRIF load): stress stiffening and spin softening at that rate.
[preload]
stiffness = "spun.sti.gz"
dof_map = "spun.dof.gz"
deck = "spun.inp"

[geometry]
nodes = "nodes.csv"

[node_sets]
root = {root}
tip = {tip}
""")
    print(json.dumps(reference, indent=1))


if __name__ == "__main__":
    main()
