#!/usr/bin/env python3
"""SciPy reference values for rigid (RBE2) interfaces, computed from a body's own files.

For each case (a list of node sets, each tied rigidly to a 6-DOF master at the centroid of its
nodes, and a mode count) the body is transformed by hand, u_s = u_m + theta_m x (x_s - x_m)
for every node s of a set, K' = T^T K T and M' = T^T M T; then Craig-Bampton is computed on
the transformed body with the masters' 6 DOF as the boundary (SuperLU solves, ARPACK for the
fixed-interface modes) and the reduced matrices are solved by LAPACK. Nothing here imports or
mirrors flexmodes.

    python3 assets/generate/rbe2_reference.py tests/bodies/steel-link "bore_a" "bore_a,bore_b"

writes rbe2_reference.json beside the body file;

    python3 assets/generate/rbe2_reference.py --cholmod --modes=20 DIR bore_a

does the same with CHOLMOD (pip install cholespy) in place of SuperLU and 20 fixed-interface
modes: the 512 k-DOF link (`make_bodies.py --large DIR --h 0.00105 --no-cases --cholmod`),
whose SuperLU factor would not fit in 24 GB;

    python3 assets/generate/rbe2_reference.py --ccm tests/bodies/steel-link bore_a 6,12,24,48

writes ccm_reference.json: Craig-Bampton on the set with its interface reduced to n_c
characteristic constraint modes (Castanier, Tan & Pierre 2001), for each n_c.

The committed references were made by:

    python3 assets/generate/rbe2_reference.py tests/bodies/steel-link bore_a bore_a,bore_b
    python3 assets/generate/rbe2_reference.py tests/bodies/flange-hub bore bore,bolt_1
    python3 assets/generate/rbe2_reference.py --ccm tests/bodies/steel-link bore_a 6,12,24,48

Run them again whenever make_bodies.py rewrites the bodies.
"""
import csv
import gzip
import json
import os
import sys
import tomllib

import numpy as np
import scipy.io
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as sla

MODES = 10


def read_matrix(path):
    with gzip.open(path, "rb") as f:
        return sp.csr_matrix(scipy.io.mmread(f))


def read_nodes(path):
    rows = []
    with open(path) as f:
        for row in csv.reader(f):
            if not row or row[0].startswith("#"):
                continue
            rows.append([float(v) for v in row[1:4]])
    return np.array(rows)


def transformation(n_nodes, nodes, sets):
    """T (3 n_nodes x n') and the master DOF (last 6 per set, in order)."""
    slave = {}
    masters = []
    for k, s in enumerate(sets):
        xm = nodes[np.array(s) - 1].mean(axis=0)
        masters.append(xm.tolist())
        for nd in s:
            if nd in slave:
                raise ValueError(f"node {nd} is in two rigid interfaces")
            slave[nd] = (k, nodes[nd - 1] - xm)
    free = [nd for nd in range(1, n_nodes + 1) if nd not in slave]
    n_free = 3 * len(free)
    ncols = n_free + 6 * len(sets)
    rows, cols, vals = [], [], []
    for j, nd in enumerate(free):
        for a in range(3):
            rows.append(3 * (nd - 1) + a)
            cols.append(3 * j + a)
            vals.append(1.0)
    for nd, (k, r) in slave.items():
        base = n_free + 6 * k
        for a in range(3):
            row = 3 * (nd - 1) + a
            rows.append(row); cols.append(base + a); vals.append(1.0)
            # (theta x r)_a = eps_abc theta_b r_c
            for b in range(3):
                c = 3 - a - b
                if a == b or c < 0 or c > 2 or c == a or c == b:
                    continue
                sign = 1.0 if (a, b, c) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] else -1.0
                rows.append(row); cols.append(base + 3 + b); vals.append(sign * r[c])
    T = sp.csr_matrix((vals, (rows, cols)), shape=(3 * n_nodes, ncols))
    boundary = np.arange(n_free, ncols)
    return T, boundary, masters


def lapack_hz(k, m):
    k, m = (k + k.T) / 2, (m + m.T) / 2
    s = 1.0 / np.abs(k).max()
    w = sl.eigh(k * s, m, eigvals_only=True, driver="gvd") / s
    return (np.sqrt(np.clip(w, 0.0, None)) / (2 * np.pi)).tolist()


def cholmod_solver(A):
    """B -> A^-1 B by CHOLMOD (cholespy), for parts whose SuperLU factor would not fit."""
    from cholespy import CholeskySolverD, MatrixType
    C = sp.coo_matrix(A)
    ch = CholeskySolverD(A.shape[0], C.row.astype(np.int32), C.col.astype(np.int32), C.data,
                         MatrixType.COO)

    def solve(B):
        B = np.asarray(B, dtype=np.float64)
        flat = B.ndim == 1
        B = np.ascontiguousarray(B.reshape(A.shape[0], -1))
        X = np.zeros_like(B)
        ch.solve(B, X)
        return X[:, 0] if flat else X
    return solve


def interior_pieces(K, M, b, modes, cholmod=False):
    """The interior i, the constraint modes' interior rows -K_ii^-1 K_ib (SuperLU, or CHOLMOD
    with `cholmod`) and the lowest fixed-interface modes (ARPACK shift-invert at 0 through the
    same factor)."""
    n = K.shape[0]
    i = np.setdiff1d(np.arange(n), b)
    K, M = K.tocsr(), M.tocsr()
    Kii, Kib = K[i][:, i].tocsc(), K[i][:, b].toarray()
    Mii = M[i][:, i].tocsc()
    if cholmod:
        solve = cholmod_solver(Kii)
    else:
        solve = sla.splu(Kii, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                         options={"SymmetricMode": True}).solve
    op = sla.LinearOperator(Kii.shape, matvec=solve, dtype=float)
    lam, Phi = sla.eigsh(Kii, k=modes, M=Mii, sigma=0.0, OPinv=op, which="LM", tol=1e-14)
    order = np.argsort(lam)
    return i, -solve(Kib), lam[order], Phi[:, order]


