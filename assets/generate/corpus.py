#!/usr/bin/env python3
"""A corpus of external bodies from four FE toolchains, each with the reference values its own
toolchain (SciPy/ARPACK, CalculiX) computed when it was written.

Nothing here imports or mirrors flexmodes' own assembly. The bodies vary what breaks partial
eigensolvers: sizes from 3 k to 150 k DOF, SI and mm-t-s, thin walls, jagged surfaces carved
by removing elements, symmetric parts with repeated frequencies, stiff inserts, elements of very
different sizes and a nearly free mechanism.

Toolchains:
- scikit-fem on its own structured meshes (MeshTet/MeshHex.init_tensor), features carved by
  removing elements (only the face-connected part kept), P2 tetrahedra or trilinear hexahedra;
- gmsh (OpenCASCADE) meshes assembled by scikit-fem (assets/generate/make_bodies.py; its
  committed bodies live in tests/bodies/ and are part of the corpus);
- FElupe (its Grid hexahedral meshes, its SolidBody stiffness and mass);
- CalculiX 2.20 (Debian `calculix-ccx`): gmsh C3D10 meshes written as .inp decks, K and M
  written by CalculiX itself (`*FREQUENCY, SOLVER=MATRIXSTORAGE`: job.sti, job.mas, job.dof),
  and CalculiX's own free-free frequencies (`*FREQUENCY` with a negative lower bound) read from
  its .dat. Each CalculiX body is written twice: read directly (`format = "calculix"`) and
  converted to Matrix Market (node-major) by SciPy, its "converted twin".

    pip install -r assets/generate/requirements.txt
    apt-get install calculix-ccx
    python3 assets/generate/corpus.py --out target/corpus                 # every body but 150 k
    python3 assets/generate/corpus.py --out target/corpus --only skfem-eyebar-si
    python3 assets/generate/corpus.py --list

Each body is a folder with body.toml (and for CalculiX bodies converted/body.toml),
nodes.csv and reference.json:

- toolchain, units, dofs, nodes;
- free_free_hz: 6 zero-energy and the 12 lowest elastic free-free frequencies by ARPACK
  (shift-invert, two shifts that must agree to 1e-9) with their largest residual;
- zero_energy_modes: eigenvalues below 1e-8 of the 7th;
- calculix_hz (CalculiX bodies): the frequencies CalculiX printed (7 digits).
"""
import argparse
import gzip
import json
import os
import re
import shutil
import subprocess
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


# ---------------------------------------------------------------------------------------------
# scikit-fem on its own structured meshes
# ---------------------------------------------------------------------------------------------

def face_connected(mesh):
    """The elements of `mesh` face-connected to its largest part (carving can leave elements
    that touch the rest at a vertex or an edge only: mechanisms no real part has)."""
    t2f = mesh.t2f
    nel = mesh.t.shape[1]
    f2t = {}
    for e in range(nel):
        for f in t2f[:, e]:
            f2t.setdefault(int(f), []).append(e)
    adj = sp.lil_matrix((nel, nel))
    for pair in f2t.values():
        if len(pair) == 2:
            adj[pair[0], pair[1]] = 1
    count, label = sp.csgraph.connected_components(adj.tocsr(), directed=False)
    big = np.argmax(np.bincount(label))
    return np.nonzero(label == big)[0]


def skfem_vector_body(mesh, element, material, intorder):
    from skfem import Basis, BilinearForm, ElementVector, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity
    basis = Basis(mesh, ElementVector(element), intorder=intorder)
    return basis, assemble_skfem(basis, material)


def assemble_skfem(basis, material, young_field=None):
    from skfem import BilinearForm, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity
    lam, mu = lame_parameters(material["young"], material["poisson"])
    K = asm(linear_elasticity(lam, mu), basis)
    rho = material["density"]

    @BilinearForm
    def mass(u, v, w):
        return rho * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2])

    return K, asm(mass, basis)


def skfem_node_major(basis, K, M, p2):
    nodal = basis.nodal_dofs
    per_node = np.hstack([nodal, basis.edge_dofs]) if p2 else nodal
    perm = per_node.T.reshape(-1)
    K = K[perm][:, perm].tocsr()
    M = M[perm][:, perm].tocsr()
    X = basis.doflocs[:, per_node[0]].T
    return K, M, X, per_node


