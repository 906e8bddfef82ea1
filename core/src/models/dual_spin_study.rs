//! Spanos–Tsuha §4 on an assembly of our own (a dual-spin rotor on a grounded stator with a
//! rigid platform): Craig–Bampton, MacNeal–Rubin and Benfield–Hruda component mode sets
//! truncated at twice the frequency of interest, joined by component mode synthesis, against
//! the full model's motor-to-platform response; then the rotor's CB modes ranked by
//! Gregory's influence coefficients against as many lowest-frequency modes.

use crate::reduction::{ReductionRequest, reduce, reduce_interior};
use faer::Mat;

use crate::{
    Result,
    analysis::{FrequencyResponse, band_frequencies},
    fem::{DualSpin, DualSpinParameters, FeModel, NodeIndex, add_lumped, dual_spin},
    linalg::{GeneralizedEigen, generalized_eigen, identity},
    reduction::{
        Basis, Component, InterfaceLoading, InteriorProblem, IoMap, LoadedInterface,
        MacNealRubinParameters, Method, ModalModel, ModeSelection, Partition, SolverPath,
        Synthesis, benfield_hruda, macneal_rubin, modal_influence,
    },
};

/// The mode sets of the study, in Spanos–Tsuha's order.
pub const DUAL_SPIN_METHODS: [Method; 3] = [
    Method::CraigBampton,
    Method::MacNealRubin,
    Method::BenfieldHruda,
];
/// Rotor angles (degrees) of the other frozen configurations the study repeats at.
pub const ARTICULATION_DEG: [f64; 2] = [11.25, 22.5];
/// Modes of the full assembly drawn at most.
const DRAWN_MODES: usize = 9;

/// One mode set, assembled, against the full response.
#[derive(Debug, Clone)]
pub struct AssembledSet {
    /// The method.
    pub method: Method,
    /// Rotor and stator coordinates, and the assembled system's.
    pub coordinates: [usize; 3],
    /// Its response on the study's frequencies.
    pub frf: FrequencyResponse,
    /// Max over channels and frequencies of ||G̃| − |G|| over the channel's peak |G|.
    pub error: f64,
}

/// The rotor's kept elastic modes (by influence or lowest), assembled with the stator's CB set.
#[derive(Debug, Clone)]
pub struct RotorSelection {
    /// The response.
    pub frf: FrequencyResponse,
    /// Its error against the full response.
    pub error: f64,
}

/// Everything the study computes.
#[derive(Debug, Clone)]
pub struct DualSpinStudy {
    /// The assembly's parameters.
    pub params: DualSpinParameters,
    /// The assembly.
    pub ds: DualSpin,
    /// The reference synthesis with identity bases.
    pub full: Synthesis,
    /// Its frequencies, Hz.
    pub full_hz: Vec<f64>,
    /// Modes of the full model up to [`INTEREST_HZ`].
    pub in_band: usize,
    /// The full response on the study's frequencies (0 to [`INTEREST_HZ`]).
    pub reference: FrequencyResponse,
    /// Each requested mode set.
    pub sets: Vec<AssembledSet>,
    /// Benfield–Hruda truncated at [`TRUNCATION_HZ`] like the others (when BH is requested).
    pub bh_truncated: Option<AssembledSet>,
    /// The rotor's ranking.
    pub ranking: RotorRanking,
    /// The rotor's modes kept by influence, then as many lowest ones.
    pub selections: [RotorSelection; 2],
    /// At each of [`ARTICULATION_DEG`]: every set's error, then influence's and lowest's.
    pub articulation: Vec<(f64, Vec<f64>, [f64; 2])>,
    /// The first modes of the full assembly on every node, with their frequencies.
    pub shapes: Vec<(Vec<f64>, f64)>,
}

impl DualSpinStudy {
    /// The rotor's elastic modes.
    pub fn rotor_elastic(&self) -> usize {
        self.ranking.modes.mode_count() - self.ranking.modes.rigid
    }
}

