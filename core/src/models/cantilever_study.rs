//! Witteveen (World J. Mech. 2012) §4: Craig–Bampton, Krylov moment matching and balanced
//! truncation, 14 vectors each, built once on a clamped beam structure (variant 1) and then
//! used under supports changed on the reduced models only (A clamped: variant 2; A sliding
//! with 250 kg: variant 3). The study computes the full and reduced modes of each variant,
//! paired by MAC, the static load cases and the values Witteveen printed next to ours.

use crate::reduction::{ReductionRequest, reduce_interior};
use faer::Mat;

use crate::{
    Result,
    analysis::{ModePair, StaticLoadCase, full_static_response, modes_in_band, pair_modes},
    fem::{Direction, FeModel, NodeDof, OverhangFrame, OverhangFrameParameters, overhang_frame},
    linalg::{identity, principal_angles},
    reduction::{
        BalancedBasisParameters, Basis, InteriorProblem, Method, ModeSelection,
        MomentMatchingParameters, Partition, RestrainedRitzModel, SolverPath, balanced_basis,
        moment_matching,
    },
};

/// The methods of the study, in Witteveen's order.
pub const CANTILEVER_METHODS: [Method; 3] = [
    Method::CraigBampton,
    Method::MomentMatching,
    Method::BalancedTruncation,
];

/// The frequencies Witteveen printed that calibrate our geometry (his Fig. 1 is missing), Hz:
/// variant 1's mode 5, CB's 7th fixed-interface mode, variant 3's torsion of the bottom
/// section and variant 3's new mode (A moves most in x).
pub const PRINTED_HZ: Printed = Printed {
    variant1_mode5: 129.9,
    cb_seventh_fixed_interface: 331.0,
    variant3_torsion: 98.38,
    variant3_mass_mode: 145.1,
};

/// Witteveen's printed frequencies, Hz (see [`PRINTED_HZ`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Printed {
    pub variant1_mode5: f64,
    pub cb_seventh_fixed_interface: f64,
    pub variant3_torsion: f64,
    pub variant3_mass_mode: f64,
}

/// The full model's modes in one variant, paired with each method's reduced modes.
#[derive(Debug, Clone)]
pub struct VariantModes {
    /// 1, 2 or 3.
    pub variant: usize,
    /// The full model's frequencies in the band up to [`BAND_HZ`], Hz.
    pub band_hz: Vec<f64>,
    /// Their mode shapes, one column each (all DOF).
    pub shapes: Mat<f64>,
    /// For each method: each band mode paired with the reduced mode of best MAC.
    pub pairs: Vec<(Method, Vec<ModePair>)>,
    /// The bottom section's first torsion: (1-based mode in the band, Hz).
    pub first_torsion: Option<(usize, f64)>,
    /// The band mode in which A moves most in x, Hz.
    pub mass_mode_hz: Option<f64>,
}

/// One static load case: the deflection line of the bottom section, full and reduced.
#[derive(Debug, Clone)]
pub struct StaticCase {
    /// `lc1`, `lc2` or `v2`.
    pub id: &'static str,
    /// What is loaded and which deflection is judged.
    pub text: &'static str,
    /// The full model's line: (x, deflection) per bottom node, mm.
    pub full_line: Vec<[f64; 2]>,
    /// For each method: its line and its error ([`bottom_line_error`]).
    pub methods: Vec<(Method, Vec<[f64; 2]>, f64)>,
}

impl StaticCase {
    /// The full model's largest deflection magnitude, mm.
    pub fn peak(&self) -> f64 {
        self.full_line.iter().fold(0.0f64, |m, p| m.max(p[1].abs()))
    }

    /// `method`'s error, if it was computed.
    pub fn error(&self, method: Method) -> Option<f64> {
        self.methods
            .iter()
            .find(|(m, _, _)| *m == method)
            .map(|(_, _, e)| *e)
    }
}

