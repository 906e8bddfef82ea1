#!/usr/bin/env python3
"""Bodies meshed and assembled by codes other than flexmodes, with SciPy/LAPACK reference values.

Geometry and quadratic tetrahedral meshes by gmsh (OpenCASCADE kernel, curved second-order
elements); stiffness and consistent mass by scikit-fem (ElementTetP2, isoparametric MeshTet2);
reference frequencies by SciPy (ARPACK shift-invert on the full matrices, LAPACK `eigh` on the
reduced ones). Nothing here imports or mirrors flexmodes' own assembly.

    pip install -r assets/generate/requirements.txt
    python3 assets/generate/make_bodies.py                 # the committed bodies (tests/bodies/)
    python3 assets/generate/make_bodies.py --only steel-rod
    python3 assets/generate/make_bodies.py --large DIR     # the 32 k-DOF link for the slow tests
    python3 assets/generate/make_bodies.py --large DIR --h 0.002 --no-cases   # 92 k DOF
    python3 assets/generate/make_bodies.py --large DIR --h 0.00105 --no-cases --cholmod  # ~500 k

The committed bodies: a steel link in m-kg-s (two bores), a flanged hub in mm-t-s (a bore and
four bolt holes) and a slender rod with a cross hole at each end (its coarse mesh has one badly
shaped element, so its largest eigenvalue is 3e10 times its lowest elastic one).

Each body is a folder with body.toml, k.mtx.gz, m.mtx.gz (node-major x, y, z; full
precision), nodes.csv, edges.csv (surface triangles) and reference.json:

- free_free_hz: the lowest 18 free-free frequencies (6 zero-energy, 12 elastic);
- zero_energy_modes: how many eigenvalues lie below 1e-8 of the 7th;
- for each case in `cases` (a boundary node set and a mode count): the Guyan frequencies,
  the fixed-interface frequencies and the Craig-Bampton frequencies of the reduced matrices
  solved by LAPACK;
- mass, centre of mass, inertia tensor about the centre, all from the consistent mass matrix
  acting on rigid translations and rotations.
"""
import argparse
import gzip
import json
import os
import sys

import gmsh
import numpy as np
import scipy
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as sla
import skfem
from dataclasses import replace

from skfem import Basis, BilinearForm, ElementTetP2, ElementVector, MeshTet1, MeshTet2, asm
from skfem.models.elasticity import lame_parameters, linear_elasticity

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


# ---------------------------------------------------------------------------------------------
# Geometry (gmsh, OpenCASCADE)
# ---------------------------------------------------------------------------------------------

def link_geometry(h, length=0.12, width=0.04, thick=0.012, bore=0.008, boss=0.02):
    """A connecting link in metres: a web between two round bosses, each with a through bore."""
    occ = gmsh.model.occ
    half = length / 2 - boss
    web = occ.addBox(-half, -width / 4, 0, 2 * half, width / 2, thick * 0.6)
    b1 = occ.addCylinder(-half, 0, 0, 0, 0, thick, boss)
    b2 = occ.addCylinder(half, 0, 0, 0, 0, thick, boss * 0.8)
    body, _ = occ.fuse([(3, web)], [(3, b1), (3, b2)])
    h1 = occ.addCylinder(-half, 0, -1e-3, 0, 0, thick + 2e-3, bore)
    h2 = occ.addCylinder(half, 0, -1e-3, 0, 0, thick + 2e-3, bore * 0.75)
    occ.cut(body, [(3, h1), (3, h2)])
    occ.synchronize()
    bores = {
        "bore_a": ((-half, 0.0), bore),
        "bore_b": ((half, 0.0), bore * 0.75),
    }
    return bores, h


def flange_geometry(h, r_out=60.0, r_hub=25.0, r_bore=15.0, t_flange=10.0, l_hub=40.0,
                    r_bolt=45.0, d_bolt=5.0):
    """A flanged hub in millimetres: a disc with four bolt holes on a tube with a central bore."""
    occ = gmsh.model.occ
    disc = occ.addCylinder(0, 0, 0, 0, 0, t_flange, r_out)
    hub = occ.addCylinder(0, 0, 0, 0, 0, l_hub, r_hub)
    body, _ = occ.fuse([(3, disc)], [(3, hub)])
    tools = [(3, occ.addCylinder(0, 0, -1, 0, 0, l_hub + 2, r_bore))]
    bolts = {}
    for k in range(4):
        a = np.pi / 4 + k * np.pi / 2
        cx, cy = r_bolt * np.cos(a), r_bolt * np.sin(a)
        tools.append((3, occ.addCylinder(cx, cy, -1, 0, 0, t_flange + 2, d_bolt)))
        bolts[f"bolt_{k + 1}"] = ((cx, cy), d_bolt)
    occ.cut(body, tools)
    occ.synchronize()
    bores = {"bore": ((0.0, 0.0), r_bore)}
    bores.update(bolts)
    return bores, h


