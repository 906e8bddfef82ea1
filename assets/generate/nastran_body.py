#!/usr/bin/env python3
"""The hb-bar's matrices as Nastran DMIG cards, written by pyNastran (its BDF writer, large
field, double precision) the way a Nastran punch of `EXTSEOUT(DMIGPCH)` holds them: symmetric
(IFO 6) KAAX and MAAX, one triangle, each entry by grid and component. The matrices are the
bar's Matrix Market twin (assembled by scikit-fem in `hb_body.py`); pyNastran reads the file
back and its matrices are checked against them before the body file is written.

pyNastran 1.4.1 needs numpy < 2, so this runs in its own environment:

    python3 -m venv /tmp/nastran && /tmp/nastran/bin/pip install -r assets/generate/requirements-nastran.txt
    /tmp/nastran/bin/python assets/generate/nastran_body.py [--out tests/bodies/hb-bar]
"""

import argparse
import gzip
import os
import shutil

import numpy as np
import scipy.io
import scipy.sparse as sp
from pyNastran.bdf.bdf import BDF, read_bdf

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def read_mtx_gz(path):
    with gzip.open(path, "rb") as f:
        return sp.csc_matrix(scipy.io.mmread(f))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default=os.path.join(REPO, "tests", "bodies", "hb-bar"))
    args = p.parse_args()
    k = read_mtx_gz(os.path.join(args.out, "k.mtx.gz"))
    m = read_mtx_gz(os.path.join(args.out, "m.mtx.gz"))
    n = k.shape[0]
    model = BDF(debug=None)
    for name, a in (("KAAX", k), ("MAAX", m)):
        lower = sp.tril(a).tocoo()
        # Node-major x y z: DOF d is grid d // 3 + 1, component d % 3 + 1.
        gcj = [(int(j) // 3 + 1, int(j) % 3 + 1) for j in lower.col]
        gci = [(int(i) // 3 + 1, int(i) % 3 + 1) for i in lower.row]
        model.add_dmig(name, ifo=6, tin=2, tout=2, polar=0, ncols=n,
                       GCj=gcj, GCi=gci, Real=list(lower.data))
    path = os.path.join(args.out, "bar.pch")
    model.write_bdf(path, size=16, is_double=True, enddata=True)

    # pyNastran reads back what it wrote: the same matrices.
    back = read_bdf(path, xref=False, debug=None, punch=True)
    for name, a in (("KAAX", k), ("MAAX", m)):
        dense, rows, cols = back.dmig[name].get_matrix(is_sparse=False, apply_symmetry=True)
        order = [3 * (g - 1) + (c - 1) for (g, c) in (rows[i] for i in range(len(rows)))]
        full = np.zeros((n, n))
        full[np.ix_(order, order)] = dense
        err = abs(full - a.toarray()).max() / abs(a).max()
        # 16-column fields hold 11 significant digits (`4.3062334215D+08`): ~1e-11 each.
        assert err < 1e-10, (name, err)
        print(f"{name}: {a.nnz} entries, {len(order)} DOF, read back by pyNastran to {err:.1e}")
    with gzip.open(path + ".gz", "wb") as f, open(path, "rb") as raw:
        shutil.copyfileobj(raw, f)
    os.remove(path)

    with open(os.path.join(args.out, "body.toml")) as f:
        twin = f.read()
    head, _, rest = twin.partition("[matrices]")
    matrices = ('[matrices]\nformat = "nastran-dmig"\nstiffness = "bar.pch.gz"\n'
                'mass = "bar.pch.gz"\nstiffness_matrix = "KAAX"\nmass_matrix = "MAAX"\n')
    rest = rest.split("\n[", 1)[1]
    with open(os.path.join(args.out, "body-dmig.toml"), "w") as f:
        f.write("# written by assets/generate/nastran_body.py: DMIG cards by pyNastran\n")
        f.write(head.split("\n", 1)[1] if head.startswith("#") else head)
        f.write(matrices + "\n[" + rest)


if __name__ == "__main__":
    main()