def craig_bampton(K, M, b, modes, cholmod=False):
    n = K.shape[0]
    i, psi_s, lam, Phi = interior_pieces(K, M, b, modes, cholmod)
    K, M = K.tocsr(), M.tocsr()
    nb = len(b)
    Psi = np.zeros((n, nb + modes))
    Psi[b, :nb] = np.eye(nb)
    Psi[i, :nb] = psi_s
    Psi[i, nb:] = Phi
    Kr, Mr = Psi.T @ (K @ Psi), Psi.T @ (M @ Psi)
    Kg, Mg = Kr[:nb, :nb], Mr[:nb, :nb]
    return {"cb_hz": lapack_hz(Kr, Mr), "guyan_hz": lapack_hz(Kg, Mg),
            "fixed_interface_hz": (np.sqrt(lam) / (2 * np.pi)).tolist()}


def main():
    args = sys.argv[1:]
    cholmod = "--cholmod" in args
    args = [a for a in args if a != "--cholmod"]
    modes = MODES
    if args and args[0].startswith("--modes="):
        modes = int(args.pop(0).split("=", 1)[1])
    folder, cases = args[0], args[1:]
    spec = tomllib.load(open(os.path.join(folder, "body.toml"), "rb"))
    K = read_matrix(os.path.join(folder, spec["matrices"]["stiffness"]))
    M = read_matrix(os.path.join(folder, spec["matrices"]["mass"]))
    nodes = read_nodes(os.path.join(folder, spec["geometry"]["nodes"]))
    out = {"generator": "assets/generate/rbe2_reference.py (SciPy %s)" % scipy.__version__,
           "master": "centroid of the set's nodes", "cases": []}
    for case in cases:
        names = case.split(",")
        sets = [spec["node_sets"][name] for name in names]
        T, b, masters = transformation(len(nodes), nodes, sets)
        Kt, Mt = (T.T @ K @ T).tocsr(), (T.T @ M @ T).tocsr()
        result = craig_bampton(Kt, Mt, b, modes, cholmod)
        result.update({"interfaces": names, "modes": modes, "master_points": masters})
        out["cases"].append(result)
        print(names, "CB", ["%.6g" % f for f in result["cb_hz"][:10]], file=sys.stderr)
    with open(os.path.join(folder, "rbe2_reference.json"), "w") as f:
        json.dump(out, f, indent=1)




def characteristic_constraint_modes(folder, set_name, counts, modes=MODES):
    """Castanier-Tan-Pierre's interface reduction of Craig-Bampton on one node set: the
    Guyan-reduced boundary matrices K_g = Psi_c^T K Psi_c, M_g = Psi_c^T M Psi_c are solved by
    LAPACK, the lowest n_c eigenvectors Phi_c kept, and the basis [Psi_c Phi_c, Phi_fixed]
    solved again by LAPACK; for each n_c in counts."""
    spec = tomllib.load(open(os.path.join(folder, "body.toml"), "rb"))
    K = read_matrix(os.path.join(folder, spec["matrices"]["stiffness"])).tocsr()
    M = read_matrix(os.path.join(folder, spec["matrices"]["mass"])).tocsr()
    nodes = spec["node_sets"][set_name]
    n = K.shape[0]
    b = np.array(sorted(3 * (nd - 1) + a for nd in nodes for a in range(3)))
    i, psi_s, _, Phi = interior_pieces(K, M, b, modes)
    nb = len(b)
    Psi_c = np.zeros((n, nb))
    Psi_c[b, :] = np.eye(nb)
    Psi_c[i, :] = psi_s
    Kg, Mg = Psi_c.T @ (K @ Psi_c), Psi_c.T @ (M @ Psi_c)
    Kg, Mg = (Kg + Kg.T) / 2, (Mg + Mg.T) / 2
    s = 1.0 / np.abs(Kg).max()
    w, V = sl.eigh(Kg * s, Mg, driver="gvd")
    cases = []
    for nc in counts:
        Psi = np.zeros((n, nc + modes))
        Psi[:, :nc] = Psi_c @ V[:, :nc]
        Psi[i, nc:] = Phi
        Kr, Mr = Psi.T @ (K @ Psi), Psi.T @ (M @ Psi)
        cases.append({"interface_modes": int(nc), "modes": modes, "hz": lapack_hz(Kr, Mr),
                      "characteristic_hz": (np.sqrt(np.clip(w[:nc] / s, 0, None))
                                            / (2 * np.pi)).tolist()})
        print(set_name, nc, ["%.6g" % f for f in cases[-1]["hz"][6:12]], file=sys.stderr)
    out = {"generator": "assets/generate/rbe2_reference.py --ccm (SciPy %s)" % scipy.__version__,
           "interface": set_name, "boundary_dofs": int(nb), "cases": cases}
    with open(os.path.join(folder, "ccm_reference.json"), "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    if sys.argv[1] == "--ccm":
        # rbe2_reference.py --ccm FOLDER SET N1,N2,...
        characteristic_constraint_modes(sys.argv[2], sys.argv[3],
                                        [int(x) for x in sys.argv[4].split(",")])
    else:
        main()
