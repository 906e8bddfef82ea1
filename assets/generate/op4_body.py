#!/usr/bin/env python3
"""The hb-bar's matrices as Nastran OUTPUT4 (OP4) files, written by pyyeti (NASA's
`pyyeti.nastran.op4`), in the FE code's own equation order of `k.mapping` (the order the
Harwell-Boeing twin uses): `bar.op4.gz` binary, double precision, sparse "bigmat" (what Nastran
writes for large matrices), and `bar-ascii.op4.gz` ASCII with 16 digits, K in sparse
"nonbigmat" strings and M dense. pyyeti reads each file back and its matrices are checked
against the Matrix Market twin before the body files are written.

pyyeti works with numpy 2 but pulls pandas, matplotlib and numba, so it has its own
environment:

    python3 -m venv /tmp/op4 && /tmp/op4/bin/pip install -r assets/generate/requirements-op4.txt
    /tmp/op4/bin/python assets/generate/op4_body.py [--out tests/bodies/hb-bar]
"""

import argparse
import gzip
import os
import shutil
import tempfile

import numpy as np
import scipy.io
import scipy.sparse as sp
from pyyeti.nastran import op4

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
LABELS = {"UX": 0, "UY": 1, "UZ": 2}


def read_mtx_gz(path):
    with gzip.open(path, "rb") as f:
        return sp.csc_matrix(scipy.io.mmread(f))


def equation_order(path):
    """Body DOF (0-based, node-major x y z) of each equation of the mapping file."""
    order = []
    with open(path) as f:
        next(f)
        for line in f:
            eqn, node, dof = line.split()
            assert int(eqn) == len(order) + 1
            order.append(3 * (int(node) - 1) + LABELS[dof])
    return np.array(order)


def gzip_file(path):
    with open(path, "rb") as raw, gzip.open(path + ".gz", "wb") as f:
        shutil.copyfileobj(raw, f)
    os.remove(path)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default=os.path.join(REPO, "tests", "bodies", "hb-bar"))
    args = p.parse_args()
    order = equation_order(os.path.join(args.out, "k.mapping"))
    k = read_mtx_gz(os.path.join(args.out, "k.mtx.gz"))[order][:, order]
    m = read_mtx_gz(os.path.join(args.out, "m.mtx.gz"))[order][:, order]
    files = {
        "bar.op4": dict(binary=True, sparse="bigmat", matrices={"KAAX": k, "MAAX": m}),
        "bar-ascii.op4": dict(binary=False, sparse="nonbigmat", digits=16,
                              matrices={"KAAX": k, "MAAX": m.toarray()}),
    }
    for name, spec in files.items():
        path = os.path.join(args.out, name)
        matrices = spec.pop("matrices")
        kwargs = {key: value for key, value in spec.items() if key != "sparse"}
        if isinstance(matrices["MAAX"], np.ndarray):
            # K as nonbigmat strings, M dense: write them one by one into one file.
            with tempfile.TemporaryDirectory() as tmp:
                parts = []
                for matrix, sparse in (("KAAX", spec["sparse"]), ("MAAX", "dense")):
                    part = os.path.join(tmp, matrix)
                    op4.write(part, {matrix: matrices[matrix]}, sparse=sparse, **kwargs)
                    parts.append(part)
                with open(path, "wb") as out:
                    for part in parts:
                        with open(part, "rb") as f:
                            out.write(f.read())
        else:
            op4.write(path, matrices, sparse=spec["sparse"], **kwargs)
        back = op4.read(path, sparse=True)
        for matrix, original in (("KAAX", k), ("MAAX", m)):
            a = sp.csc_matrix(back[matrix.lower()])
            err = abs(a - original).max() / abs(original).max()
            assert err < 1e-15, (name, matrix, err)
            print(f"{name} {matrix}: {original.nnz} entries, read back by pyyeti to {err:.1e}")
        gzip_file(path)

    with open(os.path.join(args.out, "body-hb.toml")) as f:
        hb = f.read()
    head, _, rest = hb.partition("[matrices]")
    rest = rest.split("\n[", 1)[1]
    head = head.split("\n", 1)[1] if head.startswith("#") else head
    for body, op4_file, what in (("body-op4.toml", "bar.op4.gz", "binary, bigmat"),
                                 ("body-op4-ascii.toml", "bar-ascii.op4.gz", "ASCII")):
        with open(os.path.join(args.out, body), "w") as f:
            f.write(f"# written by assets/generate/op4_body.py: OP4 ({what}) by pyyeti\n")
            f.write(head)
            f.write(f'[matrices]\nformat = "op4"\nstiffness = "{op4_file}"\nmass = "{op4_file}"\n'
                    'stiffness_matrix = "KAAX"\nmass_matrix = "MAAX"\ndof_map = "k.mapping"\n')
            f.write("\n[" + rest)


if __name__ == "__main__":
    main()