/// Runs the study for `methods` (a subset of [`DUAL_SPIN_METHODS`]); with `threads` above 1
/// the other articulations ([`ARTICULATION_DEG`], independent assemblies) run on a second
/// thread beside the first.
pub fn dual_spin_study(methods: &[Method], threads: usize) -> Result<DualSpinStudy> {
    let params = DualSpinParameters::default();
    let articulate = || {
        ARTICULATION_DEG
            .iter()
            .map(|&degrees| {
                let (sets, selected) = errors_at(
                    &DualSpinParameters {
                        rotor_angle: degrees.to_radians(),
                        ..params.clone()
                    },
                    methods,
                )?;
                Ok((degrees, sets, selected))
            })
            .collect::<Result<Vec<_>>>()
    };
    if threads > 1 {
        std::thread::scope(|scope| {
            let articulation = scope.spawn(articulate);
            let study = study_at_rest(&params, methods)?;
            let articulation = articulation
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))?;
            Ok(DualSpinStudy {
                articulation,
                ..study
            })
        })
    } else {
        let study = study_at_rest(&params, methods)?;
        Ok(DualSpinStudy {
            articulation: articulate()?,
            ..study
        })
    }
}

/// The study of the assembly at rest (rotor angle of `params`), without the articulations.
fn study_at_rest(params: &DualSpinParameters, methods: &[Method]) -> Result<DualSpinStudy> {
    let params = params.clone();
    let ds = dual_spin(&params)?;
    let dof_sets = DualSpinSets::of(&ds)?;
    let full_syn = full_synthesis(&ds, &dof_sets)?;
    let full_eig = generalized_eigen(full_syn.k.as_ref(), full_syn.m.as_ref(), "assembly")?;
    let full = io_model_of(&ds, &full_syn, &full_eig)?;
    let cb = CbSets::of(&ds, &dof_sets)?;
    let full_hz = full.hz();
    let hz = band_frequencies(0.0, INTEREST_HZ, 600, &full_hz);
    let reference = response(&full, &hz);
    let in_band = full_hz.iter().filter(|&&f| f <= INTEREST_HZ).count();
    let assembled = |method: Method, [rotor, stator]: [Mat<f64>; 2]| -> Result<AssembledSet> {
        let (nr, ns) = (rotor.ncols(), stator.ncols());
        let syn = assemble(&ds, rotor, stator)?;
        let frf = response(&io_model(&ds, &syn)?, &hz);
        let error = frf.relative_magnitude_error(&reference)?;
        Ok(AssembledSet {
            method,
            coordinates: [nr, ns, syn.size()],
            frf,
            error,
        })
    };
    let sets = methods
        .iter()
        .map(|&m| assembled(m, mode_set_bases(&ds, &dof_sets, m, &cb)?))
        .collect::<Result<Vec<_>>>()?;
    let bh_truncated = if methods.contains(&Method::BenfieldHruda) {
        let cut = ModeSelection::UpToHz(TRUNCATION_HZ);
        Some(assembled(
            Method::BenfieldHruda,
            benfield_hruda_bases(&ds, &dof_sets, cut, cut)?,
        )?)
    } else {
        None
    };
    let ranking = rank_rotor(&ds, &dof_sets, &cb)?;
    let rigid = ranking.modes.rigid;
    let select = |kept: &[usize]| -> Result<RotorSelection> {
        let keep: Vec<usize> = (0..rigid).chain(kept.iter().copied()).collect();
        let syn = assemble(&ds, ranking.modes.keep(&keep).shapes, cb.stator.clone())?;
        let frf = response(&io_model(&ds, &syn)?, &hz);
        let error = frf.relative_magnitude_error(&reference)?;
        Ok(RotorSelection { frf, error })
    };
    let selections = [select(&ranking.influence)?, select(&ranking.lowest)?];
    let shapes = expand_modes(&ds.assembly, &full_syn, &full_eig, in_band.min(DRAWN_MODES))?;
    Ok(DualSpinStudy {
        params,
        ds,
        full: full_syn,
        full_hz,
        in_band,
        reference,
        sets,
        bh_truncated,
        ranking,
        selections,
        articulation: Vec::new(),
        shapes,
    })
}

/// The first `count` modes of a synthesis on every assembly DOF, with their frequencies.
fn expand_modes(
    assembly: &FeModel,
    s: &Synthesis,
    eig: &GeneralizedEigen,
    count: usize,
) -> Result<Vec<(Vec<f64>, f64)>> {
    let hz = eig.hz();
    let per = assembly.dofs.per_node();
    let mut rows = Vec::with_capacity(assembly.node_count());
    for node in 0..assembly.node_count() {
        rows.push(s.node_rows(node)?);
    }
    Ok((0..count.min(hz.len()))
        .map(|j| {
            let mut u = vec![0.0; assembly.dof_count()];
            for (node, r) in rows.iter().enumerate() {
                for d in 0..per {
                    u[node * per + d] = (0..r.ncols())
                        .map(|q| r[(d, q)] * eig.vectors[(q, j)])
                        .sum();
                }
            }
            (u, hz[j])
        })
        .collect())
}

