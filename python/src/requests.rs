//! What the Python side hands over for one call: a dict per request, its keys the fields
//! below (flexmodes/__init__.py builds them from its keyword arguments, checked there and
//! again here by type). A missing key or a value of the wrong type is a `TypeError` naming the
//! key.

use std::collections::BTreeMap;

use numpy::PyReadonlyArray1;
use pyo3::prelude::*;

/// A sparse matrix as Python hands it over: its shape and its entries' 0-based rows and
/// columns and values.
pub(crate) type Triplets<'py> = (
    (usize, usize),
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, f64>,
);

/// An interface as Python hands it over: kind (`rbe2`, `rbe3`), node set, master point
/// (None: the set's centroid), RBE3 weights.
pub(crate) type GivenInterface = (String, String, Option<[f64; 3]>, Option<Vec<f64>>);

/// Everything of a body from entries but its matrices: DOF names, node coordinates, node
/// sets, interfaces and units.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct BodyLayout {
    pub dofs: Vec<String>,
    pub nodes: Option<Vec<[f64; 3]>>,
    pub node_sets: BTreeMap<String, Vec<usize>>,
    pub interfaces: BTreeMap<String, GivenInterface>,
    pub default_interface: Option<String>,
    /// Length, mass and force.
    pub units: (String, String, String),
}

/// A reduction as `flexmodes export` makes it.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct ReduceRequest {
    pub method: String,
    pub boundary: Option<Vec<String>>,
    pub modes: usize,
    pub interface_modes: Option<usize>,
    pub exudyn: bool,
    pub eigensolver: String,
    pub residual_vectors: bool,
}

/// The comparison of `bench modes --body`.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct CompareRequest {
    pub methods: Option<Vec<String>>,
    pub modes: Option<Vec<usize>>,
    pub boundary: Option<Vec<String>>,
    pub interface_modes: Option<usize>,
    pub band_hz: Option<f64>,
    pub tolerance: f64,
}

/// The Campbell table of `flexmodes campbell`.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct CampbellRequest {
    pub drive: String,
    /// Spin rates, rad/s.
    pub rates: Vec<f64>,
    pub axis: [f64; 3],
    pub axis_point: Option<[f64; 3]>,
    pub count: usize,
    pub methods: Vec<String>,
    pub modes: Vec<usize>,
    /// Whether the full body is solved too.
    pub full: bool,
    pub stiffening: bool,
    pub residual_vectors: bool,
}

/// The driven body of `flexmodes simulate --body`.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct SimulateRequest {
    pub drive: String,
    pub methods: Vec<String>,
    pub modes: Vec<usize>,
    /// Whether the full body is integrated too.
    pub full: bool,
    pub boundary: Vec<String>,
    pub outputs: Vec<String>,
    /// Final rate, rad/s, and the ramp to it, s.
    pub rate: f64,
    pub ramp: f64,
    pub axis: [f64; 3],
    /// Simulated interval and step, s.
    pub end: f64,
    pub step: f64,
    pub output_every: usize,
    pub pinned: Vec<String>,
    pub axis_point: Option<[f64; 3]>,
    /// Direction, amplitude (m) and frequency (Hz) of the drive's shake.
    pub shake: Option<([f64; 3], f64, f64)>,
    /// Gravity in ground axes, m/s².
    pub gravity: Option<[f64; 3]>,
    pub spectral_radius: f64,
    pub mean_axes: bool,
    pub stiffening: bool,
    pub residual_vectors: bool,
}