/// Everything the study computes.
#[derive(Debug, Clone)]
pub struct CantileverStudy {
    /// The structure's parameters.
    pub params: OverhangFrameParameters,
    /// The structure.
    pub frame: OverhangFrame,
    /// Its input/output DOF and supports.
    pub io: CantileverIo,
    /// The methods' bases (14 vectors each, on variant 1).
    pub bases: Vec<Basis>,
    /// Moment matching's deflated columns.
    pub deflated: usize,
    /// Variants 1, 2, 3.
    pub variants: Vec<VariantModes>,
    /// Load cases LC 1, LC 2 and variant 2's.
    pub statics: Vec<StaticCase>,
    /// CB's fixed-interface frequencies, Hz (empty without CB).
    pub cb_fixed_interface_hz: Vec<f64>,
    /// Principal angles between the first three modes and the first three BT vectors,
    /// degrees (`None` without BT).
    pub subspace_angles_deg: Option<Vec<f64>>,
}

impl CantileverStudy {
    /// Our values beside Witteveen's printed ones: (what, printed Hz, ours Hz).
    pub fn calibration(&self) -> Vec<(&'static str, f64, f64)> {
        let v1 = &self.variants[0].band_hz;
        let v3 = self.variants.get(2);
        vec![
            (
                "variant 1, mode 5",
                PRINTED_HZ.variant1_mode5,
                v1.get(4).copied().unwrap_or(f64::NAN),
            ),
            (
                "CB, 7th fixed-interface mode",
                PRINTED_HZ.cb_seventh_fixed_interface,
                self.cb_fixed_interface_hz
                    .get(6)
                    .copied()
                    .unwrap_or(f64::NAN),
            ),
            (
                "variant 3, torsion of the bottom section",
                PRINTED_HZ.variant3_torsion,
                v3.and_then(|v| v.first_torsion)
                    .map_or(f64::NAN, |(_, hz)| hz),
            ),
            (
                "variant 3, new mode (A moves most in x)",
                PRINTED_HZ.variant3_mass_mode,
                v3.and_then(|v| v.mass_mode_hz).unwrap_or(f64::NAN),
            ),
        ]
    }
}

/// Runs the study for `methods` (a subset of [`CANTILEVER_METHODS`]).
pub fn cantilever_study(methods: &[Method]) -> Result<CantileverStudy> {
    let params = OverhangFrameParameters::default();
    let frame = overhang_frame(&params)?;
    let model = &frame.model;
    let io = CantileverIo::of(&frame)?;
    let (bases, deflated) = witteveen_bases(&frame, &io, methods)?;
    let mut variants = Vec::new();
    for v in 1..=3 {
        let (held, masses) = io.variant(v);
        let full =
            RestrainedRitzModel::new(model, identity(model.dof_count()).as_ref(), &held, &masses)?
                .modes()?;
        let full_hz = full.hz();
        let band = modes_in_band(&full_hz, 0.0, BAND_HZ, "full cantilever model")?;
        let mut pairs = Vec::new();
        for basis in &bases {
            let modes =
                RestrainedRitzModel::new(model, basis.psi.as_ref(), &held, &masses)?.modes()?;
            pairs.push((
                basis.method,
                pair_modes(
                    full.vectors.as_ref(),
                    &full_hz,
                    &band,
                    modes.vectors.as_ref(),
                    &modes.hz(),
                ),
            ));
        }
        let mut first_torsion = None;
        for (k, &i) in band.iter().enumerate() {
            if is_bottom_torsion(&frame, &full.vectors, i)? {
                first_torsion = Some((k + 1, full_hz[band[k]]));
                break;
            }
        }
        let mass_mode_hz = band
            .iter()
            .copied()
            .max_by(|&i, &j| {
                full.vectors[(io.a[0], i)]
                    .abs()
                    .total_cmp(&full.vectors[(io.a[0], j)].abs())
            })
            .map(|i| full_hz[i]);
        variants.push(VariantModes {
            variant: v,
            band_hz: band.iter().map(|&i| full_hz[i]).collect(),
            shapes: Mat::from_fn(model.dof_count(), band.len(), |r, c| {
                full.vectors[(r, band[c])]
            }),
            pairs,
            first_torsion,
            mass_mode_hz,
        });
    }
    let statics = load_cases(&io)
        .iter()
        .map(|case| static_case(&frame, &io, &bases, case))
        .collect::<Result<Vec<_>>>()?;
    let cb_fixed_interface_hz = bases
        .iter()
        .find(|b| b.method == Method::CraigBampton)
        .map(|b| b.normal_hz())
        .unwrap_or_default();
    let subspace_angles_deg = match bases
        .iter()
        .find(|b| b.method == Method::BalancedTruncation)
    {
        Some(bt) => {
            let n = model.dof_count();
            let modes3 = Mat::from_fn(n, 3, |r, c| variants[0].shapes[(r, c)]);
            let bt3 = Mat::from_fn(n, 3, |r, c| bt.psi[(r, c)]);
            Some(
                principal_angles(modes3.as_ref(), bt3.as_ref())?
                    .iter()
                    .map(|a| a.to_degrees())
                    .collect(),
            )
        }
        None => None,
    };
    Ok(CantileverStudy {
        params,
        frame,
        io,
        bases,
        deflated,
        variants,
        statics,
        cb_fixed_interface_hz,
        subspace_angles_deg,
    })
}