/// The system frequency of interest, Hz (the paper's 10 Hz).
pub const INTEREST_HZ: f64 = 10.0;

/// Component modes are truncated above twice that (Spanos–Tsuha, p. 6).
pub const TRUNCATION_HZ: f64 = 20.0;

/// Uniform modal damping ratio of the FRFs and the influence coefficients (the paper gives
/// none).
pub const ZETA: f64 = 0.01;

/// Rotor modes whose influence coefficient is at least this fraction of the largest are kept.
pub const INFLUENCE_FRACTION: f64 = 1e-3;

/// The DOF sets of the two flexible components (0-based component DOF).
#[derive(Debug, Clone)]
pub struct DualSpinSets {
    /// Rotor DOF at the hub (its interface with the stator).
    pub rotor_hub: Vec<usize>,
    /// Rotor r-set for MacNeal–Rubin: the six DOF of the first boom's first node.
    pub rotor_r_set: Vec<usize>,
    /// Stator DOF at its base (held: the ground).
    pub stator_base: Vec<usize>,
    /// Stator DOF at the hub.
    pub stator_hub: Vec<usize>,
    /// Stator DOF at the platform node.
    pub stator_platform: Vec<usize>,
}

impl DualSpinSets {
    /// The sets of an assembly.
    pub fn of(ds: &DualSpin) -> Result<Self> {
        Ok(Self {
            rotor_hub: ds.rotor.dofs_of_nodes(&[1])?,
            rotor_r_set: ds.rotor.dofs_of_nodes(&[2])?,
            stator_base: ds.stator.dofs_of_nodes(&[1])?,
            stator_hub: ds
                .stator
                .dofs_of_nodes(&[NodeIndex(ds.stator_hub).number()])?,
            stator_platform: ds
                .stator
                .dofs_of_nodes(&[NodeIndex(ds.stator_platform).number()])?,
        })
    }

    /// The stator's interface DOF: hub, then platform.
    pub fn stator_interface(&self) -> Vec<usize> {
        [self.stator_hub.clone(), self.stator_platform.clone()].concat()
    }
}

/// Rotor and stator bases of one mode set, truncated at [`TRUNCATION_HZ`].
/// One assembly's Craig–Bampton sets, solved once: the CB mode set itself, the size every
/// Benfield–Hruda set matches, the stator set every rotor selection is assembled with, and
/// the rotor modes Gregory's ranking diagonalises.
#[derive(Debug, Clone)]
pub struct CbSets {
    /// The rotor's CB basis (hub node 1 as its interface), truncated at [`TRUNCATION_HZ`].
    pub rotor: Basis,
    /// The stator's CB basis (hub and platform as interface, base held), on its DOF.
    pub stator: Mat<f64>,
}

impl CbSets {
    /// Solves both components' CB sets of `ds`.
    pub fn of(ds: &DualSpin, sets: &DualSpinSets) -> Result<Self> {
        let cut = ModeSelection::UpToHz(TRUNCATION_HZ);
        let rotor = reduce(
            &ds.rotor,
            &ReductionRequest::of(Method::CraigBampton)
                .boundary(&[1])
                .modes(cut),
        )?;
        let partition =
            Partition::from_dofs(&ds.stator, &sets.stator_interface(), &sets.stator_base)?;
        let mut problem = InteriorProblem::on(&ds.stator, partition, SolverPath::Auto)?;
        let stator = reduce_interior(
            &mut problem,
            &ReductionRequest::of(Method::CraigBampton).modes(cut),
        )?
        .psi;
        Ok(Self { rotor, stator })
    }
}