def rod_geometry(h, length=0.3, radius=0.006, hole=0.0025, inset=0.012):
    """A slender round steel rod in metres along x with a cross hole (along y) near each end:
    its lowest elastic frequency lies far below its stiffest element's, the case a shift
    chosen from the matrix diagonal gets wrong."""
    occ = gmsh.model.occ
    rod = occ.addCylinder(0, 0, 0, length, 0, 0, radius)
    a = occ.addCylinder(inset, -2 * radius, 0, 0, 4 * radius, 0, hole)
    b = occ.addCylinder(length - inset, -2 * radius, 0, 0, 4 * radius, 0, hole)
    occ.cut([(3, rod)], [(3, a), (3, b)])
    occ.synchronize()
    # Bores along y: centre (x, z) in the plane normal to y.
    return {"end_a": ((inset, 0.0), hole), "end_b": ((length - inset, 0.0), hole)}, h


def mesh_p2(geometry, h, curvature=12, **kw):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("part")
    bores, h = geometry(h, **kw)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeMin", h / 3)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", curvature)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(2)
    gmsh.model.mesh.optimize("HighOrderElastic")
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    coords = coords.reshape(-1, 3)
    index = {int(t): i for i, t in enumerate(node_tags)}
    etypes, _, enodes = gmsh.model.mesh.getElements(3)
    tets = None
    for et, en in zip(etypes, enodes):
        if et == 11:  # 10-node tetrahedron
            tets = np.array([index[int(t)] for t in en], dtype=np.int64).reshape(-1, 10)
    gmsh.finalize()
    assert tets is not None, "gmsh made no quadratic tetrahedra"
    # Keep only the nodes the tetrahedra use (gmsh keeps geometry points too).
    used = np.unique(tets)
    remap = -np.ones(len(coords), dtype=np.int64)
    remap[used] = np.arange(len(used))
    return coords[used], remap[tets], bores


# ---------------------------------------------------------------------------------------------
# Assembly (scikit-fem)
# ---------------------------------------------------------------------------------------------

def assemble(coords, tets, young, poisson, density):
    """K and consistent M of the P2 tetrahedral mesh, permuted to node-major order over the
    mesh's own nodes (vertices, then edge midpoints as scikit-fem numbers them)."""
    # gmsh's 10-node order: 4 vertices, then edges (0,1) (1,2) (2,0) (3,0) (3,2) (3,1).
    # scikit-fem's MeshTet2 takes the vertex connectivity and the midpoint coordinates.
    vert = np.unique(tets[:, :4])
    vmap = -np.ones(len(coords), dtype=np.int64)
    vmap[vert] = np.arange(len(vert))
    t = vmap[tets[:, :4]].T
    p = coords[vert].T
    base = MeshTet2.from_mesh(MeshTet1(p, t))
    # Edge midpoints of the linear mesh are replaced by gmsh's curved ones.
    mid = {}
    gmsh_edges = [(0, 1), (1, 2), (2, 0), (3, 0), (3, 2), (3, 1)]
    for e, (a, b) in enumerate(gmsh_edges):
        va, vb = vmap[tets[:, a]], vmap[tets[:, b]]
        for i in range(len(tets)):
            key = (min(va[i], vb[i]), max(va[i], vb[i]))
            mid[key] = tets[i, 4 + e]
    edges = base.edges  # 2 x nedges, vertex indices (of p)
    edge_loc = base.dofs.edge_dofs[0]  # the column of doflocs holding edge e's midpoint
    doflocs = base.doflocs.copy()
    for e in range(edges.shape[1]):
        key = (int(min(edges[0, e], edges[1, e])), int(max(edges[0, e], edges[1, e])))
        doflocs[:, edge_loc[e]] = coords[mid[key]]
    mesh = replace(base, doflocs=doflocs)
    basis = Basis(mesh, ElementVector(ElementTetP2()), intorder=4)
    lam, mu = lame_parameters(young, poisson)
    K = asm(linear_elasticity(lam, mu), basis)

    @BilinearForm
    def mass(u, v, w):
        return density * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2])

    M = asm(mass, basis)
    # Node-major permutation: node j of ours = scikit-fem node j (vertices then edges).
    nodal = basis.nodal_dofs  # 3 x nv
    edge = basis.edge_dofs  # 3 x ne
    per_node = np.hstack([nodal, edge])  # 3 x nnodes
    perm = per_node.T.reshape(-1)
    K = K[perm][:, perm].tocsr()
    M = M[perm][:, perm].tocsr()
    X = basis.doflocs[:, per_node[0]].T
    # Surface triangles (corner nodes) for the wireframe.
    facets = mesh.facets[:, mesh.boundary_facets()]
    return K, M, X, facets.T


