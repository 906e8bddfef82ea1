"""flexmodes from Python, against SciPy/LAPACK on bodies other FE codes made.

- a steel bar assembled here by scikit-fem (trilinear hexahedra, consistent mass, SI), its
  free-free frequencies against LAPACK's dense solve of the same matrices;
- the committed corpus bodies (scikit-fem, FElupe, CalculiX; tests/corpus/), against the
  SciPy/ARPACK references written with them, to 1e-6 as the Rust tests;
- reductions: Ψ, K_r and M_r against SciPy's products, the reduced frequencies against
  LAPACK's, Ritz bounds; the comparison and the driven body;
- scikit-fem → flexmodes → Exudyn: the exported body loaded by assets/python/flexmodes_exudyn.py;
- bad inputs raising the named exceptions with their data.

Run: python3 -m pip install ./python scikit-fem pytest; python3 -m pytest python/tests (from
the repository's root).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp

import flexmodes

ROOT = Path(__file__).resolve().parents[2]
CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/reference.json"))


def skfem_bar(cells=(12, 3, 3), size=(0.24, 0.03, 0.03)):
    """A steel bar (E 210 GPa, ν 0.3, ρ 7850 kg/m³) meshed and assembled by scikit-fem:
    K, M node-major (CSR), node coordinates and the two end faces as 1-based node sets."""
    skfem = pytest.importorskip("skfem")
    from skfem.helpers import dot
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    mesh = skfem.MeshHex.init_tensor(*(np.linspace(0.0, s, c + 1) for s, c in zip(size, cells)))
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementHex1()))
    K = linear_elasticity(*lame_parameters(210e9, 0.3)).assemble(basis)

    @skfem.BilinearForm
    def mass(u, v, _):
        return 7850.0 * dot(u, v)

    M = mass.assemble(basis)
    order = basis.nodal_dofs.T.ravel()  # node-major: node 1's x y z, then node 2's
    K = K[order][:, order].tocsr()
    M = M[order][:, order].tocsr()
    nodes = mesh.p.T
    sets = {
        "end_a": np.flatnonzero(np.isclose(nodes[:, 0], 0.0)) + 1,
        "end_b": np.flatnonzero(np.isclose(nodes[:, 0], size[0])) + 1,
    }
    return K, M, nodes, sets


def lapack_hz(K, M):
    lam = scipy.linalg.eigh(K.toarray(), M.toarray(), eigvals_only=True)
    return np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * np.pi)


@pytest.fixture(scope="module")
def bar():
    K, M, nodes, sets = skfem_bar()
    return K, M, nodes, sets, lapack_hz(K, M)


def test_scikit_fem_bar_free_modes_match_lapack(bar):
    K, M, nodes, sets, reference = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets, name="skfem bar")
    assert body.dofs == K.shape[0] and body.units == ("m", "kg", "N")
    summary = body.summary()
    assert summary["zero_energy_modes"] == 6 and summary["missed_modes"] == 0
    assert summary["total_mass"] == pytest.approx(7850.0 * 0.24 * 0.03 * 0.03, rel=1e-9)
    modes = body.free_modes(12)
    np.testing.assert_allclose(modes["hz"], reference[6:18], rtol=1e-8)
    assert modes["residuals"].max() < 1e-8
    # Mass-normalised: Φᵀ M Φ = I, and K Φ = M Φ Λ.
    phi = modes["vectors"]
    np.testing.assert_allclose(phi.T @ (M @ phi), np.eye(12), atol=1e-8)
    lam = (2 * np.pi * modes["hz"]) ** 2
    assert np.abs(K @ phi - (M @ phi) * lam).max() <= 1e-7 * np.abs(K @ phi).max()


def test_amls_gives_lapacks_frequencies_and_says_it_made_them(bar):
    K, M, nodes, sets, reference = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets, name="skfem bar")
    amls = body.summary(eigensolver="amls")
    assert amls["eigensolver"] == "amls" and amls["amls"]["reductions"] >= 1
    assert amls["zero_energy_modes"] == 6 and amls["missed_modes"] == 0
    hz = np.array(amls["lowest_elastic_hz"])
    np.testing.assert_allclose(hz, reference[6 : 6 + len(hz)], rtol=1e-5)
    assert body.summary()["eigensolver"] == "lanczos"
    with pytest.raises(flexmodes.InputError, match="eigensolver"):
        body.summary(eigensolver="arpack")


@pytest.mark.parametrize("fmt", ["csr", "csc", "coo", "lower", "upper"])
def test_every_sparse_format_and_one_triangle_give_the_same_body(bar, fmt):
    K, M, nodes, sets, reference = bar
    convert = {
        "csr": lambda A: A.tocsr(),
        "csc": lambda A: A.tocsc(),
        "coo": lambda A: sp.coo_array(A),
        "lower": lambda A: sp.tril(A, format="csc"),
        "upper": lambda A: sp.triu(A, format="coo"),
    }[fmt]
    body = flexmodes.Body(convert(K), convert(M), nodes=nodes, node_sets=sets)
    np.testing.assert_allclose(body.free_modes(6)["hz"], reference[6:12], rtol=1e-8)


def test_a_lumped_mass_vector_is_taken(bar):
    K, M, nodes, sets, _ = bar
    lumped = np.asarray(M.sum(axis=1)).ravel()
    body = flexmodes.Body(K, lumped, nodes=nodes, node_sets=sets)
    reference = lapack_hz(K, sp.diags(lumped))
    np.testing.assert_allclose(body.free_modes(6)["hz"], reference[6:12], rtol=1e-8)


@pytest.mark.parametrize("reference", CORPUS, ids=[p.parent.name for p in CORPUS])
def test_corpus_bodies_match_their_references(reference):
    expected = json.loads(reference.read_text())
    body = flexmodes.Body.from_file(reference.parent / "body.toml")
    assert body.dofs == expected["dofs"]
    modes = body.free_modes(12)
    assert modes["zero_energy_modes"] == expected["zero_energy_modes"] == 6
    assert modes["missed_modes"] == 0
    np.testing.assert_allclose(modes["hz"], expected["free_free_hz"][6:18], rtol=1e-6)
    assert modes["residuals"].max() < 1e-6


def test_rbe2_craig_bampton_against_scipy(bar):
    K, M, nodes, sets, reference = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets)
    model = body.reduce("cb", boundary="rbe2:end_a", modes=10)
    psi = model.psi
    # 6 rigid-interface columns, 10 modes and the inertia loads' residual vectors (twelve
    # loads; those the basis already holds to 1e-8 are dropped).
    rv = sum(label.startswith("residual vector") for label in model.labels)
    assert 9 <= rv <= 12
    assert psi.shape == (K.shape[0], 16 + rv) and len(model.labels) == 16 + rv
    plain = body.reduce("cb", boundary="rbe2:end_a", modes=10, residual_vectors=False)
    assert plain.psi.shape == (K.shape[0], 16)
    assert sum("rbe2" in label or "end_a" in label for label in model.labels) == 6
    scale = np.abs(model.k_r).max()
    np.testing.assert_allclose(model.k_r, psi.T @ (K @ psi), atol=1e-10 * scale)
    np.testing.assert_allclose(model.m_r, psi.T @ (M @ psi), atol=1e-10 * np.abs(model.m_r).max())
    lam = scipy.linalg.eigh(model.k_r, model.m_r, eigvals_only=True)
    hz = np.sqrt(np.clip(lam, 0, None)) / (2 * np.pi)
    assert model.zero_energy_modes == 6
    np.testing.assert_allclose(model.hz, hz[6:], rtol=1e-8)
    assert model.residuals.max() < 1e-8
    # Rayleigh–Ritz: each reduced frequency bounds the free body's from above.
    assert np.all(model.hz[:8] >= reference[6:14] * (1 - 1e-10))
    assert model.hz[0] == pytest.approx(reference[6], rel=1e-3)


def test_every_method_reduces_the_bar(bar):
    K, M, nodes, sets, reference = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets, default_interface="end_a")
    # Every basis lies in the body's space: its frequencies, zero-energy ones included, bound
    # the free bar's from above one by one (Rayleigh–Ritz). Modal truncation holds no rigid
    # motion (its interface DOF move alone), so it has none at zero.
    for method in flexmodes.METHODS:
        try:
            model = body.reduce(method, modes=8)
        except flexmodes.ReductionError as refused:
            # Eitelberg's state-space reduction needs a stable A; the free bar's is not, and
            # the refusal says by how much (as `flexmodes export` does).
            assert method == "eit" and refused.kind == "Reduction.UnstableSystem"
            assert refused.data["max_real_part"] > 0
            continue
        assert model.method == method
        assert model.psi.shape[0] == K.shape[0]
        assert model.residuals[:6].max() < 1e-8, method
        assert model.zero_energy_modes == (0 if method == "mt" else 6), method
        spectrum = np.concatenate([np.zeros(model.zero_energy_modes), model.hz])
        assert np.all(spectrum[6:12] >= reference[6:12] * (1 - 1e-8)), method


def test_save_writes_what_export_writes(bar, tmp_path):
    K, M, nodes, sets, _ = bar
    model = flexmodes.Body(K, M, nodes=nodes, node_sets=sets).reduce("cb", "rbe2:end_a", 6)
    files = model.save(tmp_path / "cb")
    assert files == ["psi.npy", "k_r.mtx", "m_r.mtx", "model.json"]
    np.testing.assert_array_equal(np.load(tmp_path / "cb" / "psi.npy"), model.psi)
    doc = json.loads((tmp_path / "cb" / "model.json").read_text())
    assert doc["method"] == "cb" and doc["size"] == model.psi.shape[1]
    assert doc == json.loads(json.dumps(model.document()))


def test_scikit_fem_to_flexmodes_to_exudyn(bar, tmp_path):
    pytest.importorskip("exudyn")
    sys.path.insert(0, str(ROOT / "assets" / "python"))
    from flexmodes_exudyn import load

    K, M, nodes, sets, _ = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets, name="skfem bar")
    model = body.reduce("cb", boundary="rbe2:end_a", modes=8, exudyn=True)
    files = model.save(tmp_path / "bar", exudyn=True)
    assert any(f.startswith("exudyn") or "body.json" in f for f in files)
    fem, cms, exported = load(tmp_path / "bar" / "exudyn")
    lam = scipy.linalg.eigh(cms.stiffnessMatrixReduced, cms.massMatrixReduced, eigvals_only=True)
    hz = np.sqrt(np.clip(lam, 0, None)) / (2 * np.pi)
    np.testing.assert_allclose(hz, exported["hz"], rtol=1e-8)
    total = 7850.0 * 0.24 * 0.03 * 0.03
    assert cms.Mtt[0, 0] == pytest.approx(total, rel=1e-9)


def test_compare_measures_every_model(bar):
    K, M, nodes, sets, reference = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets)
    result = flexmodes.compare(body, methods=("cb", "mc", "gr"), modes=(4, 8), boundary="end_a")
    np.testing.assert_allclose(result["reference_hz"], reference[6:12], rtol=1e-8)
    points = result["points"]
    assert [(p["method"], p["modes"]) for p in points] == [
        ("cb", 4), ("cb", 8), ("mc", 4), ("mc", 8), ("gr", 0),
    ]
    cb4, cb8 = points[0], points[1]
    assert 0 <= cb8["freq_rel_error"] <= cb4["freq_rel_error"]
    assert all(0.0 <= p["min_mac"] <= 1.0 + 1e-12 for p in points)
    assert any(p["pareto"] for p in points)


def test_a_progress_callback_sees_phases_and_can_stop_the_work(bar):
    K, M, nodes, sets, _ = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets)
    seen = []

    def stop(phase, fraction):
        seen.append(phase)
        raise KeyboardInterrupt("stopped by the callback")

    with pytest.raises(KeyboardInterrupt, match="stopped by the callback"):
        flexmodes.compare(body, modes=(2, 4, 8, 16, 32, 64), progress=stop)
    assert seen and seen[0] is not None


def test_driven_link_reduced_follows_the_full_body():
    body = flexmodes.Body.from_file(ROOT / "tests" / "bodies" / "steel-link" / "body.toml")
    result = body.simulate(
        "rbe2:bore_a", methods=("nr", "cb"), modes=(8,), outputs=("bore_b",),
        rate=200.0, ramp=0.02, end=0.03, step=5e-4, output_every=2,
    )
    times = result["times"]
    assert times[0] == 0.0 and times[-1] == pytest.approx(0.03)
    full, cb = result["runs"]
    assert full["method"] == "nr" and cb["label"] == "CB 8"
    for run in (full, cb):
        assert run["outputs"].shape == (len(times), 1, 3)
        assert run["reaction"].shape == (len(times), 6)
        assert np.isfinite(run["outputs"]).all()
    assert np.abs(full["outputs"]).max() > 0
    assert cb["history_error"] < 0.05


# Bad input: a named exception with its data, never a crash.


def test_a_spinning_calculix_lever_at_calculix_frequencies():
    """The lever CalculiX wrote spinning (assets/generate/spun_body.py): its frequencies in
    the turning frame at 1 000 and 2 000 rad/s, with the [preload]'s stiffening, equal
    CalculiX's prestressed ones to 2e-4; without it the first one falls below them; a driven
    run says it carried the stiffening."""
    folder = ROOT / "assets" / "bodies" / "spun-lever"
    body = flexmodes.Body.from_file(folder / "body.toml")
    reference = json.loads((folder / "reference.json").read_text())
    table = body.campbell("rbe2:root", [1000.0, 2000.0], count=6, methods=["nr", "cb"], modes=[12])
    assert table["stiffened"]
    assert [c["method"] for c in table["curves"]] == ["nr", "cb"]
    ccx = np.array(reference["spinning_hz"])[:, :6]
    nr = table["curves"][0]["hz"]
    assert nr.shape == (2, 6)
    assert np.max(np.abs(nr - ccx) / ccx) < 2e-4
    assert np.max(np.abs(table["curves"][1]["hz"] - ccx) / ccx) < 2e-3
    off = body.campbell("rbe2:root", [2000.0], count=1, methods=["nr"], stiffening=False)
    assert not off["stiffened"]
    assert off["curves"][0]["hz"][0, 0] < 0.9 * ccx[1, 0]
    run = body.simulate("rbe2:root", methods=["nr"], rate=1000.0, ramp=0.002, end=0.002,
                        step=1e-4, output_every=5)
    assert run["stiffened"]
    with pytest.raises(flexmodes.errors.DynamicsError) as e:
        body.campbell("rbe2:root", [1000.0], axis=(0.0, 1.0, 0.0), methods=["nr"])
    assert "another spin" in str(e.value)


def test_dense_and_mis_shaped_inputs_are_refused(bar):
    K, M, nodes, sets, _ = bar
    with pytest.raises(flexmodes.InputError, match="dense"):
        flexmodes.Body(K.toarray(), M)
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body(sp.csr_array((10, 12)), sp.eye(10))
    assert caught.value.kind == "BodyFile.MatrixSizeMismatch"
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body(K, M, nodes=nodes[:-1])
    assert caught.value.data["rows"] == K.shape[0]
    with pytest.raises(flexmodes.InputError, match="nodes has shape"):
        flexmodes.Body(K, M, nodes=nodes[:, 0])
    with pytest.raises(flexmodes.InputError, match="node numbers"):
        flexmodes.Body(K, M, node_sets={"a": [1.5, 2.0]})


def test_absurd_sizes_and_fatal_files_raise_named_errors(bar, tmp_path):
    # A shape of 10^12 DOF with a handful of entries once sized an allocation from the shape;
    # the files the reader fuzzer keeps (tests/fuzz/regressions) once aborted `import`. Each
    # is a named exception, and the interpreter goes on to load a good body.
    import shutil
    import tomllib

    huge = 10**12
    few = sp.coo_array((np.ones(3), ([0, 1, 2], [0, 1, 2])), shape=(huge, huge))
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body(few, few)
    assert caught.value.kind == "BodyFile.MatrixSizeMismatch"
    assert caught.value.data["rows"] == huge
    regressions = ROOT / "tests" / "fuzz" / "regressions"
    manifest = tomllib.loads((regressions / "regressions.toml").read_text())
    for file, entry in manifest.items():
        case = tmp_path / file
        shutil.copytree(ROOT / entry["body"], case)
        shutil.copy(regressions / file, case / entry["replaces"])
        with pytest.raises(flexmodes.BodyFileError) as caught:
            flexmodes.Body.from_file(case / entry["spec"])
        assert entry["error"] in str(caught.value), (file, str(caught.value))
    K, M, *_ = bar
    assert flexmodes.Body(K, M).summary()


def test_a_nan_names_its_entry(bar):
    K, M, *_ = bar
    bad = sp.coo_array(K)
    data = bad.data.copy()
    data[17] = np.nan
    bad = sp.coo_array((data, (bad.row, bad.col)), shape=K.shape)
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body(bad, M)
    assert caught.value.kind == "BodyFile.NonFiniteEntry"
    assert caught.value.data["line"] == 18 and caught.value.data["value"] == "NaN"


def test_a_non_symmetric_stiffness_names_its_worst_entry(bar):
    K, M, *_ = bar
    bad = K.tolil()
    bad[4, 40] += 1e-3 * abs(K).max()
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body(bad.tocsr(), M)
    assert caught.value.kind == "BodyFile.NotSymmetric"
    assert {caught.value.data["row"], caught.value.data["col"]} == {5, 41}


def test_a_negative_mass_names_its_dof(bar):
    K, M, *_ = bar
    lumped = np.asarray(M.sum(axis=1)).ravel()
    lumped[7] = -1.0
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body(K, lumped)
    assert caught.value.kind == "BodyFile.MassNotPositive" and caught.value.data["dof"] == 8


def test_a_mechanism_is_refused_with_its_count(bar):
    K, M, *_ = bar
    two = flexmodes.Body(sp.block_diag([K, K], format="csr"), sp.block_diag([M, M], format="csr"))
    with pytest.raises(flexmodes.MechanismError) as caught:
        two.summary()
    assert caught.value.data["zero_modes"] == 12 and caught.value.data["rigid"] == 6


def test_unknown_names_are_refused(bar):
    K, M, nodes, sets, _ = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets)
    with pytest.raises(flexmodes.InputError, match="method"):
        body.reduce("xx", "end_a")
    with pytest.raises(flexmodes.BodyFileError) as caught:
        body.reduce("cb", "rbe2:nowhere")
    assert "nowhere" in str(caught.value)
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body(K, M, node_sets={"far": [10**6]})
    assert caught.value.kind == "BodyFile.NodeSetOutOfRange"
    assert caught.value.data["node"] == 10**6
    with pytest.raises(flexmodes.FileError):
        flexmodes.Body.from_file(ROOT / "no" / "such" / "body.toml")


def test_a_bad_table_line_is_named_with_its_data(tmp_path):
    # The committed steel rod, its edge table given a node it does not have on line 2.
    import shutil

    rod = ROOT / "tests" / "bodies" / "steel-rod"
    for f in ["body.toml", "k.mtx.gz", "m.mtx.gz", "nodes.csv"]:
        shutil.copy(rod / f, tmp_path / f)
    lines = (rod / "edges.csv").read_text().splitlines()
    count = len((rod / "nodes.csv").read_text().splitlines()) - 1
    first = next(i for i, line in enumerate(lines) if line[:1].isdigit())
    lines[first] = f"1 {count + 5}"
    (tmp_path / "edges.csv").write_text("\n".join(lines) + "\n")
    with pytest.raises(flexmodes.BodyFileError) as caught:
        flexmodes.Body.from_file(tmp_path / "body.toml")
    assert caught.value.kind == "BodyFile.TableLine"
    data = caught.value.data
    assert data["line"] == first + 1 and data["path"].endswith("edges.csv")
    assert data["problem"]["NodeOutOfRange"]["node"] == count + 5


def test_readme_example_runs_as_written(bar):
    """The README's ten-line script, extracted and run: it meshes this file's bar, so its
    Craig–Bampton frequencies bound LAPACK's free-bar ones from above, within 1 %."""
    text = (ROOT / "README.md").read_text()
    start = text.index("```python\n") + len("```python\n")
    script = text[start : text.index("```", start)]
    namespace: dict = {}
    exec(compile(script, "README.md", "exec"), namespace)
    model, reference = namespace["model"], bar[4]
    # Six master DOF, ten fixed-interface modes and the inertia loads' residual vectors.
    rv = sum(label.startswith("residual vector") for label in model.labels)
    assert 9 <= rv <= 12
    assert model.psi.shape == (624, 16 + rv) and model.zero_energy_modes == 6
    assert np.all(model.hz[:4] >= reference[6:10] * (1 - 1e-10))
    np.testing.assert_allclose(model.hz[:4], reference[6:10], rtol=1e-2)


