//! A body's preloaded stiffness from its FE code: the stiffness CalculiX writes for a body
//! spinning at a known rate, and from it the geometric stiffness of the centrifugal load per
//! unit rate², which a driven frame scales with the square of its own rate.
//!
//! CalculiX writes it with a `*STEP, PERTURBATION` whose `*FREQUENCY, SOLVER=MATRIXSTORAGE`
//! follows a `*STATIC` step loaded by `*DLOAD … CENTRIF, Ω₀², x, y, z, a, b, c`: the `.sti`
//! then holds $K_0 = K + K_\sigma(\Omega_0) + \Omega_0^2 H$, the elastic stiffness, the stress
//! stiffening of the centrifugal prestress and the spin softening $\Omega_0^2 H$
//! ($H = M(I\otimes\tilde e^2)$, $e$ the axis), on the DOF the static step left free. The
//! floating frame already makes the softening from $M$, so flexmodes keeps
//! $$K_{\sigma,1} = (K_0 - K - \Omega_0^2 H)/\Omega_0^2$$
//! on those DOF (zero on the held ones) and adds $\dot\theta^2 K_{\sigma,1}$ at any rate: the
//! prestress of a linear static step is linear in $\Omega^2$.

use nalgebra::{Unit, Vector3};
use serde::Deserialize;

use super::{BodyFileError, BodyLocation, calculix_matrix, matrix_bytes::line_error};
use crate::{
    Error, Result,
    error::{BodySpecProblem, MatrixLineProblem},
    fem::FeModel,
    linalg::{MassMatrix, SparseSymmetric},
};

/// A body file's `[preload]` table: CalculiX's files of the spinning run.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PreloadSpec {
    /// The `.sti` of the perturbation step (stiffness with stress stiffening and spin
    /// softening), relative to the body file.
    pub stiffness: String,
    /// Its `.dof`: the equations of the DOF the static step left free.
    pub dof_map: String,
    /// The `.inp` deck: its `CENTRIF` load gives the rate, a point of the axis and the axis.
    pub deck: String,
}

/// The centrifugal load of a CalculiX deck.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentrifugalLoad {
    /// Ω₀, rad/s.
    pub rate: f64,
    /// A point of the axis (the body's length unit).
    pub point: [f64; 3],
    /// The axis, normalised.
    pub axis: Unit<Vector3<f64>>,
}

/// The geometric stiffness of the centrifugal load per unit rate², from a preloaded
/// stiffness.
#[derive(Debug, Clone)]
pub struct Preload {
    /// The load it was written for.
    pub load: CentrifugalLoad,
    /// The body's DOF (0-based) the static step held: the spinning frame must hold them.
    pub held: Vec<usize>,
    /// $K_{\sigma,1}$ on every DOF of the body (zero rows on the held ones).
    pub rate_squared: SparseSymmetric,
}

/// Reads the `CENTRIF` load of deck `path`: the first `*DLOAD` data line whose second field
/// is `CENTRIF` (case-insensitive), `set, CENTRIF, Ω², x, y, z, a, b, c`.
pub fn parse_centrifugal_load(bytes: &[u8], path: &str) -> Result<CentrifugalLoad> {
    let text = String::from_utf8_lossy(bytes);
    let problem = |line: usize, text: &str, reason: &'static str| -> Error {
        line_error(
            path,
            line,
            MatrixLineProblem::NotLayout {
                text: text.trim().into(),
                layout: reason,
            },
        )
    };
    for (i, line) in text.lines().enumerate() {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() < 2 || !fields[1].eq_ignore_ascii_case("centrif") {
            continue;
        }
        const LAYOUT: &str = "set, CENTRIF, Ω², x, y, z, a, b, c (Ω² > 0, a nonzero axis)";
        if fields.len() < 9 {
            return Err(problem(i + 1, line, LAYOUT));
        }
        let v: Vec<f64> = fields[2..9]
            .iter()
            .map(|f| f.parse::<f64>().map_err(|_| problem(i + 1, line, LAYOUT)))
            .collect::<Result<_>>()?;
        let axis = Vector3::new(v[4], v[5], v[6]);
        if !(v[0].is_finite() && v[0] > 0.0 && axis.norm() > 0.0 && axis.norm().is_finite()) {
            return Err(problem(i + 1, line, LAYOUT));
        }
        return Ok(CentrifugalLoad {
            rate: v[0].sqrt(),
            point: [v[1], v[2], v[3]],
            axis: Unit::new_normalize(axis),
        });
    }
    Err(problem(
        0,
        "",
        "a *DLOAD line `set, CENTRIF, Ω², x, y, z, a, b, c`",
    ))
}

