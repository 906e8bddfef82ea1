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
import os
import shutil

import numpy as np
import scipy.sparse as sp

from corpus_calculix import bell_crank_geometry, block_geometry, calculix_body, \
    calculix_spun_body
from corpus_files import ALU_SI, MM, SI, STEEL_MM, STEEL_SI, finish, surface_nodes_near


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
    from skfem import Basis, ElementVector
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
    from skfem.helpers import ddot, sym_grad, trace
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
