//! [`export`]: reduce a body and write the reduced model (see the module `export`).

use super::{ExudynBody, exudyn_body};
use crate::error::ReductionError;
use std::{
    path::{Path, PathBuf},
    time::Instant,
};

use faer::Mat;

use crate::{
    Error, Progress, Result,
    analysis::{count_zero_energy_modes_by, zero_energy_below, zero_energy_threshold_hz},
    atomic_file::write_atomically,
    body_file::{ImportedBody, write_array, write_npy},
    fem::{FeModel, InertiaLoads},
    linalg::{SturmCount, generalized_eigen},
    models::{BodyInterfaces, BodyReducer, macneal_rubin_on_body},
    reduction::{
        AveragingInterface, Basis, CONSTRAINT_COUPLING_TOLERANCE, Eigensolver, InteriorProblem,
        Method, ModeSelection, ReducedMatrices, ReductionRequest, RigidInterface, SolverPath,
        reduce, reduce_interface, reduce_interior, tie_rigid_interfaces,
        with_inertia_residual_vectors,
    },
};

impl std::fmt::Display for PsiFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

impl std::str::FromStr for PsiFormat {
    type Err = crate::error::UnknownId;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "npy" => Ok(Self::Npy),
            "mtx" => Ok(Self::MatrixMarket),
            other => Err(crate::error::UnknownId::new("Ψ format", other, &Self::IDS)),
        }
    }
}

/// How Ψ is written.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum PsiFormat {
    /// `psi.npy`: binary, for `numpy.load` (8 bytes a value, written at disk speed).
    #[default]
    Npy,
    /// `psi.mtx`: Matrix Market `array real general` text (~25 bytes a value).
    MatrixMarket,
}

impl PsiFormat {
    /// The ids `--psi-format` takes.
    pub const IDS: [&'static str; 2] = ["npy", "mtx"];

    /// `npy` or `mtx`.
    pub fn id(self) -> &'static str {
        match self {
            Self::Npy => "npy",
            Self::MatrixMarket => "mtx",
        }
    }

    /// The file name Ψ is written to.
    pub fn file_name(self) -> &'static str {
        match self {
            Self::Npy => "psi.npy",
            Self::MatrixMarket => "psi.mtx",
        }
    }
}

/// Settings of [`export`].
#[derive(Debug, Clone, PartialEq)]
pub struct ExportParameters {
    /// The format of Ψ.
    pub psi_format: PsiFormat,
    /// Node sets of the boundary tied rigidly to a master node each (RBE2): the reduced model
    /// sees each as its master's six DOF.
    pub rigid_interfaces: Vec<RigidInterface>,
    /// Node sets averaged into a master node each (RBE3): loads for the load-built methods.
    pub averaging_interfaces: Vec<AveragingInterface>,
    /// Reduce the remaining constraint modes to this many characteristic constraint modes.
    pub interface_modes: Option<usize>,
    /// Also write the body for Exudyn (`exudyn/`, see [`super::exudyn_body`]): the floating
    /// frame on the first rigid interface.
    pub exudyn: bool,
    /// Write the geometric stiffness of a body file's `[preload]` (`--stiffening on`, the
    /// default).
    pub stiffening: bool,
    /// Append the residual vectors of the frame's inertia loads to a fixed-interface basis
    /// (GR, MT, CB, MC: [`crate::reduction::with_inertia_residual_vectors`]).
    pub residual_vectors: bool,
    /// The solver of the fixed-interface pairs on the sparse path and of the free-free pairs
    /// the load-built methods start from (`--eigensolver`; Lanczos by default).
    pub eigensolver: Eigensolver,
}

impl Default for ExportParameters {
    /// Ψ as `.npy`, no rigid or averaging interface, every constraint mode, no Exudyn body,
    /// the preload's stiffening written, no residual vectors, Lanczos.
    fn default() -> Self {
        Self {
            psi_format: PsiFormat::default(),
            rigid_interfaces: Vec::new(),
            averaging_interfaces: Vec::new(),
            interface_modes: None,
            exudyn: false,
            stiffening: true,
            residual_vectors: false,
            eigensolver: Eigensolver::default(),
        }
    }
}

