"""Load a body exported by `flexmodes export --exudyn` into Exudyn.

The export folder's `exudyn/` holds plain files (numpy's .npy, Matrix Market, JSON), so this
adapter needs numpy, scipy and exudyn only, not flexmodes:

    from flexmodes_exudyn import load
    fem, cms, body = load("out/rod-cb/exudyn")
    parts = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0, 0, 0])

`fem` is Exudyn's own `FEMinterface` (nodes, full mass and stiffness, mode basis, node sets),
`cms` its `ObjectFFRFreducedOrderInterface` (the reduced-order FFRF invariants, computed by
Exudyn from the full matrices), `body` the export's `body.json` as a dict. The floating frame
is attached to the export's first rbe2 interface: its ring never moves in the frame, so a
motion prescribed on the frame (`parts['nRigidBody']`) drives the body through that ring.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import scipy.io
import scipy.sparse

FORMAT = "flexmodes exudyn body 1"


class ExportError(ValueError):
    """A folder that is not a readable flexmodes Exudyn export (the file and what is wrong)."""


def read_body(folder: str | Path) -> dict:
    """The export's body.json, checked for its format and files."""
    folder = Path(folder)
    path = folder / "body.json"
    if not path.is_file():
        raise ExportError(f"{path}: not found (export with `flexmodes export --exudyn`)")
    body = json.loads(path.read_text())
    if body.get("format") != FORMAT:
        raise ExportError(f"{path}: format {body.get('format')!r}, expected {FORMAT!r}")
    for name in body["files"].values():
        if not (folder / name).is_file():
            raise ExportError(f"{folder / name}: missing")
    return body


def load_fem(folder: str | Path):
    """Exudyn's FEMinterface filled from the export folder, and the body.json dict."""
    from exudyn.FEM import FEMinterface

    folder = Path(folder)
    body = read_body(folder)
    files = body["files"]
    nodes = np.load(folder / files["nodes"])
    mass = scipy.sparse.csr_matrix(scipy.io.mmread(folder / files["mass"]))
    stiffness = scipy.sparse.csr_matrix(scipy.io.mmread(folder / files["stiffness"]))
    modes = np.load(folder / files["modes"])
    n = 3 * len(nodes)
    for name, shape in (("mass", mass.shape), ("stiffness", stiffness.shape)):
        if shape != (n, n):
            raise ExportError(f"{folder / files[name]}: {shape}, expected {(n, n)} for {len(nodes)} nodes")
    if modes.shape != (n, body["modes"]):
        raise ExportError(f"{folder / files['modes']}: {modes.shape}, expected {(n, body['modes'])}")

    fem = FEMinterface()
    fem.metaData = {"source": "flexmodes", "body": body["body_name"], "units": body["units"]}
    fem.nodes = {"Position": nodes}
    fem.massMatrix = mass
    fem.stiffnessMatrix = stiffness
    fem.modeBasis = {"matrix": modes, "type": body["mode_type"]}
    fem.eigenValues = np.array(body["eigenvalues"])
    fem.nodeSets = [
        {
            "Name": s["name"],
            "NodeNumbers": np.array(s["node_numbers"], dtype=int),
            "NodeWeights": np.full(len(s["node_numbers"]), 1.0 / len(s["node_numbers"])),
        }
        for s in body["node_sets"]
    ]
    return fem, body


def load(folder: str | Path, rigid_body_node_type: str = "NodeType.RotationEulerParameters"):
    """`(fem, cms, body)`: FEMinterface, ObjectFFRFreducedOrderInterface and body.json."""
    from exudyn.FEM import ObjectFFRFreducedOrderInterface

    fem, body = load_fem(folder)
    cms = ObjectFFRFreducedOrderInterface(fem, rigidBodyNodeType=rigid_body_node_type)
    return fem, cms, body


def add_stiffening(mbs, parts: dict, folder: str | Path, body: dict | None = None) -> np.ndarray:
    """Puts the export's dynamic stiffening into Exudyn; returns the modal matrix it uses.

    A body file with a `[preload]` gives `geometric_stiffness.npy`: the modal geometric
    stiffness of the centrifugal prestress per unit rate², K_g. Exudyn's
    `ObjectFFRFreducedOrder` has no such term; this sets the object's force user function to
    f_z = -(omega . a)^2 K_g z, with omega the frame's angular velocity in body axes (from the
    rigid node's Tait-Bryan angles or Euler parameters and their rates) and a the preload's
    axis: the stiffness `flexmodes simulate` adds for a spin about that axis. `parts` is what
    `cms.AddObjectFFRFreducedOrder` returned.
    """
    from exudyn.rigidBodyUtilities import EulerParameters2GLocal, RotXYZ2GLocal

    folder = Path(folder)
    body = body if body is not None else read_body(folder)
    stiffening = body.get("stiffening")
    if not stiffening:
        raise ExportError(
            f"{folder / 'body.json'}: no geometric stiffness (the body file gives no [preload], "
            "or the export left it out with --stiffening off)"
        )
    kg = np.load(folder / stiffening["matrix"])
    m = body["modes"]
    if kg.shape != (m, m):
        raise ExportError(f"{folder / stiffening['matrix']}: {kg.shape}, expected {(m, m)}")
    axis = np.asarray(stiffening["axis"], dtype=float)

    def force(mbs, t, item, q, q_t):
        q, q_t = np.asarray(q), np.asarray(q_t)
        rigid = len(q) - m
        if rigid == 6:
            w = np.asarray(RotXYZ2GLocal(q[3:6])) @ q_t[3:6]
        elif rigid == 7:
            w = np.asarray(EulerParameters2GLocal(q[3:7])) @ q_t[3:7]
        else:
            raise ExportError(f"{rigid} rigid coordinates: expected Tait-Bryan angles or Euler parameters")
        f = np.zeros(len(q))
        f[rigid:] = -float(w @ axis) ** 2 * (kg @ q[rigid:])
        return f

    mbs.SetObjectParameter(parts["oFFRFreducedOrder"], "forceUserFunction", force)
    return kg