# ---------------------------------------------------------------------------------------------
# Reference values (SciPy / LAPACK)
# ---------------------------------------------------------------------------------------------

def hz(lam):
    return (np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi)).tolist()


def mass_properties(M, X):
    """Mass, centre and inertia about the centre from the consistent M acting on rigid fields
    (exact: translations and rotations lie in the P2 space)."""
    n = X.shape[0]
    T = np.zeros((3 * n, 3))
    for a in range(3):
        T[a::3, a] = 1.0
    mass = float(np.trace(T.T @ (M @ T)) / 3)
    pos = X.reshape(-1)
    # First moment in direction a: the translation e_a against the field x_a e_a.
    first = np.array([T[:, a] @ (M @ (pos * T[:, a])) for a in range(3)])
    centre = first / mass
    xc, yc, zc = (X - centre).T
    Rc = np.zeros((3 * n, 3))
    Rc[1::3, 0], Rc[2::3, 0] = -zc, yc
    Rc[0::3, 1], Rc[2::3, 1] = zc, -xc
    Rc[0::3, 2], Rc[1::3, 2] = -yc, xc
    J = Rc.T @ (M @ Rc)
    return mass, centre.tolist(), ((J + J.T) / 2).tolist()


def cholmod_inverse(A):
    """x = A^-1 b by CHOLMOD (cholespy): a sparse Cholesky factor, where SuperLU's LU of a
    500 k-DOF part would not fit in memory."""
    from rbe2_reference import cholmod_solver  # the same solver the rigid references use
    return sla.LinearOperator(A.shape, matvec=cholmod_solver(A), dtype=float)


def free_free(K, M, X, count=18, cholmod=False):
    # A shift well below zero in the body's own scale: a tenth of the lowest elastic
    # eigenvalue estimated from a first, rough solve with a larger negative shift.
    # A shift of 1e-9 of the stiffest diagonal ratio: K - sigma M stays well conditioned
    # (1e9) and sigma lies below the lowest elastic eigenvalue of any of these parts, so the
    # ordering of 1/(lambda - sigma) is the ordering of lambda. (The median diagonal ratio,
    # tried first, is above the slender rod's bending eigenvalues: ARPACK then returned three
    # of its six rigid modes and skipped the rest.)
    diag = K.diagonal() / M.diagonal()
    sigma = -1e-9 * diag.max()
    opinv = cholmod_inverse((K - sigma * M).tocsc()) if cholmod else None
    lam, phi = sla.eigsh(K.tocsc(), k=count, M=M.tocsc(), sigma=sigma, which="LM", tol=1e-14,
                         OPinv=opinv)
    order = np.argsort(lam)
    lam, phi = lam[order], phi[:, order]
    res = np.linalg.norm(K @ phi - (M @ phi) * lam, axis=0) / (
        abs(K).max() * np.linalg.norm(phi, axis=0))
    zero = int(np.sum(lam < 1e-8 * lam[6]))
    return lam, float(res.max()), zero