def test_the_kernels_use_every_core_and_can_be_told_fewer(bar):
    import os

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    assert flexmodes.threads() == cores
    K, M, nodes, sets, reference = bar
    body = flexmodes.Body(K, M, nodes=nodes, node_sets=sets)
    try:
        assert flexmodes.set_threads(1) == 1 and flexmodes.threads() == 1
        one = body.reduce("cb", "rbe2:end_a", 8).hz
    finally:
        assert flexmodes.set_threads() == cores
    np.testing.assert_allclose(body.reduce("cb", "rbe2:end_a", 8).hz, one, rtol=1e-10)


def test_driven_link_on_mean_axes_with_a_shake():
    body = flexmodes.Body.from_file(ROOT / "tests" / "bodies" / "steel-link" / "body.toml")
    common = dict(methods=("cb",), modes=(6,), outputs=("bore_b",), rate=100.0, ramp=0.02,
                  end=0.02, step=5e-4, output_every=4, shake=((1.0, 0.0, 0.0), 1e-4, 200.0))
    nodal = body.simulate("rbe2:bore_a", **common)["runs"][0]["outputs"]
    mean = body.simulate("rbe2:bore_a", axes="mean", **common)["runs"][0]["outputs"]
    assert nodal.shape == mean.shape and np.isfinite(mean).all()
    # The same motion seen from another frame: the rigid part taken out differs.
    assert np.abs(nodal - mean).max() > 1e-3 * np.abs(nodal).max()
    with pytest.raises(flexmodes.InputError, match="axes"):
        body.simulate("rbe2:bore_a", axes="principal", **common)
    with pytest.raises(flexmodes.DynamicsError) as caught:
        body.simulate("rbe2:bore_a", methods=("cb",), modes=(6,), axis=(0, 0, 0))
    assert caught.value.kind == "Dynamics.ZeroDirection"