/// $H = M(I \otimes \tilde e^2)$, the spin softening per unit rate² as the floating frame
/// applies it ($M\tilde e^2$ node by node), as triplets scaled by `scale`: each stored entry
/// $M_{i,3b+c}$ gives $M_{i,3b+c}\,(\tilde e^2)_{cd}$ at $(i, 3b+d)$, with $\tilde e^2 =
/// ee^T - I$.
fn centrifugal_triplets(
    m: &MassMatrix,
    axis: &Vector3<f64>,
    scale: f64,
) -> Vec<(usize, usize, f64)> {
    let e2 = axis * axis.transpose() - nalgebra::Matrix3::identity();
    let mut out = Vec::new();
    let mut entry = |i: usize, j: usize, v: f64| {
        let (b, c) = (j / 3, j % 3);
        for d in 0..3 {
            let w = scale * v * e2[(c, d)];
            if w != 0.0 {
                out.push((i, 3 * b + d, w));
            }
        }
    };
    match m {
        MassMatrix::Lumped(d) => d.iter().enumerate().for_each(|(i, &v)| entry(i, i, v)),
        MassMatrix::Consistent(s) => {
            let inner = s.as_faer();
            for j in 0..inner.ncols() {
                let rows = inner.symbolic().row_idx_of_col_raw(j);
                for (&i, &v) in rows.iter().zip(inner.val_of_col(j)) {
                    entry(i, j, v);
                }
            }
        }
    }
    out
}

impl Preload {
    /// Reads `spec`'s files beside the body file at `location` and forms $K_{\sigma,1}$ for
    /// `model` (solid DOF; its K and M the body's at rest, in the same units as the
    /// preloaded run).
    pub fn read(model: &FeModel, location: &BodyLocation, spec: &PreloadSpec) -> Result<Self> {
        if model.dofs != crate::fem::DofMap::solid() {
            return Err(Error::BodyFile(BodyFileError::BodyFile {
                path: location.display().into(),
                line: None,
                problem: BodySpecProblem::PreloadNeedsSolid,
            }));
        }
        let (deck, deck_name) = location.read(Some(&spec.deck))?;
        let load = parse_centrifugal_load(&deck, &deck_name)?;
        let (map_bytes, map_name) = location.read(Some(&spec.dof_map))?;
        let n = model.dof_count();
        let equations = calculix_matrix::parse_calculix_dof_map_partial(
            &map_bytes,
            &map_name,
            &model.dofs,
            model.node_count(),
        )?;
        let (k_bytes, k_name) = location.read(Some(&spec.stiffness))?;
        let spun = calculix_matrix::parse_calculix_matrix(&k_bytes, &k_name, equations.len())?;
        let mut kept = vec![false; n];
        equations.iter().for_each(|&d| kept[d] = true);
        let held: Vec<usize> = (0..n).filter(|&d| !kept[d]).collect();
        let omega2 = load.rate * load.rate;
        let mut entries = Vec::with_capacity(3 * spun.entries.len());
        for &(i, j, v) in &spun.entries {
            let (a, b) = (equations[i], equations[j]);
            entries.push((a, b, v / omega2));
            if a != b {
                entries.push((b, a, v / omega2));
            }
        }
        let k = model.k.as_faer();
        for j in 0..n {
            if !kept[j] {
                continue;
            }
            let rows = k.symbolic().row_idx_of_col_raw(j);
            for (&i, &v) in rows.iter().zip(k.val_of_col(j)) {
                if kept[i] {
                    entries.push((i, j, -v / omega2));
                }
            }
        }
        for (i, j, v) in centrifugal_triplets(&model.m, &load.axis, -1.0) {
            if kept[i] && kept[j] {
                entries.push((i, j, v));
            }
        }
        let rate_squared = SparseSymmetric::from_triplets(n, &entries);
        Ok(Self {
            load,
            held,
            rate_squared,
        })
    }
}