/// The rotor and stator bases of method `m` (one of [`DUAL_SPIN_METHODS`]); `cb` are the
/// assembly's CB sets.
pub fn mode_set_bases(
    ds: &DualSpin,
    sets: &DualSpinSets,
    m: Method,
    cb: &CbSets,
) -> Result<[Mat<f64>; 2]> {
    let cut = ModeSelection::UpToHz(TRUNCATION_HZ);
    Ok(match m {
        Method::CraigBampton => [cb.rotor.psi.clone(), cb.stator.clone()],
        Method::MacNealRubin => {
            let rotor = macneal_rubin(
                &ds.rotor,
                &MacNealRubinParameters {
                    interface: sets.rotor_hub.clone(),
                    r_set: sets.rotor_r_set.clone(),
                    modes: cut,
                    held: vec![],
                },
            )?;
            let stator = macneal_rubin(
                &ds.stator,
                &MacNealRubinParameters {
                    interface: sets.stator_interface(),
                    r_set: vec![],
                    modes: cut,
                    held: sets.stator_base.clone(),
                },
            )?;
            [rotor.psi, stator.psi]
        }
        _ => {
            // As many loaded modes as the CB set has coordinates, per component: the paper
            // eliminates the same number of DOF with every set (163 from the rotor, 35 from
            // the stator). A 20 Hz cut leaves the stiff stator five loaded modes, too few to
            // follow the hub and the platform (the scene shows that case too).
            benfield_hruda_bases(
                ds,
                sets,
                ModeSelection::Count(cb.rotor.psi.ncols()),
                ModeSelection::Count(cb.stator.ncols()),
            )?
        }
    })
}

/// Benfield–Hruda bases of rotor and stator with the given selections of loaded modes.
pub fn benfield_hruda_bases(
    ds: &DualSpin,
    sets: &DualSpinSets,
    rotor_modes: ModeSelection,
    stator_modes: ModeSelection,
) -> Result<[Mat<f64>; 2]> {
    // The rotor is loaded by the stator carrying the platform, through the hub.
    let mut stator_with_platform = ds.stator.clone();
    add_lumped(
        &mut stator_with_platform,
        ds.stator_platform,
        &ds.platform_mass,
    )?;
    let on_rotor =
        InterfaceLoading::of_component(&stator_with_platform, &sets.stator_hub, &sets.stator_base)?;
    let rotor = benfield_hruda(
        &ds.rotor,
        &[LoadedInterface {
            dofs: sets.rotor_hub.clone(),
            loading: on_rotor,
        }],
        &[],
        rotor_modes,
    )?;
    // The stator by the rotor (statically determinate interface: its rigid-body mass about
    // the hub) and by the platform.
    let by_rotor = InterfaceLoading::of_component(&ds.rotor, &sets.rotor_hub, &[])?;
    let by_platform = InterfaceLoading {
        mass: Mat::from_fn(6, 6, |i, j| if i == j { ds.platform_mass[i] } else { 0.0 }),
        stiffness: Mat::zeros(6, 6),
    };
    let stator = benfield_hruda(
        &ds.stator,
        &[
            LoadedInterface {
                dofs: sets.stator_hub.clone(),
                loading: by_rotor,
            },
            LoadedInterface {
                dofs: sets.stator_platform.clone(),
                loading: by_platform,
            },
        ],
        &sets.stator_base,
        stator_modes,
    )?;
    Ok([rotor.psi, stator.psi])
}

/// The assembly of a rotor and a stator basis with the platform's mass.
pub fn assemble(ds: &DualSpin, rotor: Mat<f64>, stator: Mat<f64>) -> Result<Synthesis> {
    let platform = Mat::from_fn(6, 6, |i, j| if i == j { ds.platform_mass[i] } else { 0.0 });
    Synthesis::new(
        &[
            Component {
                model: &ds.rotor,
                basis: rotor,
                nodes: ds.rotor_nodes.clone(),
            },
            Component {
                model: &ds.stator,
                basis: stator,
                nodes: ds.stator_nodes.clone(),
            },
        ],
        &[(ds.platform, platform)],
    )
}

/// The full model as a synthesis of identity bases (the stator's without its base DOF).
pub fn full_synthesis(ds: &DualSpin, sets: &DualSpinSets) -> Result<Synthesis> {
    let ns = ds.stator.dof_count();
    let free: Vec<usize> = (0..ns).filter(|d| !sets.stator_base.contains(d)).collect();
    let stator = Mat::from_fn(ns, free.len(), |r, c| if free[c] == r { 1.0 } else { 0.0 });
    assemble(ds, identity(ds.rotor.dof_count()), stator)
}

/// The motor-to-platform model: input the torque about z at the hub; outputs the platform's
/// rotation about z (its attitude about the spin axis) and about x.
pub fn io_model(ds: &DualSpin, s: &Synthesis) -> Result<ModalModel> {
    io_model_of(
        ds,
        s,
        &generalized_eigen(s.k.as_ref(), s.m.as_ref(), "reduced")?,
    )
}