def skfem_eyebar(out, name, cells, scale, units, material, description):
    """A steel eye-bar on scikit-fem's own structured tetrahedral mesh: two eyes and a waist
    carved by removing elements (jagged surfaces), quadratic tetrahedra, consistent mass."""
    from skfem import ElementTetP2, MeshTet
    L, W, T = 0.24, 0.06, 0.02
    nx = cells
    ny, nz = max(3, round(nx * W / L)), max(2, round(nx * T / L))
    m = MeshTet.init_tensor(np.linspace(0, L, nx + 1), np.linspace(-W / 2, W / 2, ny + 1),
                            np.linspace(0, T, nz + 1))
    c = m.p[:, m.t].mean(axis=1)
    eyes = {"eye_a": ((0.03, 0.0), 0.011), "eye_b": ((L - 0.03, 0.0), 0.008)}
    remove = (np.abs(c[0] - L / 2) < 0.04) & (np.abs(c[1]) > 0.012)
    for (cx, cy), r in eyes.values():
        remove |= np.hypot(c[0] - cx, c[1] - cy) < r
    m = MeshTet(m.p, m.t[:, ~remove])
    m = MeshTet(m.p, m.t[:, face_connected(m)]).remove_unused_nodes()
    m = m.scaled(scale)
    basis, (K, M) = skfem_vector_body(m, ElementTetP2(), material, 4)
    K, M, X, per_node = skfem_node_major(basis, K, M, p2=True)
    surface = boundary_nodes(basis, per_node)
    h = scale * L / nx
    sets = {s: surface_nodes_near(X, surface, (scale * cx, scale * cy), scale * r, 1.5 * h)
            for s, ((cx, cy), r) in eyes.items()}
    finish(out, name, "scikit-fem (structured MeshTet, carved)", description, units, K, M, X,
           sets)


def boundary_nodes(basis, per_node):
    """0-based node numbers (node-major order) of the dofs on boundary facets."""
    dofs = basis.get_dofs().flatten()
    on = np.zeros(basis.N, dtype=bool)
    on[dofs] = True
    return np.nonzero(on[per_node[0]])[0]


def skfem_thin_plate(out, name, cells, units, material, scale, description):
    """A thin-walled channel: 2 mm walls, 200 mm long, P2 tetrahedra on a structured mesh with
    the inside of the channel and a row of lightening holes removed."""
    from skfem import ElementTetP2, MeshTet
    L, W, H, t = 0.2, 0.06, 0.04, 0.002
    xs = np.linspace(0, L, cells + 1)
    ys = np.unique(np.concatenate([np.linspace(0, W, 9), [t, W - t]]))
    zs = np.unique(np.concatenate([np.linspace(0, H, 6), [t]]))
    m = MeshTet.init_tensor(xs, ys, zs)
    c = m.p[:, m.t].mean(axis=1)
    inside = (c[1] > t) & (c[1] < W - t) & (c[2] > t)
    holes = np.zeros_like(inside)
    for k in range(4):
        holes |= (np.hypot(c[0] - (0.04 + 0.04 * k), c[1] - W / 2) < 0.012) & (c[2] < t)
    m = MeshTet(m.p, m.t[:, ~(inside | holes)])
    m = MeshTet(m.p, m.t[:, face_connected(m)]).remove_unused_nodes().scaled(scale)
    basis, (K, M) = skfem_vector_body(m, ElementTetP2(), material, 4)
    K, M, X, per_node = skfem_node_major(basis, K, M, p2=True)
    tol = 1e-9 * scale
    sets = {"end_a": (np.nonzero(np.abs(X[:, 0]) < tol)[0] + 1).tolist(),
            "end_b": (np.nonzero(np.abs(X[:, 0] - scale * L) < tol)[0] + 1).tolist()}
    finish(out, name, "scikit-fem (structured MeshTet, thin walls)", description, units, K, M,
           X, sets)


def skfem_hex_cube(out, name, cells, units, material, scale, description):
    """A cube of trilinear hexahedra on a uniform grid: its cubic symmetry makes frequencies
    repeated twice and three times."""
    from skfem import ElementHex1, MeshHex
    g = np.linspace(0, scale * 0.05, cells + 1)
    m = MeshHex.init_tensor(g, g, g)
    basis, (K, M) = skfem_vector_body(m, ElementHex1(), material, 3)
    K, M, X, _ = skfem_node_major(basis, K, M, p2=False)
    tol = 1e-9 * scale
    face = np.abs(X[:, 2]) < tol
    centre = np.hypot(X[:, 0] - scale * 0.025, X[:, 1] - scale * 0.025) < scale * 0.012
    sets = {"pad": (np.nonzero(face & centre)[0] + 1).tolist()}
    finish(out, name, "scikit-fem (structured MeshHex, symmetric)", description, units, K, M,
           X, sets)