def craig_bampton(K, M, boundary_nodes, modes):
    n = K.shape[0]
    b = np.array(sorted(3 * (nd - 1) + a for nd in boundary_nodes for a in range(3)))
    i = np.setdiff1d(np.arange(n), b)
    K, M = K.tocsr(), M.tocsr()
    Kii, Kib = K[i][:, i].tocsc(), K[i][:, b].toarray()
    Mii = M[i][:, i].tocsc()
    lu = sla.splu(Kii, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                  options={"SymmetricMode": True})
    Phi_c = -lu.solve(Kib)
    op = sla.LinearOperator(Kii.shape, matvec=lu.solve, dtype=float)
    lam_f, Phi = sla.eigsh(Kii, k=modes, M=Mii, sigma=0.0, OPinv=op, which="LM", tol=1e-14)
    order = np.argsort(lam_f)
    lam_f, Phi = lam_f[order], Phi[:, order]
    res_f = np.linalg.norm(Kii @ Phi - (Mii @ Phi) * lam_f, axis=0) / np.linalg.norm(Kii @ Phi, axis=0)
    nb = len(b)
    # Guyan: the constraint modes alone.
    Psi_g = np.zeros((n, nb))
    Psi_g[b, :] = np.eye(nb)
    Psi_g[i, :] = Phi_c
    Kg = Psi_g.T @ (K @ Psi_g)
    Mg = Psi_g.T @ (M @ Psi_g)
    Psi = np.zeros((n, nb + modes))
    Psi[:, :nb] = Psi_g
    Psi[i, nb:] = Phi
    Kr = Psi.T @ (K @ Psi)
    Mr = Psi.T @ (M @ Psi)

    def lapack(k, m):
        k, m = (k + k.T) / 2, (m + m.T) / 2
        s = 1.0 / np.abs(k).max()
        w = sl.eigh(k * s, m, eigvals_only=True, driver="gvd") / s
        return w

    return {
        "boundary_dofs": int(nb),
        "modes": int(modes),
        "fixed_interface_hz": hz(lam_f),
        "fixed_interface_max_residual": float(res_f.max()),
        "guyan_hz": hz(lapack(Kg, Mg))[:40],
        "cb_hz": hz(lapack(Kr, Mr))[:40],
    }


# ---------------------------------------------------------------------------------------------
# Writing
# ---------------------------------------------------------------------------------------------

def write_mtx_gz(path, A):
    """Lower triangle, symmetric coordinate Matrix Market, 17 significant digits, gzip."""
    L = sp.tril(A).tocoo()
    order = np.lexsort((L.row, L.col))
    with gzip.open(path, "wt", compresslevel=9) as f:
        f.write("%%MatrixMarket matrix coordinate real symmetric\n")
        f.write("% written by flexmodes' assets/generate/make_bodies.py (scikit-fem "
                f"{skfem.__version__}, gmsh {gmsh.__version__})\n")
        f.write(f"{A.shape[0]} {A.shape[1]} {L.nnz}\n")
        for r, c, v in zip(L.row[order] + 1, L.col[order] + 1, L.data[order]):
            f.write(f"{r} {c} {float(v)!r}\n")


def nodes_on_bore(X, centre, radius, tol, axis=2):
    """Nodes on the cylinder of `radius` about the line through `centre` along `axis` (the
    two other coordinates, in order)."""
    u, v = [a for a in range(3) if a != axis]
    d = np.hypot(X[:, u] - centre[0], X[:, v] - centre[1])
    return (np.nonzero(np.abs(d - radius) < tol)[0] + 1).tolist()


def make(out, name, description, geometry, h, units, young, poisson, density, cases, default,
         bore_axis=2, curvature=12, cholmod=False, **kw):
    os.makedirs(out, exist_ok=True)
    coords, tets, bores = mesh_p2(geometry, h, curvature, **kw)
    K, M, X, tri = assemble(coords, tets, young, poisson, density)
    n = K.shape[0]
    print(f"{name}: {X.shape[0]} nodes, {n} DOF, {len(tets)} P2 tetrahedra", file=sys.stderr)
    scale = np.abs(X).max()
    sets = {}
    for set_name, (centre, radius) in bores.items():
        sets[set_name] = nodes_on_bore(X, centre, radius, 1e-6 * scale, bore_axis)
    write_mtx_gz(os.path.join(out, "k.mtx.gz"), K)
    write_mtx_gz(os.path.join(out, "m.mtx.gz"), M)
    with open(os.path.join(out, "nodes.csv"), "w") as f:
        f.write("# node, x, y, z\n")
        for j, x in enumerate(X):
            f.write(f"{j + 1},{float(x[0])!r},{float(x[1])!r},{float(x[2])!r}\n")
    with open(os.path.join(out, "edges.csv"), "w") as f:
        f.write("# surface triangles, 1-based corner nodes\n")
        for a, b, c in tri:
            f.write(f"{a + 1},{b + 1},{c + 1}\n")
    with open(os.path.join(out, "body.toml"), "w") as f:
        f.write("# flexmodes body file, written by assets/generate/make_bodies.py\n")
        f.write(f'name = "{name}"\n')
        f.write(f'description = "{description}"\n')
        f.write('dofs = ["x", "y", "z"]\n')
        f.write('dof_order = "node-major"\n')
        f.write(f'default_interface = "{default}"\n\n')
        f.write("[units]\n")
        for key, val in units.items():
            f.write(f'{key} = "{val}"\n')
        f.write('\n[matrices]\nstiffness = "k.mtx.gz"\nmass = "m.mtx.gz"\n\n')
        f.write('[geometry]\nnodes = "nodes.csv"\nedges = "edges.csv"\n\n[node_sets]\n')
        for set_name, nodes in sets.items():
            f.write(f"{set_name} = {nodes}\n")
    lam, res, zero = free_free(K, M, X, cholmod=cholmod)
    mass, centre, inertia = mass_properties(M, X)
    ref = {
        "generator": {"scikit-fem": skfem.__version__, "gmsh": gmsh.__version__,
                      "scipy": scipy.__version__, "numpy": np.__version__},
        "dofs": int(n),
        "nodes": int(X.shape[0]),
        "node_set_sizes": {k: len(v) for k, v in sets.items()},
        "material": {"young": young, "poisson": poisson, "density": density},
        "units": units,
        "free_free_hz": hz(lam),
        "free_free_max_residual": res,
        "zero_energy_modes": zero,
        "mass": mass,
        "centre_of_mass": centre,
        "inertia_about_centre": inertia,
        "cases": [],
    }
    for boundary, modes in cases:
        case = craig_bampton(K, M, sets[boundary], modes)
        case["boundary"] = boundary
        ref["cases"].append(case)
    with open(os.path.join(out, "reference.json"), "w") as f:
        json.dump(ref, f, indent=1)
    print(json.dumps({k: ref[k] for k in ("dofs", "zero_energy_modes", "mass")}), file=sys.stderr)


