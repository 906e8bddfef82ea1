//! `flexmodes._flexmodes`: the Rust side of the Python package. Bodies from entries (the
//! Python side turns SciPy matrices into them) or body files, reductions as `export` builds
//! them, the comparison of `bench modes --body` and the driven body of `simulate --body`.
//! Every call releases the GIL while it computes; errors are raised as the exception classes
//! of `flexmodes.errors`, carrying the error's data.

use std::{
    collections::BTreeMap,
    sync::{Arc, Mutex},
};

use flexmodes::{
    analysis::count_zero_energy_modes,
    body_file::{BodyMatrices, ImportedBody, InterfaceKind, InterfaceSpec, Units},
    export::{ExportParameters, ReducedExport, reduce_for_export},
    models::{
        BodyCampbellParameters, BodyComparisonParameters, BodyInterfaces, DrivenBodyParameters,
        body_campbell, compare_body_methods, driven_body_study, import_summary_by,
        refuse_mechanism,
    },
};
use numpy::{IntoPyArray, PyArray1, PyArray2, ndarray::Array2};
use pyo3::{
    prelude::*,
    types::{PyDict, PyList},
};

mod bridge;
mod requests;

use bridge::{computing, entries, input_error, json_to_py, matrix, method, vector};
use requests::{
    BodyLayout, CampbellRequest, CompareRequest, ReduceRequest, SimulateRequest, Triplets,
};

/// A checked body (`flexmodes.Body` wraps it).
#[pyclass(module = "flexmodes._flexmodes", name = "RustBody", frozen)]
struct RustBody {
    body: Arc<ImportedBody>,
}

#[pymethods]
impl RustBody {
    /// A body from stiffness and mass entries (0-based, node-major), checked as a body file.
    #[staticmethod]
    #[pyo3(signature = (name, k, m, layout))]
    fn from_entries(
        py: Python<'_>,
        name: String,
        k: Triplets<'_>,
        m: Triplets<'_>,
        layout: BodyLayout,
    ) -> PyResult<Self> {
        let stiffness = entries(py, "K", k)?;
        let mass = entries(py, "M", m)?;
        let BodyLayout {
            dofs,
            nodes,
            node_sets,
            interfaces,
            default_interface,
            units,
        } = layout;
        let mut specs = BTreeMap::new();
        for (iname, (kind, node_set, master, weights)) in interfaces {
            let kind = match kind.as_str() {
                "rbe2" => InterfaceKind::Rbe2,
                "rbe3" => InterfaceKind::Rbe3,
                other => {
                    return Err(input_error(
                        py,
                        format!("interface `{iname}`: kind `{other}` (known: rbe2, rbe3)"),
                    ));
                }
            };
            specs.insert(
                iname,
                InterfaceSpec {
                    kind,
                    node_set,
                    master,
                    weights,
                },
            );
        }
        let given = BodyMatrices {
            name,
            stiffness,
            mass,
            dofs,
            nodes,
            node_sets,
            interfaces: specs,
            default_interface,
            units: Units {
                length: units.0,
                mass: units.1,
                force: units.2,
            },
        };
        let body = computing(py, None, move |_| ImportedBody::from_matrices(given))?;
        Ok(Self {
            body: Arc::new(body),
        })
    }