def skfem_insert(out, name, cells, units, scale, description):
    """An aluminium block with a steel insert a thousand times stiffer (E 70 GPa vs 70 TPa,
    an insert idealised as nearly rigid), P2 tetrahedra on a structured mesh with a bore
    through the insert carved out."""
    from skfem import Basis, ElementTetP2, ElementVector, MeshTet, asm, BilinearForm
    from skfem.helpers import ddot, sym_grad, trace, eye
    from skfem.models.elasticity import lame_parameters
    L, W, T = 0.1, 0.05, 0.02
    m = MeshTet.init_tensor(np.linspace(0, L, cells + 1), np.linspace(0, W, cells // 2 + 1),
                            np.linspace(0, T, max(2, cells // 5) + 1))
    c = m.p[:, m.t].mean(axis=1)
    bore = np.hypot(c[0] - 0.07, c[1] - W / 2) < 0.006
    m = MeshTet(m.p, m.t[:, ~bore])
    m = MeshTet(m.p, m.t[:, face_connected(m)]).remove_unused_nodes().scaled(scale)
    basis = Basis(m, ElementVector(ElementTetP2()), intorder=4)
    c = m.p[:, m.t].mean(axis=1) / scale
    stiff = (np.hypot(c[0] - 0.07, c[1] - W / 2) < 0.014).astype(float)
    young = basis.zeros()  # placeholder to get shapes
    e_el = ALU_SI["young"] * (1 + 999.0 * stiff) * (1e-6 if scale == 1000.0 else 1.0)
    rho_el = (ALU_SI["density"] * (1 - stiff) + 7850.0 * stiff) * (1e-12 if scale == 1000.0
                                                                  else 1.0)
    nu = 0.3
    lam_el = e_el * nu / ((1 + nu) * (1 - 2 * nu))
    mu_el = e_el / (2 * (1 + nu))
    nq = basis.X.shape[-1]
    lam_q = np.repeat(lam_el[:, None], nq, axis=1)
    mu_q = np.repeat(mu_el[:, None], nq, axis=1)
    rho_q = np.repeat(rho_el[:, None], nq, axis=1)

    @BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return w["lam"] * trace(eu) * trace(ev) + 2 * w["mu"] * ddot(eu, ev)

    @BilinearForm
    def mass(u, v, w):
        return w["rho"] * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2])

    K = asm(stiffness, basis, lam=lam_q, mu=mu_q)
    M = asm(mass, basis, rho=rho_q)
    del young
    K, M, X, per_node = skfem_node_major(basis, K, M, p2=True)
    surface = boundary_nodes(basis, per_node)
    sets = {"bore": surface_nodes_near(X, surface, (scale * 0.07, scale * W / 2),
                                       scale * 0.006, scale * 1.5 * L / cells),
            "end": (np.nonzero(np.abs(X[:, 0]) < 1e-9 * scale)[0] + 1).tolist()}
    finish(out, name, "scikit-fem (structured MeshTet, stiff insert)", description, units, K, M,
           X, sets)


# ---------------------------------------------------------------------------------------------
# gmsh + scikit-fem (assets/generate/make_bodies.py's meshing and assembly)
# ---------------------------------------------------------------------------------------------

def graded_plate_geometry(h):
    """A 100 x 50 x 8 mm plate (in metres) with a 20 mm bore and a 2 mm pin hole beside it:
    curvature-driven sizing makes elements near the pin hole ~10 times smaller than the rest."""
    import gmsh
    occ = gmsh.model.occ
    plate = occ.addBox(0, 0, 0, 0.1, 0.05, 0.008)
    tools = [(3, occ.addCylinder(0.03, 0.025, -0.001, 0, 0, 0.01, 0.01)),
             (3, occ.addCylinder(0.075, 0.025, -0.001, 0, 0, 0.01, 0.001))]
    occ.cut([(3, plate)], tools)
    occ.synchronize()
    return {"bore": ((0.03, 0.025), 0.01), "pin": ((0.075, 0.025), 0.001)}, h


def gmsh_skfem_graded(out, name, h, description):
    import make_bodies
    coords, tets, bores = make_bodies.mesh_p2(graded_plate_geometry, h, 16)
    K, M, X, _ = make_bodies.assemble(coords, tets, **STEEL_SI)
    scale = np.abs(X).max()
    sets = {s: make_bodies.nodes_on_bore(X, c, r, 1e-6 * scale) for s, (c, r) in bores.items()}
    finish(out, name, "gmsh + scikit-fem (graded P2 tetrahedra)", description, SI, K, M, X, sets)


# ---------------------------------------------------------------------------------------------
# FElupe
# ---------------------------------------------------------------------------------------------

def felupe_assemble(points, cells_by_material):
    """K and M summed over sub-meshes of one point set, one material each (FElupe's Grid
    hexahedra, its LinearElastic umat and its mass matrix)."""
    import felupe as fem
    K = M = None
    for cells, mat in cells_by_material:
        mesh = fem.Mesh(points, cells, "hexahedron")
        region = fem.RegionHexahedron(mesh)
        field = fem.FieldContainer([fem.Field(region, dim=3)])
        solid = fem.SolidBody(fem.LinearElastic(E=mat["young"], nu=mat["poisson"]), field,
                              density=mat["density"])
        k = solid.assemble.matrix()
        mm = solid.assemble.mass()
        K = k if K is None else K + k
        M = mm if M is None else M + mm
    return sp.csr_matrix(K), sp.csr_matrix(M)


def felupe_graded(out, name, units, material, scale, description):
    """A block of trilinear hexahedra graded geometrically from 0.2 mm to 8 mm (element sizes
    40 times apart), a pad of nodes at the fine end."""
    import felupe as fem
    x = np.cumsum(np.concatenate([[0], 0.0002 * 1.18 ** np.arange(26)]))
    y = np.linspace(0, 0.03, 9)
    z = np.linspace(0, 0.012, 5)
    mesh = fem.Grid(x * scale, y * scale, z * scale)
    K, M = felupe_assemble(mesh.points, [(mesh.cells, material)])
    X = mesh.points
    sets = {"fine_end": (np.nonzero(np.abs(X[:, 0]) < 1e-9 * scale)[0] + 1).tolist(),
            "coarse_end": (np.nonzero(np.abs(X[:, 0] - x[-1] * scale) < 1e-9 * scale)[0]
                           + 1).tolist()}
    finish(out, name, "FElupe (graded Grid, hexahedra)", description, units, K, M, X, sets)


def felupe_mechanism(out, name, units, scale, description, ratio=1e-5):
    """Two steel blocks joined by a 1 mm layer 1e5 times softer: a nearly free mechanism (the
    lowest elastic frequency 300 times below the blocks' own)."""
    import felupe as fem
    x = np.unique(np.concatenate([np.linspace(0, 0.05, 11), np.linspace(0.051, 0.101, 11)]))
    y = np.linspace(0, 0.03, 7)
    z = np.linspace(0, 0.02, 5)
    mesh = fem.Grid(x * scale, y * scale, z * scale)
    centre_x = mesh.points[mesh.cells].mean(axis=1)[:, 0] / scale
    layer = (centre_x > 0.05) & (centre_x < 0.051)
    mat = STEEL_SI if scale == 1.0 else STEEL_MM
    soft = dict(mat, young=mat["young"] * ratio)
    K, M = felupe_assemble(mesh.points, [(mesh.cells[~layer], mat), (mesh.cells[layer], soft)])
    X = mesh.points
    sets = {"left": (np.nonzero(np.abs(X[:, 0]) < 1e-9 * scale)[0] + 1).tolist(),
            "right": (np.nonzero(np.abs(X[:, 0] - 0.101 * scale) < 1e-9 * scale)[0]
                      + 1).tolist()}
    finish(out, name, "FElupe (Grid, soft layer)", description, units, K, M, X, sets)


# ---------------------------------------------------------------------------------------------
# CalculiX
# ---------------------------------------------------------------------------------------------

def gmsh_c3d10(geometry, h):
    """gmsh C3D10 mesh of an OpenCASCADE part: node coordinates and 10-node connectivity in
    CalculiX's order (gmsh's last two midside nodes swapped)."""
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("part")
    holes = geometry()
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeMin", h / 3)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 10)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(2)
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    xyz = xyz.reshape(-1, 3)
    et, _, en = gmsh.model.mesh.getElements(3)
    tets = [np.array(e, dtype=np.int64).reshape(-1, 10) for t, e in zip(et, en) if t == 11][0]
    gmsh.finalize()
    index = {int(t): i for i, t in enumerate(tags)}
    tets = np.vectorize(index.get)(tets)
    used = np.unique(tets)
    remap = -np.ones(len(xyz), dtype=np.int64)
    remap[used] = np.arange(len(used))
    tets = remap[tets][:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
    return xyz[used], tets, holes


def bracket_geometry():
    """An angle bracket in mm: a 100 x 60 x 6 base with two bolt holes, an 80 x 60 x 6 upright
    with a 20 mm bore, a triangular rib."""
    import gmsh
    occ = gmsh.model.occ
    base = occ.addBox(0, 0, 0, 100, 60, 6)
    upright = occ.addBox(0, 0, 0, 6, 60, 80)
    rib = occ.addWedge(6, 27, 6, 50, 6, 50)
    body, _ = occ.fuse([(3, base)], [(3, upright), (3, rib)])
    tools = [(3, occ.addCylinder(70, 15, -1, 0, 0, 8, 5)), (3, occ.addCylinder(70, 45, -1, 0, 0, 8, 5)),
             (3, occ.addCylinder(-1, 30, 55, 8, 0, 0, 10))]
    occ.cut(body, tools)
    occ.synchronize()
    return {"bolt_a": ((70.0, 15.0), 5.0, 2), "bolt_b": ((70.0, 45.0), 5.0, 2),
            "bore": ((30.0, 55.0), 10.0, 0)}


def block_geometry():
    """A 60 x 24 x 10 mm block with a 10 mm through bore: a small CalculiX body."""
    import gmsh
    occ = gmsh.model.occ
    body = occ.addBox(0, 0, 0, 60, 24, 10)
    occ.cut([(3, body)], [(3, occ.addCylinder(15, 12, -1, 0, 0, 12, 5))])
    occ.synchronize()
    return {"bore": ((15.0, 12.0), 5.0, 2)}


def bell_crank_geometry():
    """A steel bell crank in mm: a hub (radius 22, 20 thick) on a 10 mm pivot bore about z
    through the origin, two arms 14 x 10 radial to it, one along +x to an eye at x = 130, one
    along +y to an eye at y = 95 (radius 13, bore 6): parts whose arms stretch under their own
    centrifugal load when the crank turns about its pivot."""
    import gmsh
    occ = gmsh.model.occ
    hub = occ.addCylinder(0, 0, -10, 0, 0, 20, 22)
    arm_a = occ.addBox(15, -7, -5, 105, 14, 10)
    arm_b = occ.addBox(-7, 15, -5, 14, 72, 10)
    eye_a = occ.addCylinder(130, 0, -6, 0, 0, 12, 13)
    eye_b = occ.addCylinder(0, 95, -6, 0, 0, 12, 13)
    body, _ = occ.fuse([(3, hub)], [(3, arm_a), (3, arm_b), (3, eye_a), (3, eye_b)])
    tools = [(3, occ.addCylinder(0, 0, -11, 0, 0, 22, 10)),
             (3, occ.addCylinder(130, 0, -7, 0, 0, 14, 6)),
             (3, occ.addCylinder(0, 95, -7, 0, 0, 14, 6))]
    occ.cut(body, tools)
    occ.synchronize()
    return {"pivot": ((0.0, 0.0), 10.0, 2), "eye_a": ((130.0, 0.0), 6.0, 2),
            "eye_b": ((0.0, 95.0), 6.0, 2)}


def ccx_number(v):
    """A coordinate as CalculiX reads it: its fields hold 20 characters, so a longer repr
    (-5.3884459162483544e-15) is written with 13 decimals of mantissa instead."""
    text = repr(float(v))
    return text if len(text) <= 20 else f"{float(v):.13e}"


def calculix_deck(path, X, tets, material, step):
    with open(path, "w") as f:
        f.write("** written by flexmodes' assets/generate/corpus.py\n*NODE\n")
        for j, p in enumerate(X):
            f.write(f"{j + 1}," + ",".join(ccx_number(p[a]) for a in range(3)) + "\n")
        f.write("*ELEMENT,TYPE=C3D10,ELSET=EALL\n")
        for e, nodes in enumerate(tets):
            f.write(f"{e + 1}," + ",".join(str(int(v) + 1) for v in nodes) + "\n")
        f.write("*MATERIAL,NAME=STEEL\n*ELASTIC\n"
                f"{material['young']!r},{material['poisson']!r}\n"
                f"*DENSITY\n{material['density']!r}\n"
                "*SOLID SECTION,ELSET=EALL,MATERIAL=STEEL\n")
        f.write(step)


def run_ccx(folder, job):
    done = subprocess.run(["ccx", "-i", job], cwd=folder, capture_output=True, text=True)
    if done.returncode != 0 or "Job finished" not in done.stdout:
        raise SystemExit(f"CalculiX failed on {folder}/{job}.inp:\n{done.stdout[-2000:]}")


def calculix_frequencies(dat):
    """The CYCLES/TIME column of CalculiX's eigenvalue output (its 7 printed digits)."""
    hz_out = []
    with open(dat) as f:
        text = f.read()
    block = text.split("E I G E N V A L U E   O U T P U T")[1].split("P A R T I C I P")[0]
    for line in block.splitlines():
        parts = line.split()
        if len(parts) == 5 and parts[0].isdigit():
            hz_out.append(float(parts[3]))
    return hz_out


def read_calculix_matrix(path, n):
    rows, cols, vals = np.loadtxt(path, unpack=True)
    rows, cols = rows.astype(np.int64) - 1, cols.astype(np.int64) - 1
    upper = sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()
    return (upper + sp.triu(upper, 1).T).tocsr()


def calculix_body(out, name, h, units, material, description, geometry=bracket_geometry):
    """A C3D10 bracket meshed by gmsh, K and M written by CalculiX itself; its frequencies
    computed by CalculiX. Written twice: CalculiX's own files (body.toml, format "calculix")
    and converted to node-major Matrix Market (converted/body.toml)."""
    X, tets, holes = gmsh_c3d10(geometry, h)
    os.makedirs(out, exist_ok=True)
    calculix_deck(os.path.join(out, "job.inp"), X, tets, material,
                  "*STEP\n*FREQUENCY,SOLVER=MATRIXSTORAGE\n*END STEP\n")
    calculix_deck(os.path.join(out, "frequency.inp"), X, tets, material,
                  "*STEP\n*FREQUENCY\n18,-1.0\n*END STEP\n")
    run_ccx(out, "job")
    run_ccx(out, "frequency")
    ccx_hz = calculix_frequencies(os.path.join(out, "frequency.dat"))
    eqs = []
    with open(os.path.join(out, "job.dof")) as f:
        for line in f:
            node, comp = line.strip().split(".")
            eqs.append(3 * (int(node) - 1) + int(comp) - 1)
    n_eq = len(eqs)
    K_eq = read_calculix_matrix(os.path.join(out, "job.sti"), n_eq)
    M_eq = read_calculix_matrix(os.path.join(out, "job.mas"), n_eq)
    # Equation -> node-major DOF.
    n = 3 * X.shape[0]
    assert sorted(eqs) == list(range(n)), "CalculiX left out DOF of the mesh"
    P = sp.coo_matrix((np.ones(n_eq), (np.array(eqs), np.arange(n_eq))), shape=(n, n_eq)).tocsr()
    K = (P @ K_eq @ P.T).tocsr()
    M = (P @ M_eq @ P.T).tocsr()
    for junk in ("job.12d", "job.cvg", "job.sta", "job.frd", "job.dat", "frequency.12d",
                 "frequency.cvg", "frequency.sta", "frequency.frd", "spooles.out"):
        p = os.path.join(out, junk)
        if os.path.exists(p):
            os.remove(p)
    with open(os.path.join(out, "frequency.dat")) as f:
        dat = f.read()
    with gzip.open(os.path.join(out, "frequency.dat.gz"), "wt") as f:
        f.write(dat)
    os.remove(os.path.join(out, "frequency.dat"))
    # Surface nodes: those on exactly one tetrahedron face (corner nodes of boundary faces).
    faces = np.sort(np.concatenate([tets[:, [0, 1, 2]], tets[:, [0, 1, 3]], tets[:, [1, 2, 3]],
                                    tets[:, [0, 2, 3]]]), axis=1)
    uniq, counts = np.unique(faces, axis=0, return_counts=True)
    surface = np.unique(uniq[counts == 1])
    sets = {}
    for hname, (centre, radius, axis) in holes.items():
        sets[hname] = surface_nodes_near(X, surface, centre, radius, 0.05 * radius, axis)
    # CalculiX's own files, byte for byte, gzip-compressed (flexmodes reads either).
    for ext in ("sti", "mas", "dof"):
        path = os.path.join(out, f"job.{ext}")
        with open(path, "rb") as f, gzip.open(path + ".gz", "wb", compresslevel=6) as g:
            g.write(f.read())
        os.remove(path)
    write_nodes(os.path.join(out, "nodes.csv"), X)
    write_body_toml(os.path.join(out, "body.toml"), name, description, units, sets,
                    {"format": "calculix", "stiffness": "job.sti.gz", "mass": "job.mas.gz",
                     "dof_map": "job.dof.gz"})
    conv = os.path.join(out, "converted")
    os.makedirs(conv, exist_ok=True)
    write_mtx_gz(os.path.join(conv, "k.mtx.gz"), K, "CalculiX 2.20 MATRIXSTORAGE, converted")
    write_mtx_gz(os.path.join(conv, "m.mtx.gz"), M, "CalculiX 2.20 MATRIXSTORAGE, converted")
    write_body_toml(os.path.join(conv, "body.toml"), name + "_converted", description, units,
                    sets, {"stiffness": "k.mtx.gz", "mass": "m.mtx.gz"}, nodes="../nodes.csv")
    finish(out, name, "CalculiX 2.20 (gmsh C3D10 mesh)", description, units, K, M, X, sets,
           extra={"calculix_hz": ccx_hz}, write=False)
    return X, tets, holes, sets


def calculix_spun_body(out, name, h, rate, description, geometry, drive):
    """A CalculiX body (as calculix_body) spun about the axis of its hole `drive`, that hole's
    surface nodes held: CalculiX's stiffness after a static CENTRIF step at `rate` (rad/s),
    written by a perturbation step with MATRIXSTORAGE (the body file's [preload]), and
    CalculiX's own prestressed frequencies at `rate` and 2 `rate` (reference.json,
    `spinning_hz`)."""
    X, tets, holes, sets = calculix_body(out, name, h, MM, STEEL_MM, description, geometry)
    (c1, c2), _, axis_index = holes[drive]
    others = [a for a in range(3) if a != axis_index]
    point = [0.0, 0.0, 0.0]
    point[others[0]], point[others[1]] = c1, c2
    axis = [0.0, 0.0, 0.0]
    axis[axis_index] = 1.0
    held = "*NSET,NSET=DRIVE\n" + "".join(f"{n},\n" for n in sets[drive]) + \
        "*BOUNDARY\nDRIVE,1,3\n"

    def centrif(w2):
        return (f"*STEP\n*STATIC\n*DLOAD\nEALL,CENTRIF,{w2!r},{point[0]!r},{point[1]!r},"
                f"{point[2]!r},{axis[0]!r},{axis[1]!r},{axis[2]!r}\n*END STEP\n")
    decks = {
        "spun": "*STEP,PERTURBATION\n*FREQUENCY,SOLVER=MATRIXSTORAGE\n*END STEP\n",
        "rate1": "*STEP,PERTURBATION\n*FREQUENCY\n10\n*END STEP\n",
        "rate2": "*STEP,PERTURBATION\n*FREQUENCY\n10\n*END STEP\n",
    }
    for job, step in decks.items():
        w2 = (2 * rate) ** 2 if job == "rate2" else rate ** 2
        calculix_deck(os.path.join(out, job + ".inp"), X, tets, STEEL_MM, held + centrif(w2) + step)
        run_ccx(out, job)
    spinning = [calculix_frequencies(os.path.join(out, f"rate{k}.dat")) for k in (1, 2)]
    for f in ("spun.sti", "spun.dof"):
        with open(os.path.join(out, f), "rb") as src, \
                gzip.GzipFile(os.path.join(out, f + ".gz"), "wb", mtime=0) as dst:
            shutil.copyfileobj(src, dst)
    for f in os.listdir(out):
        if f.startswith(("spun.", "rate1.", "rate2.")) and f not in ("spun.sti.gz", "spun.dof.gz",
                                                                    "spun.inp") \
                or f == "spooles.out":
            os.remove(os.path.join(out, f))
    with open(os.path.join(out, "body.toml"), "a") as f:
        f.write("\n# CalculiX's stiffness of the body held at its drive and spun about the hole's "
                "axis (spun.inp's CENTRIF load)\n[preload]\nstiffness = \"spun.sti.gz\"\n"
                "dof_map = \"spun.dof.gz\"\ndeck = \"spun.inp\"\n")
    with open(os.path.join(out, "reference.json")) as f:
        ref = json.load(f)
    ref.update({"spinning_hz": spinning, "rates_rad_s": [rate, 2 * rate],
                "spin_drive": f"rbe2:{drive}", "spin_axis": axis, "spin_axis_point": point})
    with open(os.path.join(out, "reference.json"), "w") as f:
        json.dump(ref, f, indent=1)
    print(f"{name}: spun at {rate} and {2 * rate} rad/s, CalculiX's first frequencies "
          f"{spinning[0][0]} and {spinning[1][0]} Hz", file=sys.stderr)


# ---------------------------------------------------------------------------------------------
# The corpus
# ---------------------------------------------------------------------------------------------

BODIES = {
    # scikit-fem, structured, carved
    "skfem-eyebar-si": (lambda o: skfem_eyebar(
        o, "skfem_eyebar_si", 42, 1.0, SI, STEEL_SI,
        "steel eye-bar 240 mm, scikit-fem structured P2 tetrahedra, eyes and waist carved by "
        "removing elements, SI"), "large"),
    "skfem-eyebar-mm": (lambda o: skfem_eyebar(
        o, "skfem_eyebar_mm", 24, 1000.0, MM, STEEL_MM,
        "steel eye-bar 240 mm, scikit-fem structured P2 tetrahedra, carved, mm-t-s"), "small"),
    "skfem-eyebar-150k": (lambda o: skfem_eyebar(
        o, "skfem_eyebar_150k", 64, 1.0, SI, STEEL_SI,
        "steel eye-bar 240 mm, scikit-fem structured P2 tetrahedra, carved, SI, ~150 k DOF"),
        "huge"),
    "skfem-thin-channel": (lambda o: skfem_thin_plate(
        o, "skfem_thin_channel", 24, SI, STEEL_SI, 1.0,
        "steel channel 200 mm, 2 mm walls, lightening holes, scikit-fem structured P2, SI"),
        "small"),
    "skfem-hex-cube": (lambda o: skfem_hex_cube(
        o, "skfem_hex_cube", 10, MM, STEEL_MM, 1000.0,
        "steel cube 50 mm, uniform trilinear hexahedra (repeated frequencies), mm-t-s"),
        "small"),
    "skfem-insert": (lambda o: skfem_insert(
        o, "skfem_insert", 14, MM, 1000.0,
        "aluminium block with an insert 1000x stiffer around a bore, scikit-fem P2, mm-t-s"),
        "small"),
    # gmsh + scikit-fem
    "gmsh-skfem-graded": (lambda o: gmsh_skfem_graded(
        o, "gmsh_skfem_graded", 0.006,
        "steel plate with a 20 mm bore and a 2 mm pin hole, gmsh P2 tetrahedra graded ~10:1, "
        "scikit-fem, SI"), "small"),
    # FElupe
    "felupe-graded": (lambda o: felupe_graded(
        o, "felupe_graded", SI, STEEL_SI, 1.0,
        "steel block, FElupe hexahedra graded 0.2 to 8 mm, SI"), "small"),
    "felupe-mechanism": (lambda o: felupe_mechanism(
        o, "felupe_mechanism", MM, 1000.0,
        "two steel blocks joined by a layer 1e5 times softer (nearly free), FElupe, mm-t-s"),
        "small"),
    # CalculiX
    "ccx-block": (lambda o: calculix_body(
        o, "ccx_block", 12.0, MM, STEEL_MM,
        "steel block with a bore, gmsh C3D10, K and M written by CalculiX 2.20, mm-t-s",
        block_geometry), "small"),
    "ccx-lever": (lambda o: calculix_spun_body(
        o, "ccx_lever", 12.0, 3000.0,
        "steel block with a bore as a lever spun about the bore, gmsh C3D10, K, M and the "
        "stiffness spun at 3000 rad/s written by CalculiX 2.20, mm-t-s", block_geometry, "bore"),
        "small"),
    "ccx-bracket": (lambda o: calculix_body(
        o, "ccx_bracket", 18.0, MM, STEEL_MM,
        "steel angle bracket, gmsh C3D10, K and M written by CalculiX 2.20, mm-t-s"), "small"),
    "ccx-bracket-large": (lambda o: calculix_body(
        o, "ccx_bracket_large", 5.0, MM, STEEL_MM,
        "steel angle bracket, gmsh C3D10, K and M written by CalculiX 2.20, mm-t-s, 30 k+ DOF"),
        "large"),
    "ccx-bell-crank": (lambda o: calculix_spun_body(
        o, "ccx_bell_crank", 4.0, 1000.0,
        "steel bell crank, two arms radial to its pivot, gmsh C3D10, K, M and the stiffness "
        "spun at 1000 rad/s about the pivot written by CalculiX 2.20, mm-t-s, 30 k+ DOF",
        bell_crank_geometry, "pivot"), "part"),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="target/corpus")
    ap.add_argument("--only", help="comma-separated body names")
    ap.add_argument("--small", action="store_true", help="only the small bodies")
    ap.add_argument("--huge", action="store_true", help="also the 150 k-DOF body")
    ap.add_argument("--parts", action="store_true",
                    help="also the spun real parts (ccx-bell-crank, ~8 min: CI leaves them out)")
    ap.add_argument("--list", action="store_true")
    args = ap.parse_args()
    if args.list:
        for name, (_, size) in BODIES.items():
            print(f"{name}\t{size}")
        return
    only = set(args.only.split(",")) if args.only else None
    for name, (build, size) in BODIES.items():
        if only is not None and name not in only:
            continue
        if only is None and (size == "huge" and not args.huge
                             or size == "part" and not args.parts
                             or size != "small" and args.small):
            continue
        folder = os.path.join(args.out, name)
        if os.path.exists(folder):
            shutil.rmtree(folder)
        build(folder)


if __name__ == "__main__":
    main()