LINK = dict(name="steel_link", geometry=link_geometry,
            description="steel connecting link, 120 mm, two bosses with bores of 16 and 12 mm, "
                        "quadratic tetrahedra (gmsh), consistent mass (scikit-fem), SI units",
            units={"length": "m", "mass": "kg", "force": "N"},
            young=210e9, poisson=0.3, density=7850.0,
            cases=[("bore_a", 10), ("bore_b", 6)], default="bore_a")
FLANGE = dict(name="flange_hub", geometry=flange_geometry,
              description="steel flanged hub, 120 mm disc with four bolt holes on a 40 mm tube, "
                          "quadratic tetrahedra (gmsh), consistent mass (scikit-fem), mm-t-s units",
              units={"length": "mm", "mass": "t", "force": "N"},
              young=210000.0, poisson=0.3, density=7.85e-9,
              cases=[("bore", 10), ("bolt_1", 4)], default="bore")
ROD = dict(name="steel_rod", geometry=rod_geometry, bore_axis=1, curvature=3,
           description="slender steel rod, 300 mm long, 12 mm diameter, a 5 mm cross hole near "
                       "each end, quadratic tetrahedra (gmsh), consistent mass (scikit-fem), SI",
           units={"length": "m", "mass": "kg", "force": "N"},
           young=210e9, poisson=0.3, density=7850.0,
           cases=[("end_a", 8)], default="end_a")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join(REPO, "tests", "bodies"))
    ap.add_argument("--large", metavar="DIR", help="write only the 30 k+ DOF link into DIR")
    ap.add_argument("--only", help="write only this body (steel-link, flange-hub, steel-rod)")
    ap.add_argument("--h", type=float, default=0.003,
                    help="with --large: the mesh size, m (0.003: 32 k DOF, 0.002: ~100 k)")
    ap.add_argument("--cholmod", action="store_true",
                    help="with --large: the free-free reference's shift-invert by CHOLMOD "
                         "(pip install cholespy) instead of SuperLU, whose LU of a 500 k-DOF "
                         "part does not fit in 24 GB")
    ap.add_argument("--no-cases", action="store_true",
                    help="with --large: free-free references only (no Craig-Bampton cases)")
    args = ap.parse_args()
    if args.large:
        spec = {**LINK, "name": "steel_link_large"}
        if args.no_cases:
            spec["cases"] = []
        make(args.large, h=args.h, cholmod=args.cholmod, **spec)
        return
    bodies = {"steel-link": (0.0095, LINK), "flange-hub": (16.0, FLANGE),
              "steel-rod": (0.012, ROD)}
    for folder, (h, spec) in bodies.items():
        if args.only in (None, folder):
            make(os.path.join(args.out, folder), h=h, **spec)


if __name__ == "__main__":
    main()