    /// A body file (`builtin:NAME` or a path), as `flexmodes import` reads it.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: String) -> PyResult<Self> {
        let body = computing(py, None, move |_| ImportedBody::load(&path))?;
        Ok(Self {
            body: Arc::new(body),
        })
    }

    #[getter]
    fn name(&self) -> String {
        self.body.model.name.clone()
    }

    #[getter]
    fn dofs(&self) -> usize {
        self.body.model.dof_count()
    }

    #[getter]
    fn nodes<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        let model = &self.body.model;
        self.body.has_coordinates.then(|| {
            Array2::from_shape_fn((model.nodes.len(), 3), |(i, j)| model.nodes[i][j])
                .into_pyarray(py)
        })
    }

    #[getter]
    fn node_sets(&self) -> BTreeMap<String, Vec<usize>> {
        self.body.node_sets.clone()
    }

    #[getter]
    fn units(&self) -> (String, String, String) {
        let u = &self.body.units;
        (u.length.clone(), u.mass.clone(), u.force.clone())
    }

    /// What `flexmodes import` prints, as a dict, the free-free pairs by `eigensolver`.
    #[pyo3(signature = (eigensolver))]
    fn summary<'py>(&self, py: Python<'py>, eigensolver: &str) -> PyResult<Bound<'py, PyAny>> {
        let solver = bridge::eigensolver(py, eigensolver)?;
        let body = &self.body;
        let (value, _) = computing(py, None, |_| import_summary_by(body, solver))?;
        json_to_py(py, &value)
    }

    /// The lowest `n` elastic free-free modes and the zero-energy ones below them.
    fn free_modes<'py>(&self, py: Python<'py>, n: usize) -> PyResult<Bound<'py, PyDict>> {
        let model = &self.body.model;
        let full = computing(py, None, |_| {
            let full = count_zero_energy_modes(model, n)?;
            refuse_mechanism(model, &full)?;
            Ok(full)
        })?;
        let z = full.zero_modes;
        let elastic = (full.modes.values.len() - z).min(n);
        let d = PyDict::new(py);
        d.set_item("zero_energy_modes", z)?;
        d.set_item("hz", vector(py, &full.modes.hz()[z..z + elastic]))?;
        d.set_item(
            "residuals",
            vector(py, &full.modes.residuals[z..z + elastic]),
        )?;
        d.set_item(
            "vectors",
            matrix(py, full.modes.vectors.as_ref().subcols(z, elastic)),
        )?;
        d.set_item(
            "zero_energy_vectors",
            matrix(py, full.modes.vectors.as_ref().subcols(0, z)),
        )?;
        d.set_item("threshold_hz", full.threshold_hz)?;
        d.set_item("missed_modes", full.modes.sturm.map_or(0, |c| c.missed()))?;
        Ok(d)
    }

    /// Reduces the body as `flexmodes export` does.
    #[pyo3(signature = (request))]
    fn reduce(&self, py: Python<'_>, request: ReduceRequest) -> PyResult<RustReducedModel> {
        let ReduceRequest {
            method,
            boundary,
            modes,
            interface_modes,
            exudyn,
            eigensolver,
            residual_vectors,
        } = request;
        let method = self::method(py, &method)?;
        let eigensolver = bridge::eigensolver(py, &eigensolver)?;
        let body = &self.body;
        let reduced = computing(py, None, |_| {
            let interfaces =
                BodyInterfaces::named_or_default(body, boundary.as_deref(), interface_modes)?;
            let parameters = ExportParameters {
                rigid_interfaces: interfaces.rigid,
                averaging_interfaces: interfaces.averaging,
                interface_modes,
                exudyn,
                eigensolver,
                residual_vectors,
                ..ExportParameters::default()
            };
            reduce_for_export(body, method, &interfaces.boundary, modes, &parameters)
        })?;
        Ok(RustReducedModel {
            body: body.clone(),
            reduced: Mutex::new(reduced),
        })
    }

    /// What `bench modes --body` measures, as a dict.
    #[pyo3(signature = (request, progress))]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        request: CompareRequest,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let CompareRequest {
            methods,
            modes,
            boundary,
            interface_modes,
            band_hz,
            tolerance,
        } = request;
        let defaults = BodyComparisonParameters::default();
        let parameters = BodyComparisonParameters {
            boundary,
            interface_modes,
            methods: match methods {
                Some(ids) => ids
                    .iter()
                    .map(|m| method(py, m))
                    .collect::<PyResult<Vec<_>>>()?,
                None => defaults.methods,
            },
            modes: modes.unwrap_or(defaults.modes),
            band_hz,
            tolerance,
        };
        let body = &self.body;
        let c = computing(py, progress, |p| compare_body_methods(body, &parameters, p))?;
        let d = PyDict::new(py);
        d.set_item("boundary", c.boundary)?;
        d.set_item("zero_energy_modes", c.zero_modes)?;
        d.set_item("reference_hz", c.reference_hz)?;
        d.set_item("reference_residuals", c.reference_residuals)?;
        d.set_item("reference_s", c.reference_s)?;
        let points = PyList::empty(py);
        for q in &c.points {
            let p = PyDict::new(py);
            p.set_item("method", q.method.id())?;
            p.set_item("modes", q.modes)?;
            p.set_item("coordinates", q.coordinates)?;
            p.set_item("offline_s", q.offline_s)?;
            p.set_item("peak_mb", q.peak_mb)?;
            p.set_item("freq_rel_error", q.freq_rel_error)?;
            p.set_item("min_mac", q.min_mac)?;
            p.set_item("static_rel_error", q.static_error)?;
            p.set_item("frf_rel_error", q.frf_error)?;
            p.set_item("pareto", q.pareto)?;
            points.append(p)?;
        }
        d.set_item("points", points)?;
        let refused = PyList::empty(py);
        for (m, why) in &c.not_applicable {
            refused.append((m.id(), why))?;
        }
        d.set_item("not_applicable", refused)?;
        d.set_item("advice", json_to_py(py, &c.advice.json())?)?;
        Ok(d)
    }

    /// The Campbell table of `flexmodes campbell`: the lowest `count` frequencies (Hz) in
    /// the turning frame at each rate, the full body first, then each method at each count.
    #[pyo3(signature = (request, progress))]
    fn campbell<'py>(
        &self,
        py: Python<'py>,
        request: CampbellRequest,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let CampbellRequest {
            drive,
            rates,
            axis,
            axis_point,
            count,
            methods,
            modes,
            full,
            stiffening,
            residual_vectors,
        } = request;
        let methods = methods
            .iter()
            .map(|m| method(py, m))
            .collect::<PyResult<Vec<_>>>()?;
        if let Some(r) = rates.iter().find(|r| !(r.is_finite() && **r >= 0.0)) {
            return Err(input_error(
                py,
                format!("rates are rad/s, finite and not negative, not {r}"),
            ));
        }
        let parameters = BodyCampbellParameters {
            drive,
            axis,
            axis_point,
            rates,
            count,
            models: methods
                .iter()
                .flat_map(|&m| modes.iter().map(move |&k| (m, k)))
                .collect(),
            stiffening,
            full,
            residual_vectors,
        };
        let body = &self.body;
        let table = computing(py, progress, |p| body_campbell(body, &parameters, p))?;
        let d = PyDict::new(py);
        d.set_item("rates", vector(py, &table.rates))?;
        d.set_item("stiffened", table.stiffened)?;
        let curves = PyList::empty(py);
        d.set_item("axis_point", table.axis_point.0.to_vec())?;
        for c in &table.curves {
            let r = PyDict::new(py);
            r.set_item("method", c.method.map(|m| m.id()).unwrap_or("nr"))?;
            r.set_item("modes", c.modes)?;
            r.set_item("coordinates", c.coordinates)?;
            r.set_item("residual_vectors", c.residual_vectors)?;
            r.set_item("unstable", c.unstable.clone())?;
            r.set_item("route", c.route)?;
            let n = c.mac.first().map_or(0, Vec::len);
            let mac = Array2::from_shape_fn((c.mac.len(), n), |(i, j)| c.mac[i][j]);
            r.set_item("mac", mac.into_pyarray(py))?;
            let n = c.hz.first().map_or(0, Vec::len);
            let hz = Array2::from_shape_fn((c.hz.len(), n), |(i, j)| c.hz[i][j]);
            r.set_item("hz", hz.into_pyarray(py))?;
            curves.append(r)?;
        }
        d.set_item("curves", curves)?;
        Ok(d)
    }

    /// The driven body of `flexmodes simulate --body`: histories as NumPy arrays.
    #[pyo3(signature = (request, progress))]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        request: SimulateRequest,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let SimulateRequest {
            drive,
            methods,
            modes,
            full,
            boundary,
            outputs,
            rate,
            ramp,
            axis,
            end,
            step,
            output_every,
            pinned,
            axis_point,
            shake,
            gravity,
            spectral_radius,
            mean_axes,
            stiffening,
            residual_vectors,
        } = request;
        let methods = methods
            .iter()
            .map(|m| method(py, m))
            .collect::<PyResult<Vec<_>>>()?;
        let defaults = DrivenBodyParameters::default();
        let parameters = DrivenBodyParameters {
            drive,
            boundary,
            outputs,
            pinned,
            axis,
            rate,
            ramp,
            axis_point,
            shake,
            gravity,
            axes: if mean_axes {
                flexmodes::dynamics::AxisKind::Mean
            } else {
                flexmodes::dynamics::AxisKind::NodalFixed
            },
            integration: flexmodes::dynamics::DrivenIntegration {
                step,
                end,
                output_every,
                spectral_radius,
            },
            stiffening,
            residual_vectors,
            ..defaults
        };
        let body = &self.body;
        let study = computing(py, progress, |p| {
            driven_body_study(body, &parameters, &methods, &modes, full, p)
        })?;
        let d = PyDict::new(py);
        d.set_item("times", vector(py, &study.times))?;
        d.set_item("outputs", study.output_names.clone())?;
        d.set_item("drive", study.drive.0.clone())?;
        d.set_item("stiffened", study.stiffened)?;
        let runs = PyList::empty(py);
        for run in &study.runs {
            let r = PyDict::new(py);
            r.set_item("label", run.label())?;
            r.set_item("method", run.method.map(|m| m.id()).unwrap_or("nr"))?;
            r.set_item("modes", run.modes)?;
            r.set_item("coordinates", run.coordinates)?;
            r.set_item("offline_s", run.offline_s)?;
            r.set_item("online_s", run.cost.online_s)?;
            r.set_item("steps", run.cost.steps)?;
            let samples = run.outputs.first().map_or(0, Vec::len);
            let sets = run.outputs.len();
            let out =
                Array2::from_shape_fn((samples, 3 * sets), |(t, k)| run.outputs[k / 3][t][k % 3])
                    .into_shape_with_order((samples, sets, 3))
                    .map_err(|e| input_error(py, e.to_string()))?;
            r.set_item("outputs", out.into_pyarray(py))?;
            let reaction =
                Array2::from_shape_fn((run.reaction.len(), 6), |(t, k)| run.reaction[t][k]);
            r.set_item("reaction", reaction.into_pyarray(py))?;
            r.set_item("history_error", run.history_error)?;
            r.set_item("reaction_error", run.reaction_error)?;
            r.set_item("residual_vectors", run.residual_vectors)?;
            r.set_item("a_priori_estimate", run.estimate_max())?;
            runs.append(r)?;
        }
        d.set_item("runs", runs)?;
        Ok(d)
    }
}