/// The load cases of §4.3.
fn load_cases(io: &CantileverIo) -> [LoadCase; 3] {
    let a = &io.a;
    [
        LoadCase {
            id: "lc1",
            variant: 1,
            loads: vec![(io.bz, 50.0), (a[2], -15.0)],
            direction: Direction::Z,
            text: "LC 1: 50 N z at B, −15 N z at A; z-deflection of the bottom section",
        },
        LoadCase {
            id: "lc2",
            variant: 1,
            loads: vec![(a[0], 1000.0)],
            direction: Direction::X,
            text: "LC 2: 1000 N x at A; x-deflection of the bottom section",
        },
        LoadCase {
            id: "v2",
            variant: 2,
            loads: vec![(io.bz, 10.0)],
            direction: Direction::Z,
            text: "variant 2: A clamped, 10 N z at B; z-deflection of the bottom section",
        },
    ]
}

/// The full and reduced deflection lines of one load case.
fn static_case(
    frame: &OverhangFrame,
    io: &CantileverIo,
    bases: &[Basis],
    case: &LoadCase,
) -> Result<StaticCase> {
    let model = &frame.model;
    let (held, _) = io.variant(case.variant);
    let mut load = vec![0.0; model.dof_count()];
    for &(d, f) in &case.loads {
        load[d] += f;
    }
    let full = full_static_response(
        model,
        &StaticLoadCase {
            held: held.iter().map(|&d| (d, 0.0)).collect(),
            load: load.clone(),
        },
    )?;
    let line = |u: &[f64]| -> Result<Vec<[f64; 2]>> {
        frame
            .bottom
            .iter()
            .map(|&n| {
                Ok([
                    model.position(model.node_index(n)?)[0],
                    u[model.node_dof(n, NodeDof::Translation(case.direction))?],
                ])
            })
            .collect()
    };
    let mut methods = Vec::new();
    for basis in bases {
        let reduced = RestrainedRitzModel::new(model, basis.psi.as_ref(), &held, &[])?;
        let u = reduced.static_response(&load)?;
        let err = bottom_line_error(model, &frame.bottom, case.direction, &u, &full)?;
        methods.push((basis.method, line(&u)?, err));
    }
    Ok(StaticCase {
        id: case.id,
        text: case.text,
        full_line: line(&full)?,
        methods,
    })
}

/// Whether mode `i` is a torsion of the bottom section: somewhere along it the rotation about
/// x times the half-width (50 mm) exceeds every translation of the section.
fn is_bottom_torsion(frame: &OverhangFrame, shapes: &Mat<f64>, i: usize) -> Result<bool> {
    let (mut twist, mut translation) = (0.0f64, 0.0f64);
    let model = &frame.model;
    for &n in &frame.bottom {
        let rotation_x = model.node_dof(n, NodeDof::Rotation(Direction::X))?;
        twist = twist.max(50.0 * shapes[(rotation_x, i)].abs());
        for d in [Direction::X, Direction::Y, Direction::Z] {
            let dof = model.node_dof(n, NodeDof::Translation(d))?;
            translation = translation.max(shapes[(dof, i)].abs());
        }
    }
    Ok(twist > translation)
}

/// The full model's modes compared: up to this frequency, Hz. Witteveen's range of interest is
/// 200 Hz; the band reaches past it to his mode 7 ("beyond the frequency limit of 200 Hz").
pub const BAND_HZ: f64 = 300.0;

