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