/// A reduced model (`flexmodes.ReducedModel` wraps it).
#[pyclass(module = "flexmodes._flexmodes", name = "RustReducedModel", frozen)]
struct RustReducedModel {
    body: Arc<ImportedBody>,
    reduced: Mutex<ReducedExport>,
}

impl RustReducedModel {
    fn with<T>(&self, f: impl FnOnce(&ReducedExport) -> T) -> T {
        f(&self.reduced.lock().expect("not poisoned"))
    }
}

#[pymethods]
impl RustReducedModel {
    #[getter]
    fn psi<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.with(|r| matrix(py, r.basis.psi.as_ref()))
    }

    #[getter]
    fn k_r<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.with(|r| matrix(py, r.k_r.as_ref()))
    }

    #[getter]
    fn m_r<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.with(|r| matrix(py, r.m_r.as_ref()))
    }

    #[getter]
    fn hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.with(|r| vector(py, &r.hz))
    }

    #[getter]
    fn residuals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.with(|r| vector(py, &r.residuals))
    }

    #[getter]
    fn zero_energy_modes(&self) -> usize {
        self.with(|r| r.zero_energy)
    }

    #[getter]
    fn labels(&self) -> Vec<String> {
        self.with(|r| r.basis.columns.iter().map(|c| c.label.clone()).collect())
    }

    #[getter]
    fn method(&self) -> &'static str {
        self.with(|r| r.method.id())
    }

    #[getter]
    fn boundary(&self) -> Vec<usize> {
        self.with(|r| r.boundary.clone())
    }

    #[getter]
    fn timings(&self) -> Vec<(&'static str, f64)> {
        self.with(|r| r.timings.clone())
    }

    /// `model.json` as a dict: columns, interfaces and their masters, inertia invariants.
    fn document<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let doc = self.with(|r| r.document(&self.body));
        json_to_py(py, &doc)
    }

    /// Writes what `flexmodes export` writes into `folder` (atomically); returns the files.
    #[pyo3(signature = (folder, exudyn))]
    fn save(
        &self,
        py: Python<'_>,
        folder: std::path::PathBuf,
        exudyn: bool,
    ) -> PyResult<Vec<String>> {
        let body = &self.body;
        let reduced = &self.reduced;
        computing(py, None, |_| {
            let mut r = reduced.lock().expect("not poisoned");
            if exudyn {
                r.with_exudyn(body)?;
            }
            Ok(r.write(body, &folder)?.files)
        })
    }
}

/// Threads for the dense and sparse kernels (None: every core); returns how many are used.
/// The pool is built once per process: only the first call (the import's, with every core)
/// can raise the count, later calls can only lower what the kernels use.
#[pyfunction]
#[pyo3(signature = (threads=None))]
fn set_threads(threads: Option<usize>) -> usize {
    flexmodes::linalg::set_threads(threads)
}

/// Threads the kernels use.
#[pyfunction]
fn threads() -> usize {
    flexmodes::linalg::threads()
}

#[pymodule]
fn _flexmodes(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Every core, as the command line uses by default.
    flexmodes::linalg::set_threads(None);
    m.add_function(wrap_pyfunction!(set_threads, m)?)?;
    m.add_function(wrap_pyfunction!(threads, m)?)?;
    m.add_class::<RustBody>()?;
    m.add_class::<RustReducedModel>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
