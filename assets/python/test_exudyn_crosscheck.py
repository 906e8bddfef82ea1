"""Cross-check: a body exported by flexmodes, loaded into Exudyn by flexmodes_exudyn.py and
driven there, against the same driven motion simulated by `flexmodes simulate`.

Both codes get the same external-FE body (gmsh + scikit-fem, tests/bodies/), the same
Craig-Bampton basis with the floating frame on the drive's rbe2 ring, the same spin-up of the
frame (Exudyn: the frame's six rigid coordinates prescribed by coordinate constraints; flexmodes:
`simulate --motion spin-up`) and the same generalized-alpha step and spectral radius. Checked:
the reduced frequencies Exudyn computes from the exported full matrices equal flexmodes' to
1e-8, and the output set's mean displacement in the frame agrees to 1 % of its largest value
over the whole history.

Run: python3 -m pip install -r assets/python/requirements.txt; cargo build;
python3 -m pytest assets/python  (FLEXMODES=path/to/flexmodes picks the binary).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

from flexmodes_exudyn import ExportError, add_stiffening, load  # noqa: E402

exu = pytest.importorskip("exudyn")
from exudyn.itemInterface import (  # noqa: E402
    CoordinateConstraint,
    MarkerNodeCoordinate,
    NodePointGround,
    SensorNode,
)


def flexmodes_binary() -> str:
    if "FLEXMODES" in os.environ:
        return os.environ["FLEXMODES"]
    for profile in ("debug", "release"):
        path = ROOT / "target" / profile / "flexmodes"
        if path.is_file():
            return str(path)
    subprocess.run(["cargo", "build", "--quiet"], cwd=ROOT, check=True)
    return str(ROOT / "target" / "debug" / "flexmodes")


def run(*args: str) -> str:
    done = subprocess.run([flexmodes_binary(), *args], cwd=ROOT, capture_output=True, text=True)
    assert done.returncode == 0, f"flexmodes {' '.join(args)}:\n{done.stderr}"
    return done.stdout


def spin_up(rate: float, ramp: float):
    """The frame's angle about the axis at t (flexmodes' SpinUp: a cosine ramp of the rate)."""

    def theta(t: float) -> float:
        if t <= 0.0:
            return 0.0
        if t >= ramp:
            return rate * ramp / 2.0 + rate * (t - ramp)
        phase = 2.0 * np.pi * t / ramp
        return rate * (t * t / (2.0 * ramp) + ramp / (4.0 * np.pi**2) * (np.cos(phase) - 1.0))

    return theta


def exudyn_history(folder: Path, output: str, point, rate, ramp, step, end, rho, stiffen=False):
    """The output set's mean displacement in the frame, Exudyn's gen-alpha, every step; with
    `stiffen`, the export's geometric stiffness added by the adapter's `add_stiffening`."""
    fem, cms, body = load(folder, "NodeType.RotationRxyz")
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    parts = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0.0, 0.0, 0.0])
    if stiffen:
        add_stiffening(mbs, parts, folder, body)
    theta = spin_up(rate, ramp)
    p = np.asarray(point, dtype=float)

    def frame(t: float):
        # The frame turns about the z axis through p: origin p - A p, Tait-Bryan angles (0, 0, θ).
        th = theta(t)
        c, s = np.cos(th), np.sin(th)
        return [p[0] - (c * p[0] - s * p[1]), p[1] - (s * p[0] + c * p[1]), 0.0, 0.0, 0.0, th]

    ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    for i in range(6):
        marker = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=parts["nRigidBody"], coordinate=i))
        mbs.AddObject(
            CoordinateConstraint(
                markerNumbers=[ground, marker],
                offsetUserFunction=lambda mbs, t, item, offset, i=i: frame(t)[i],
            )
        )
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=parts["nGenericODE2"],
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.Coordinates,
        )
    )
    mbs.Assemble()
    settings = exu.SimulationSettings()
    ti = settings.timeIntegration
    ti.numberOfSteps = int(round(end / step))
    ti.endTime = end
    ti.verboseMode = 0
    ti.generalizedAlpha.spectralRadius = rho
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.newton.relativeTolerance = 1e-10
    ti.newton.absoluteTolerance = 1e-14
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = step
    exu.SolveDynamic(mbs, settings)
    data = mbs.GetSensorStoredData(sensor)
    nodes = next(s["node_numbers"] for s in body["node_sets"] if s["name"] == output)
    psi = fem.modeBasis["matrix"]
    mean = np.stack(
        [psi[[3 * n + a for n in nodes]].mean(axis=0) @ data[:, 1:].T for a in range(3)], axis=1
    )
    return data[:, 0], mean, cms, body


CASES = {
    # The steel rod (SI), spun about its clamped end: centrifugal stretch, a bending swing.
    "rod": dict(body="tests/bodies/steel-rod/body.toml", drive="end_a", output="end_b",
                modes=8, rate=100.0, ramp=0.1, end=0.2, step=2.5e-4, axis_point=None),
    # The same rod spun about an axis 50 mm beside its drive, so the drive orbits.
    "rod-orbit": dict(body="tests/bodies/steel-rod/body.toml", drive="end_a", output="end_b",
                      modes=8, rate=60.0, ramp=0.1, end=0.15, step=2.5e-4,
                      axis_point=(-0.05, 0.0, 0.0)),
    # The flanged hub (mm-t-s units) spun about its bore: the flange's bolt ring breathes.
    "hub": dict(body="tests/bodies/flange-hub/body.toml", drive="bore", output="bolt_1",
                modes=10, rate=300.0, ramp=0.02, end=0.03, step=1e-4, axis_point=None),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_exudyn_matches_flexmodes(name, tmp_path):
    case = CASES[name]
    rho = 0.9
    out = tmp_path / "export"
    run("export", "--body", case["body"], "--method", "cb", "--boundary", f"rbe2:{case['drive']}",
        "--modes", str(case["modes"]), "--out", str(out), "--exudyn")
    steps = int(round(case["end"] / case["step"]))
    args = ["simulate", "--body", case["body"], "--drive", f"rbe2:{case['drive']}",
            "--method", "cb", "--modes", str(case["modes"]), "--output", case["output"],
            "--rate", str(case["rate"]), "--ramp", str(case["ramp"]), "--end", str(case["end"]),
            "--dt", str(case["step"]), "--rho", str(rho), "--samples", str(steps), "--json"]
    if case["axis_point"] is not None:
        args += ["--axis-point", ",".join(map(str, case["axis_point"]))]
    sim = json.loads(run(*args))
    [cb] = sim["runs"]
    point = case["axis_point"] or sim["drive"]["master"]

    t, exudyn_u, cms, body = exudyn_history(out / "exudyn", case["output"], point, case["rate"],
                                            case["ramp"], case["step"], case["end"], rho)

    # Reduced frequencies: Exudyn's reduced matrices (from the exported full M, K and basis)
    # against flexmodes' export and its simulation's range.
    lam = scipy.linalg.eigh(cms.stiffnessMatrixReduced, cms.massMatrixReduced, eigvals_only=True)
    hz = np.sqrt(lam) / (2 * np.pi)
    # Ten fixed-interface modes and the inertia loads' residual vectors (export's default).
    labels = json.loads((out / "model.json").read_text())["columns"]
    rv = sum(c["kind"] == "inertia_residual" for c in labels)
    assert rv >= 9
    assert len(hz) == len(body["hz"]) == case["modes"] + rv
    np.testing.assert_allclose(hz, body["hz"], rtol=1e-8)
    np.testing.assert_allclose([hz[0], hz[-1]], [cb["lowest_hz"], cb["highest_hz"]], rtol=1e-8)
    # Exudyn's total mass from the exported M equals the body's.
    mass_matrix = cms.Mtt
    assert abs(mass_matrix[0, 0] - mass_matrix[1, 1]) < 1e-12 * mass_matrix[0, 0]

    times = np.asarray(sim["times"])
    history = np.asarray(cb["outputs"][0])
    assert history.shape == (len(times), 3) and len(times) == steps + 1
    assert len(t) == len(times) and np.allclose(t, times, atol=1e-9)
    peak = np.abs(history).max()
    assert peak > 0.0
    error = np.abs(exudyn_u - history).max() / peak
    print(f"{name}: peak {peak:.4e} {body['units']['length']}, largest difference {error:.2e} of it")
    assert error < 0.01, f"{name}: Exudyn and flexmodes differ by {error:.2%} of the peak"


def test_exudyn_stiffens_as_flexmodes_does(tmp_path):
    """The steel lever with CalculiX's preloaded stiffness (assets/bodies/spun-lever, mm-t-s)
    spun up to 2 000 rad/s about its root: `export --exudyn` writes the modal geometric
    stiffness, the adapter's `add_stiffening` puts it into Exudyn as a user force, and the tip's
    history agrees with `flexmodes simulate` (stiffening on) to 1 % of its peak, while the
    stiffening itself moves it by several times that."""
    body, drive, output, modes = "assets/bodies/spun-lever/body.toml", "root", "tip", 10
    rate, ramp, end, step, rho = 2000.0, 0.01, 0.02, 1e-5, 0.9
    out = tmp_path / "export"
    run("export", "--body", body, "--method", "cb", "--boundary", f"rbe2:{drive}",
        "--modes", str(modes), "--out", str(out), "--exudyn")
    exported = json.loads((out / "exudyn" / "body.json").read_text())
    assert exported["stiffening"]["preload_rate_rad_s"] == 1000.0
    assert exported["stiffening"]["axis"] == [0.0, 0.0, 1.0]
    steps = int(round(end / step))

    def simulated(stiffening: str):
        sim = json.loads(run(
            "simulate", "--body", body, "--drive", f"rbe2:{drive}", "--method", "cb",
            "--modes", str(modes), "--output", output, "--rate", str(rate), "--ramp", str(ramp),
            "--end", str(end), "--dt", str(step), "--rho", str(rho), "--samples", str(steps),
            "--stiffening", stiffening, "--json"))
        [cb] = sim["runs"]
        return sim, np.asarray(cb["outputs"][0])

    sim, stiffened = simulated("on")
    _, linear = simulated("off")
    t, exudyn_u, _, _ = exudyn_history(out / "exudyn", output, sim["drive"]["master"], rate, ramp,
                                       step, end, rho, stiffen=True)
    assert len(t) == len(stiffened)
    peak = np.abs(stiffened).max()
    error = np.abs(exudyn_u - stiffened).max() / peak
    effect = np.abs(linear - stiffened).max() / peak
    print(f"lever: peak {peak:.4e} mm, Exudyn against flexmodes {error:.2e}, "
          f"the stiffening's effect {effect:.2e} of it")
    assert error < 0.01 and effect > 5 * error, (error, effect)


def test_adapter_names_a_wrong_folder(tmp_path):
    with pytest.raises(ExportError, match="body.json: not found"):
        load(tmp_path)
    (tmp_path / "body.json").write_text(json.dumps({"format": "other", "files": {}}))
    with pytest.raises(ExportError, match="format 'other'"):
        load(tmp_path)