/// What [`export`] wrote.
#[derive(Debug, Clone)]
pub struct ExportSummary {
    /// The folder.
    pub dir: PathBuf,
    /// Files written, by name.
    pub files: Vec<String>,
    /// Full DOF × reduced coordinates.
    pub shape: [usize; 2],
    /// Elastic frequencies of the reduced model, Hz.
    pub hz: Vec<f64>,
    /// The relative residual of each of [`Self::hz`].
    pub residuals: Vec<f64>,
    /// Zero-energy modes of the reduced model (judged against the body's own scale).
    pub zero_energy: usize,
    /// Wall time of each phase, s, in order.
    pub timings: Vec<(&'static str, f64)>,
    /// The Exudyn body, when asked for.
    pub exudyn: Option<ExudynBody>,
}

/// Reduces `body` by `method` on `boundary` (1-based nodes) keeping `modes` normal modes and
/// writes the reduced model to `dir` ([`reduce_for_export`], then [`ReducedExport::write`]).
pub fn export(
    body: &ImportedBody,
    method: Method,
    boundary: &[usize],
    modes: usize,
    dir: &Path,
    parameters: &ExportParameters,
) -> Result<ExportSummary> {
    let mut reduced = reduce_for_export(body, method, boundary, modes, parameters)?;
    let written = reduced.write(body, dir)?;
    reduced.timings.extend(written.timings);
    Ok(ExportSummary {
        dir: dir.to_path_buf(),
        files: written.files,
        shape: [reduced.basis.psi.nrows(), reduced.basis.psi.ncols()],
        hz: reduced.hz,
        residuals: reduced.residuals,
        zero_energy: reduced.zero_energy,
        timings: reduced.timings,
        exudyn: reduced.exudyn,
    })
}

/// What [`ReducedExport::write`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// Files written, by name.
    pub files: Vec<String>,
    /// Wall time of each writing phase, s, in order.
    pub timings: Vec<(&'static str, f64)>,
}

/// A reduced model as [`export`] writes it, in memory: Ψ, $K_r$, $M_r$, the reduced model's
/// checked elastic pairs and, when asked, the Exudyn body.
#[derive(Debug, Clone)]
pub struct ReducedExport {
    /// The method.
    pub method: Method,
    /// The interface nodes, 1-based.
    pub boundary: Vec<usize>,
    /// Kept normal modes as asked.
    pub kept_modes: usize,
    /// The settings it was built with.
    pub parameters: ExportParameters,
    /// The basis: Ψ (full DOF × reduced coordinates) and its labelled columns.
    pub basis: Basis,
    /// $K_r = \Psi^TK\Psi$.
    pub k_r: Mat<f64>,
    /// $M_r = \Psi^TM\Psi$.
    pub m_r: Mat<f64>,
    /// Elastic frequencies of the reduced model, Hz.
    pub hz: Vec<f64>,
    /// The relative residual of each of [`Self::hz`].
    pub residuals: Vec<f64>,
    /// Zero-energy modes of the reduced model (judged against the body's own scale).
    pub zero_energy: usize,
    /// The zero-energy threshold, Hz.
    pub zero_energy_threshold_hz: f64,
    /// The body's free-free Sturm check, when the method needed free-free modes.
    pub free_free_sturm: Option<Option<crate::linalg::SturmCount>>,
    /// The Exudyn body, when asked for.
    pub exudyn: Option<ExudynBody>,
    /// $\Psi^T K_{\sigma,1}\Psi$: the geometric stiffness of the body's preloaded
    /// centrifugal load per unit rate², (rad/s)⁻² times the stiffness unit (a body file's
    /// `[preload]`, unless left out).
    pub kg_r: Option<Mat<f64>>,
    /// Wall time of each phase, s, in order.
    pub timings: Vec<(&'static str, f64)>,
}

/// Reduces `body` as [`export`] does, without writing anything.
pub fn reduce_for_export(
    body: &ImportedBody,
    method: Method,
    boundary: &[usize],
    modes: usize,
    parameters: &ExportParameters,
) -> Result<ReducedExport> {
    let model = &body.model;
    let mut timings: Vec<(&'static str, f64)> = Vec::new();
    let started = Instant::now();
    let (basis, free_free_sturm) =
        export_basis(model, (method, boundary, modes), parameters, started)?;
    let total = started.elapsed().as_secs_f64();
    let s = &basis.statistics;
    timings.push(("factorisation", s.factorization_s));
    timings.push(("constraint modes", s.constraint_modes_s));
    timings.push(("fixed-interface modes", s.eigen_s));
    timings.push((
        "rest of the reduction",
        (total - s.factorization_s - s.constraint_modes_s - s.eigen_s).max(0.0),
    ));
    let mut phase = Instant::now();
    let mut lap = |name: &'static str, timings: &mut Vec<(&'static str, f64)>| {
        timings.push((name, phase.elapsed().as_secs_f64()));
        phase = Instant::now();
    };
    let reduced = ReducedMatrices::of(model, &basis);
    if reduced.structured && reduced.constraint_coupling > CONSTRAINT_COUPLING_TOLERANCE {
        return Err(ReductionError::ConstraintModesCouple {
            coupling: reduced.constraint_coupling,
            tolerance: CONSTRAINT_COUPLING_TOLERANCE,
        }
        .into());
    }
    let (k_r, m_r) = (reduced.k, reduced.m);
    lap("reduced matrices", &mut timings);
    let eig = generalized_eigen(k_r.as_ref(), m_r.as_ref(), "reduced model")?;
    let threshold = zero_energy_threshold_hz(model);
    let all_hz = eig.hz();
    let zero_energy = zero_energy_below(&all_hz, threshold);
    let hz: Vec<f64> = all_hz[zero_energy..].to_vec();
    let residuals: Vec<f64> = eig.residuals[zero_energy..].to_vec();
    lap("reduced eigenproblem", &mut timings);
    let exudyn = if parameters.exudyn {
        let ex = exudyn_body(
            body,
            &basis,
            &parameters.rigid_interfaces,
            &parameters.averaging_interfaces,
            parameters.stiffening,
        )?;
        lap("Exudyn basis", &mut timings);
        Some(ex)
    } else {
        None
    };
    let kg_r = match (&body.preload, parameters.stiffening) {
        (Some(p), true) => Some(basis.project(&p.rate_squared)),
        _ => None,
    };
    Ok(ReducedExport {
        kg_r,
        method,
        boundary: boundary.to_vec(),
        kept_modes: modes,
        parameters: parameters.clone(),
        basis,
        k_r,
        m_r,
        hz,
        residuals,
        zero_energy,
        zero_energy_threshold_hz: threshold,
        free_free_sturm,
        exudyn,
        timings,
    })
}

/// The basis of `method` on `boundary` with `modes` kept modes as [`export`] builds it, and the
/// body's free-free Sturm check when the method needed the free-free modes. `started` is when
/// the export began (a body reducer's shared work counts from it).
fn export_basis(
    model: &FeModel,
    (method, boundary, modes): (Method, &[usize], usize),
    parameters: &ExportParameters,
    started: Instant,
) -> Result<(Basis, Option<Option<SturmCount>>)> {
    // These have no unit boundary columns: rigid interfaces are tied after them, naming the
    // DOF, and their interface shapes reduced after that.
    let tied_after = matches!(
        method,
        Method::MacNealRubin | Method::NoReduction | Method::Eitelberg
    );
    let built = match method {
        Method::MacNealRubin => Some(macneal_rubin_on_body(model, boundary, modes)?),
        Method::BenfieldHruda | Method::MomentMatching | Method::BalancedTruncation => None,
        // An averaging interface: BodyReducer says which methods it takes.
        _ if !parameters.averaging_interfaces.is_empty() => None,
        Method::NoReduction | Method::Eitelberg => Some(reduce(
            model,
            &ReductionRequest {
                method,
                boundary_nodes: boundary.to_vec(),
                modes: ModeSelection::Count(modes),
                solver: SolverPath::Auto,
                ..Default::default()
            },
        )?),
        _ => Some(interior_basis(
            model,
            (method, boundary, modes),
            parameters,
        )?),
    };
    match built {
        Some(b) if tied_after => {
            let b = tie_rigid_interfaces(model, b, &parameters.rigid_interfaces)?;
            let b = match parameters.interface_modes {
                Some(count) => reduce_interface(model, b, count)?,
                None => b,
            };
            Ok((b, None))
        }
        Some(b) => Ok((b, None)),
        None => {
            // Built from the interface loads and the body's free-free modes (models'
            // BodyReducer): rigid interfaces give their masters' six loads, nothing to tie.
            let full = count_zero_energy_modes_by(model, 10, parameters.eigensolver)?.0;
            let sturm = full.modes.sturm;
            let interfaces = BodyInterfaces {
                boundary: boundary.to_vec(),
                rigid: parameters.rigid_interfaces.clone(),
                averaging: parameters.averaging_interfaces.clone(),
                interface_modes: parameters.interface_modes,
            };
            let full_s = started.elapsed().as_secs_f64();
            let basis = BodyReducer::new(model, interfaces, &full, full_s, Progress::default())?
                .with_residual_vectors(parameters.residual_vectors)
                .reduce(method, modes)?
                .basis;
            Ok((basis, Some(sturm)))
        }
    }
}

/// A fixed-interface method's basis (GR, MT, CB, MC) from the interior problem, rigid
/// interfaces tied in its boundary coordinates (six constraint modes per master), interface
/// shapes reduced where asked, then the inertia-load residual vectors where asked and the
/// boundary holds the body (modal truncation may have none).
fn interior_basis(
    model: &FeModel,
    (method, boundary, modes): (Method, &[usize], usize),
    parameters: &ExportParameters,
) -> Result<Basis> {
    let mut problem = InteriorProblem::new(model, boundary, SolverPath::Auto)?
        .with_eigensolver(parameters.eigensolver)
        .with_rigid_interfaces(&parameters.rigid_interfaces)?;
    let basis = reduce_interior(
        &mut problem,
        &ReductionRequest::of(method).modes(ModeSelection::Count(modes)),
    )?;
    let basis = match parameters.interface_modes {
        Some(count) => reduce_interface(model, basis, count)?,
        None => basis,
    };
    if parameters.residual_vectors && problem.check_restraint().is_ok() {
        let loads = InertiaLoads::of(model);
        Ok(with_inertia_residual_vectors(&mut problem, basis, &loads)?.0)
    } else {
        Ok(basis)
    }
}

impl ReducedExport {
    /// Adds the Exudyn body ([`exudyn_body`]: the floating frame on the first rigid
    /// interface) when it is not there yet.
    pub fn with_exudyn(&mut self, body: &ImportedBody) -> Result<&ExudynBody> {
        if self.exudyn.is_none() {
            let started = Instant::now();
            self.exudyn = Some(exudyn_body(
                body,
                &self.basis,
                &self.parameters.rigid_interfaces,
                &self.parameters.averaging_interfaces,
                self.parameters.stiffening,
            )?);
            self.timings
                .push(("Exudyn basis", started.elapsed().as_secs_f64()));
            self.parameters.exudyn = true;
        }
        Ok(self.exudyn.as_ref().expect("set above"))
    }

