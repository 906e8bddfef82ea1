#!/usr/bin/env python3
"""The corpus' CalculiX bodies (assets/generate/corpus.py): gmsh C3D10 meshes of OpenCASCADE
parts written as .inp decks, K and M written by CalculiX itself (`*FREQUENCY,
SOLVER=MATRIXSTORAGE`) and CalculiX's own free-free frequencies read from its .dat."""

import gzip
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import scipy.sparse as sp

from corpus_files import MM, STEEL_MM, finish, surface_nodes_near, write_body_toml, \
    write_mtx_gz, write_nodes

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
