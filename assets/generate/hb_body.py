#!/usr/bin/env python3
"""A small body written in the Harwell-Boeing format the way ANSYS HBMAT ships one: a coarse
steel bar meshed by gmsh, assembled by scikit-fem (P2 tetrahedra, consistent mass), its K and M
renumbered in an FE code's own equation order and written by SciPy's `hb_write` (RUA), with the
DOF map (`Matrix Eqn Node DOF`, labels UX UY UZ) beside them; the same matrices as Abaqus
matrix-input lines (node, DOF, node, DOF, value; lower triangle, in that equation order); and
its Matrix Market twin in the body's own node order. Both body files describe the same body: flexmodes must read the same
matrices from either.

Usage: hb_body.py [--out tests/bodies/hb-bar]
"""

import argparse
import gzip
import io
import os

import numpy as np
import scipy.io
import scipy.sparse as sp

import make_bodies as mb


def bar_geometry(h, length=0.1, width=0.02, thick=0.01):
    """A plain steel bar in metres along x, no holes: a coarse mesh stays small."""
    mb.gmsh.model.occ.addBox(0, 0, 0, length, width, thick)
    mb.gmsh.model.occ.synchronize()
    return {}, h


def write_hb_gz(path, a):
    buffer = io.StringIO()
    scipy.io.hb_write(buffer, sp.csc_matrix(a))
    with gzip.open(path, "wt") as f:
        f.write(buffer.getvalue())


def write_abaqus_gz(path, a, order):
    """Abaqus `*MATRIX OUTPUT, FORMAT=MATRIX INPUT` lines (row node, row DOF, column node,
    column DOF, value; the lower triangle), in the order of the equations `order` walks."""
    a = sp.tril(sp.csr_matrix(a)).tocsr()
    rank = np.empty(len(order), dtype=np.int64)
    rank[order] = np.arange(len(order))
    with gzip.open(path, "wt") as f:
        f.write("** written by assets/generate/hb_body.py in Abaqus matrix-input form\n")
        for i in order:
            row = a.getrow(i)
            for j, v in sorted(zip(row.indices, row.data), key=lambda e: rank[e[0]]):
                f.write(f"{i // 3 + 1},{i % 3 + 1}, {j // 3 + 1},{j % 3 + 1}, {v:.16E}\n")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=os.path.join(mb.REPO, "tests", "bodies", "hb-bar"))
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    coords, tets, _ = mb.mesh_p2(bar_geometry, 0.01, 0)
    K, M, X, tri = mb.assemble(coords, tets, 210e9, 0.3, 7850.0)
    n = K.shape[0]
    nodes = X.shape[0]
    print(f"hb-bar: {nodes} nodes, {n} DOF")
    # The twin in the body's node order.
    mb.write_mtx_gz(os.path.join(args.out, "k.mtx.gz"), K)
    mb.write_mtx_gz(os.path.join(args.out, "m.mtx.gz"), M)
    with open(os.path.join(args.out, "nodes.csv"), "w") as f:
        f.write("# node, x, y, z\n")
        for j, x in enumerate(X):
            f.write(f"{j + 1},{float(x[0])!r},{float(x[1])!r},{float(x[2])!r}\n")
    # An FE code's own equation order: nodes in a shuffled order, x y z within a node.
    rng = np.random.default_rng(7)
    order = rng.permutation(nodes)
    dof_of_equation = np.array([3 * j + a for j in order for a in range(3)])
    perm = sp.csc_matrix((np.ones(n), (np.arange(n), dof_of_equation)), shape=(n, n))
    write_hb_gz(os.path.join(args.out, "k.rua.gz"), perm @ K @ perm.T)
    write_hb_gz(os.path.join(args.out, "m.rua.gz"), perm @ M @ perm.T)
    write_abaqus_gz(os.path.join(args.out, "k_abaqus.mtx.gz"), K, dof_of_equation)
    write_abaqus_gz(os.path.join(args.out, "m_abaqus.mtx.gz"), M, dof_of_equation)
    with open(os.path.join(args.out, "k.mapping"), "w") as f:
        f.write(" Matrix Eqn   Node   DOF\n")
        for eq, dof in enumerate(dof_of_equation):
            f.write(f"{eq + 1:>11d} {dof // 3 + 1:>6d}    {'UX UY UZ'.split()[dof % 3]}\n")
    end = [j + 1 for j in range(nodes) if X[j, 0] < 1e-9]
    common = (
        'dofs = ["x", "y", "z"]\ndof_order = "node-major"\ndefault_interface = "end"\n\n'
        '[units]\nlength = "m"\nmass = "kg"\nforce = "N"\n\n'
    )
    geometry = f'\n[geometry]\nnodes = "nodes.csv"\n\n[node_sets]\nend = {end}\n'
    with open(os.path.join(args.out, "body.toml"), "w") as f:
        f.write("# written by assets/generate/hb_body.py: the Matrix Market twin\n")
        f.write('name = "hb_bar"\n' + common)
        f.write('[matrices]\nstiffness = "k.mtx.gz"\nmass = "m.mtx.gz"\n' + geometry)
    with open(os.path.join(args.out, "body-abaqus.toml"), "w") as f:
        f.write("# written by assets/generate/hb_body.py: Abaqus matrix-input lines\n")
        f.write('name = "hb_bar"\n' + common)
        f.write('[matrices]\nformat = "abaqus"\nstiffness = "k_abaqus.mtx.gz"\n'
                'mass = "m_abaqus.mtx.gz"\n' + geometry)
    with open(os.path.join(args.out, "body-hb.toml"), "w") as f:
        f.write("# written by assets/generate/hb_body.py: Harwell-Boeing in an FE code's order\n")
        f.write('name = "hb_bar"\n' + common)
        f.write('[matrices]\nformat = "harwell-boeing"\nstiffness = "k.rua.gz"\n'
                'mass = "m.rua.gz"\ndof_map = "k.mapping"\n' + geometry)


if __name__ == "__main__":
    main()