    /// Writes Ψ (`psi.npy` or `psi.mtx`), `k_r.mtx`, `m_r.mtx`, `model.json` and, when
    /// present, `exudyn/` into `dir`: a temporary folder renamed into place, so `dir` is
    /// either the old folder or the complete new one. Returns the files' names and the wall
    /// time of each writing phase, s.
    pub fn write(&self, body: &ImportedBody, dir: &Path) -> Result<Written> {
        let doc = self.document(body);
        let comment = format!(
            "{} of {} ({}), interface {:?}, {} kept modes; flexmodes export",
            self.method.name(),
            body.model.name,
            body.location.display(),
            self.boundary,
            self.kept_modes
        );
        let psi_format = self.parameters.psi_format;
        let (basis, k_r, m_r, exudyn) = (&self.basis, &self.k_r, &self.m_r, &self.exudyn);
        let mut laps = Vec::new();
        let timings = &mut laps;
        let mut phase = Instant::now();
        let mut lap = |name: &'static str, timings: &mut Vec<(&'static str, f64)>| {
            timings.push((name, phase.elapsed().as_secs_f64()));
            phase = Instant::now();
        };
        // Write into a temporary folder, then rename it into place.
        let io = |path: &Path| {
            let path = path.to_path_buf();
            move |source| Error::Io { path, source }
        };
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "export".into());
        let parent = dir
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent).map_err(io(parent))?;
        let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir(&tmp).map_err(io(&tmp))?;
        let written = (|| -> Result<Vec<String>> {
            let psi_name = psi_format.file_name();
            match psi_format {
                PsiFormat::Npy => write_npy(&tmp.join(psi_name), basis.psi.as_ref())?,
                PsiFormat::MatrixMarket => {
                    write_array(&tmp.join(psi_name), basis.psi.as_ref(), false, &comment)?
                }
            }
            lap("write Ψ", timings);
            write_array(&tmp.join("k_r.mtx"), k_r.as_ref(), true, &comment)?;
            write_array(&tmp.join("m_r.mtx"), m_r.as_ref(), true, &comment)?;
            let text = serde_json::to_string_pretty(&doc).expect("JSON of plain values");
            write_atomically(&tmp.join("model.json"), |w| w.write_all(text.as_bytes()))?;
            lap("write K_r, M_r, model.json", timings);
            let mut files = vec![
                psi_name.into(),
                "k_r.mtx".into(),
                "m_r.mtx".into(),
                "model.json".into(),
            ];
            if let Some(kg) = &self.kg_r {
                write_array(&tmp.join("kg_r.mtx"), kg.as_ref(), true, &comment)?;
                files.push("kg_r.mtx".into());
            }
            if let Some(e) = &exudyn {
                files.extend(e.write(body, &tmp.join("exudyn"))?);
                lap("write the Exudyn body", timings);
            }
            Ok(files)
        })();
        let files = match written {
            Ok(f) => f,
            Err(e) => {
                let _ = std::fs::remove_dir_all(&tmp);
                return Err(e);
            }
        };
        let old = parent.join(format!(".{name}.old-{}", std::process::id()));
        let had_old = dir.exists();
        if had_old {
            std::fs::rename(dir, &old).map_err(io(dir))?;
        }
        if let Err(e) = std::fs::rename(&tmp, dir) {
            if had_old {
                let _ = std::fs::rename(&old, dir);
            }
            let _ = std::fs::remove_dir_all(&tmp);
            return Err(io(dir)(e));
        }
        if had_old {
            let _ = std::fs::remove_dir_all(&old);
        }
        Ok(Written {
            files,
            timings: laps,
        })
    }
}