/// [`io_model`] from the synthesis' eigenpairs `eig`, already solved.
fn io_model_of(ds: &DualSpin, s: &Synthesis, eig: &GeneralizedEigen) -> Result<ModalModel> {
    let hub = s.dof_row(ds.hub, 5)?;
    let yaw = s.dof_row(ds.platform, 5)?;
    let roll = s.dof_row(ds.platform, 3)?;
    let rows = Mat::from_fn(3, s.size(), |r, c| match r {
        0 => hub[(0, c)],
        1 => yaw[(0, c)],
        _ => roll[(0, c)],
    });
    ModalModel::of_eigen(
        eig,
        rows.as_ref(),
        &IoMap {
            inputs: vec![0],
            displacement_outputs: vec![1, 2],
            velocity_outputs: vec![],
        },
        ZETA,
    )
}

/// Gregory's ranking of the rotor's CB modes with the hub's six DOF as inputs and outputs
/// (Spanos–Tsuha's second stage: the interface treated as extra I/O, no assembly needed).
#[derive(Debug, Clone)]
pub struct RotorRanking {
    /// The rotor's diagonalised CB modes (rigid first), on the rotor's DOF.
    pub modes: ModalModel,
    /// σ per mode (∞ for rigid ones).
    pub sigma: Vec<f64>,
    /// Eq. (45)'s closeness over the elastic modes.
    pub closeness: f64,
    /// The elastic modes kept by influence (indices into `modes`).
    pub influence: Vec<usize>,
    /// As many elastic modes, the lowest by frequency.
    pub lowest: Vec<usize>,
}

/// Ranks the rotor's CB set.
pub fn rank_rotor(ds: &DualSpin, sets: &DualSpinSets, cb: &CbSets) -> Result<RotorRanking> {
    let cb = &cb.rotor;
    let k = cb.reduced_stiffness(&ds.rotor);
    let m = cb.reduced_mass(&ds.rotor);
    let modes = ModalModel::new(
        k.as_ref(),
        m.as_ref(),
        cb.psi.as_ref(),
        &IoMap {
            inputs: sets.rotor_hub.clone(),
            displacement_outputs: sets.rotor_hub.clone(),
            velocity_outputs: vec![],
        },
        ZETA,
    )?;
    let inf = modal_influence(&modes)?;
    let rigid = modes.rigid;
    let top = inf.sigma[rigid..].iter().fold(0.0f64, |a, &b| a.max(b));
    let influence: Vec<usize> = (rigid..modes.mode_count())
        .filter(|&i| inf.sigma[i] >= INFLUENCE_FRACTION * top)
        .collect();
    let lowest: Vec<usize> = (rigid..rigid + influence.len()).collect();
    Ok(RotorRanking {
        sigma: inf.sigma.clone(),
        closeness: inf.closeness,
        modes,
        influence,
        lowest,
    })
}

/// FRF errors of each mode set and of the two rotor selections at one articulation.
fn errors_at(params: &DualSpinParameters, methods: &[Method]) -> Result<(Vec<f64>, [f64; 2])> {
    let ds = dual_spin(params)?;
    let sets = DualSpinSets::of(&ds)?;
    let full = io_model(&ds, &full_synthesis(&ds, &sets)?)?;
    let hz = band_frequencies(0.0, INTEREST_HZ, 600, &full.hz());
    let cb = CbSets::of(&ds, &sets)?;
    let reference = response(&full, &hz);
    let error = |rotor: Mat<f64>, stator: Mat<f64>| -> Result<f64> {
        let syn = assemble(&ds, rotor, stator)?;
        response(&io_model(&ds, &syn)?, &hz).relative_magnitude_error(&reference)
    };
    let mut sets_err = Vec::new();
    for &m in methods {
        let [rotor, stator] = mode_set_bases(&ds, &sets, m, &cb)?;
        sets_err.push(error(rotor, stator)?);
    }
    let ranking = rank_rotor(&ds, &sets, &cb)?;
    let rigid = ranking.modes.rigid;
    let mut sel = [0.0; 2];
    for (k, kept) in [&ranking.influence, &ranking.lowest]
        .into_iter()
        .enumerate()
    {
        let keep: Vec<usize> = (0..rigid).chain(kept.iter().copied()).collect();
        sel[k] = error(ranking.modes.keep(&keep).shapes, cb.stator.clone())?;
    }
    Ok((sets_err, sel))
}

fn response(model: &ModalModel, hz: &[f64]) -> FrequencyResponse {
    FrequencyResponse::sample(hz, |w| model.frf(w))
}