/// His a-priori validity limit of the CB basis, Hz.
pub const INTEREST_HZ: f64 = 200.0;

/// Variant 3's point mass on A, t (250 kg).
pub const POINT_MASS_T: f64 = 0.25;

/// Stiffness-proportional damping for the BT vectors only, s.
pub const BT_ALPHA: f64 = 1e-4;

/// The structure's input/output DOF and supports.
#[derive(Debug, Clone)]
pub struct CantileverIo {
    /// The clamp's six DOF.
    pub clamp: Vec<usize>,
    /// A's six DOF (x, y, z, θx, θy, θz).
    pub a: Vec<usize>,
    /// B's z DOF.
    pub bz: usize,
}

impl CantileverIo {
    /// The I/O DOF of the structure.
    pub fn of(frame: &OverhangFrame) -> Result<Self> {
        let m = &frame.model;
        Ok(Self {
            clamp: m.dofs_of_nodes(&[frame.clamp])?,
            a: m.dofs_of_nodes(&[frame.a])?,
            bz: m.node_dof(frame.b, NodeDof::Translation(Direction::Z))?,
        })
    }

    /// The seven I/O DOF: A's six, then B's z.
    pub fn io(&self) -> Vec<usize> {
        let mut io = self.a.clone();
        io.push(self.bz);
        io
    }

    /// Held DOF and point masses of a variant (1, 2 or 3).
    pub fn variant(&self, v: usize) -> (Vec<usize>, Vec<(usize, f64)>) {
        let mut held = self.clamp.clone();
        match v {
            2 => {
                held.extend(&self.a);
                (held, vec![])
            }
            3 => {
                held.extend(&self.a[1..]);
                (held, vec![(self.a[0], POINT_MASS_T)])
            }
            _ => (held, vec![]),
        }
    }
}

/// The three bases of §4.3, each of 14 vectors, on variant 1. Moment matching's deflated
/// columns are returned for the scene text (none on this structure).
pub fn witteveen_bases(
    frame: &OverhangFrame,
    io: &CantileverIo,
    methods: &[Method],
) -> Result<(Vec<Basis>, usize)> {
    let model = &frame.model;
    let mut bases = Vec::new();
    let mut deflated = 0;
    for &m in methods {
        let basis = match m {
            Method::CraigBampton => {
                let partition = Partition::from_dofs(model, &io.io(), &io.clamp)?;
                let mut problem = InteriorProblem::on(model, partition, SolverPath::Auto)?;
                reduce_interior(
                    &mut problem,
                    &ReductionRequest::of(Method::CraigBampton).modes(ModeSelection::Count(7)),
                )?
            }
            Method::MomentMatching => {
                let mm = moment_matching(
                    model,
                    &MomentMatchingParameters {
                        inputs: io.io(),
                        held: io.clamp.clone(),
                        blocks: 2,
                        ..Default::default()
                    },
                )?;
                deflated += mm.deflated.len();
                mm.basis
            }
            _ => balanced_basis(
                model,
                &BalancedBasisParameters {
                    inputs: io.io(),
                    held: io.clamp.clone(),
                    vectors: 14,
                    alpha: BT_ALPHA,
                },
            )?,
        };
        bases.push(basis);
    }
    Ok((bases, deflated))
}

/// A static load case of §4.3 and the deflection direction it is judged by.
struct LoadCase {
    id: &'static str,
    variant: usize,
    loads: Vec<(usize, f64)>,
    direction: Direction,
    text: &'static str,
}

/// max over the bottom section of |ũ − u| in `direction` over max |u|.
pub fn bottom_line_error(
    model: &FeModel,
    bottom: &[usize],
    direction: Direction,
    u: &[f64],
    reference: &[f64],
) -> Result<f64> {
    let line = |x: &[f64]| -> Result<Vec<f64>> {
        bottom
            .iter()
            .map(|&n| Ok(x[model.node_dof(n, NodeDof::Translation(direction))?]))
            .collect()
    };
    let (a, b) = (line(u)?, line(reference)?);
    let peak = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    Ok(if peak > 0.0 { diff / peak } else { diff })
}
