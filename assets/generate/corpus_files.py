#!/usr/bin/env python3
"""What every corpus body shares (assets/generate/corpus.py): materials and units, the
reference values SciPy/ARPACK computes as a body is written, and the files of a body folder
(body.toml, nodes.csv, gzipped Matrix Market, reference.json)."""

import gzip
import json
import os
import sys
import time

import numpy as np
import scipy
import scipy.sparse as sp
import scipy.sparse.linalg as sla

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

STEEL_SI = dict(young=210e9, poisson=0.3, density=7850.0)
STEEL_MM = dict(young=210000.0, poisson=0.3, density=7.85e-9)
ALU_SI = dict(young=70e9, poisson=0.33, density=2700.0)
SI = {"length": "m", "mass": "kg", "force": "N"}
MM = {"length": "mm", "mass": "t", "force": "N"}


# ---------------------------------------------------------------------------------------------
# Reference values (SciPy / ARPACK)
# ---------------------------------------------------------------------------------------------

def hz(lam):
    return (np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi)).tolist()


def eigsh_lowest(K, M, sigma, count, tol=1e-14):
    # A fixed start vector: the same body gives the same reference on every machine.
    v0 = np.random.default_rng(1).standard_normal(K.shape[0])
    lam, phi = sla.eigsh(K, k=count, M=M, sigma=sigma, which="LM", tol=tol, v0=v0)
    order = np.argsort(lam)
    return lam[order], phi[:, order]


def free_free(K, M, count=18):
    """The lowest `count` free-free pairs by ARPACK shift-invert. A first, loose solve with a shift
    of 1e-9 of the stiffest diagonal ratio finds the 7th eigenvalue λ₇ roughly (K − σM is then
    conditioned like λ_max/|σ|, ~1e9, and its elastic eigenvalues are good to ~1e-7 only); the
    reference is then solved with the shifts −λ₇/2 and −3λ₇/10, which must agree to 1e-7 on every
    elastic eigenvalue (5e-8 in Hz, a twentieth of the import check's 1e-6), else the body is not
    written."""
    K, M = K.tocsc(), M.tocsc()
    diag = K.diagonal() / M.diagonal()
    rough, _ = eigsh_lowest(K, M, -1e-9 * diag.max(), 7, tol=1e-8)
    lam, phi = eigsh_lowest(K, M, -0.5 * rough[6], count)
    other, _ = eigsh_lowest(K, M, -0.3 * rough[6], count)
    agree = np.max(np.abs(lam[6:] - other[6:]) / lam[6:])
    if agree > 1e-7:
        raise SystemExit(f"ARPACK's two shifts disagree by {agree:.1e}")
    kphi = K @ phi
    res = np.linalg.norm(kphi - (M @ phi) * lam, axis=0)
    scale = np.where(np.arange(count) < 6, abs(K).max() * np.linalg.norm(phi, axis=0),
                     np.linalg.norm(kphi, axis=0))
    zero = int(np.sum(lam < 1e-8 * lam[6]))
    return lam, float((res / scale)[6:].max()), zero, float(agree)


def mass_properties(M, X):
    n = X.shape[0]
    T = np.zeros((3 * n, 3))
    for a in range(3):
        T[a::3, a] = 1.0
    mass = float(np.trace(T.T @ (M @ T)) / 3)
    return mass


# ---------------------------------------------------------------------------------------------
# Writing
# ---------------------------------------------------------------------------------------------

def write_mtx_gz(path, A, source):
    """Lower triangle, symmetric coordinate Matrix Market, 17 significant digits, gzip."""
    L = sp.tril(A).tocoo()
    order = np.lexsort((L.row, L.col))
    with gzip.open(path, "wt", compresslevel=6) as f:
        f.write("%%MatrixMarket matrix coordinate real symmetric\n")
        f.write(f"% written by flexmodes' assets/generate/corpus.py ({source})\n")
        f.write(f"{A.shape[0]} {A.shape[1]} {L.nnz}\n")
        for r, c, v in zip(L.row[order] + 1, L.col[order] + 1, L.data[order]):
            f.write(f"{r} {c} {float(v)!r}\n")


def write_nodes(path, X):
    with open(path, "w") as f:
        f.write("# node, x, y, z\n")
        for j, x in enumerate(X):
            f.write(f"{j + 1},{float(x[0])!r},{float(x[1])!r},{float(x[2])!r}\n")


def write_body_toml(path, name, description, units, sets, matrices, nodes="nodes.csv"):
    default = next(iter(sets))
    with open(path, "w") as f:
        f.write("# flexmodes body file, written by assets/generate/corpus.py\n")
        f.write(f'name = "{name}"\n')
        f.write(f'description = "{description}"\n')
        f.write('dofs = ["x", "y", "z"]\n')
        f.write('dof_order = "node-major"\n')
        f.write(f'default_interface = "{default}"\n\n[units]\n')
        for key, val in units.items():
            f.write(f'{key} = "{val}"\n')
        f.write("\n[matrices]\n")
        for key, val in matrices.items():
            f.write(f'{key} = "{val}"\n')
        f.write(f'\n[geometry]\nnodes = "{nodes}"\n\n[node_sets]\n')
        for set_name, ids in sets.items():
            f.write(f"{set_name} = {[int(i) for i in ids]}\n")


def finish(out, name, toolchain, description, units, K, M, X, sets, extra=None, write=True):
    """Writes the body (Matrix Market, node-major) and its reference values."""
    n = K.shape[0]
    assert n == 3 * X.shape[0], (n, X.shape)
    for s, ids in sets.items():
        assert len(ids) >= 3, f"{name}: node set {s} has {len(ids)} nodes"
    os.makedirs(out, exist_ok=True)
    source = f"{toolchain}; SciPy {scipy.__version__}"
    if write:
        write_mtx_gz(os.path.join(out, "k.mtx.gz"), K, source)
        write_mtx_gz(os.path.join(out, "m.mtx.gz"), M, source)
        write_nodes(os.path.join(out, "nodes.csv"), X)
        write_body_toml(os.path.join(out, "body.toml"), name, description, units, sets,
                        {"stiffness": "k.mtx.gz", "mass": "m.mtx.gz"})
    started = time.time()
    lam, res, zero, agree = free_free(K, M)
    eigsh_s = time.time() - started
    ref = {
        "toolchain": toolchain,
        "description": description,
        "generator": {"scipy": scipy.__version__, "numpy": np.__version__},
        "units": units,
        "dofs": int(n),
        "nodes": int(X.shape[0]),
        "node_set_sizes": {k: len(v) for k, v in sets.items()},
        "free_free_hz": hz(lam),
        "free_free_max_residual": res,
        "free_free_shift_agreement": agree,
        "zero_energy_modes": zero,
        "mass": mass_properties(M, X),
        "scipy_eigsh_s": eigsh_s,
    }
    ref.update(extra or {})
    with open(os.path.join(out, "reference.json"), "w") as f:
        json.dump(ref, f, indent=1)
    print(f"{name}: {toolchain}, {n} DOF, lowest elastic {hz(lam)[6]:.6g} Hz, "
          f"{zero} zero-energy, residual {res:.1e}, eigsh {eigsh_s:.1f} s", file=sys.stderr)


def surface_nodes_near(X, surface, centre, radius, tol, axis=2):
    """1-based surface nodes within `tol` of the cylinder of `radius` about the line through
    `centre` along `axis` (a jagged hole's surface lies within one element of it)."""
    u, v = [a for a in range(3) if a != axis]
    d = np.hypot(X[surface, u] - centre[0], X[surface, v] - centre[1])
    return (np.sort(surface[d < radius + tol]) + 1).tolist()
