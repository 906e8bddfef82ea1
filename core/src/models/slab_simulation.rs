//! The slab simulations of §7.2: the App. B slab (or a refinement of it) on a floating frame,
//! reduced by one method, held at six coordinates under gravity (Simulation 1), pinned with
//! node 30 on an orbit (Simulation 2) or driven at its corners by recorded accelerations
//! (Simulation 3, §7.2.4).

use nalgebra::{Matrix3, Vector3};

use crate::{
    Progress, Result,
    analysis::node_deflection_history,
    dynamics::{
        AxisType, Body, Constraint, FlexibleBody, IntegratorParameters, Motion, Simulation, System,
        simulate,
    },
    fem::{FeModel, NodeIndex, SlabParameters, slab},
    reduction::{Method, ModeSelection, NodalFixedAxes, ReductionRequest, reduce},
};

/// Simulated interval of Simulations 1 and 2 unless asked otherwise, s.
pub const SIM1_END: f64 = 2.0;
/// Simulated interval of Simulation 2 unless asked otherwise, s.
pub const SIM2_END: f64 = 2.0;
/// Simulated interval of Simulation 3 unless asked otherwise, s.
pub const SIM3_END: f64 = 1.0;

impl Scenario {
    /// The scenario's simulated interval unless asked otherwise, s.
    pub fn end_time(&self) -> f64 {
        match self {
            Scenario::HeldAtSix => SIM1_END,
            Scenario::Orbit => SIM2_END,
            Scenario::Driven(_) => SIM3_END,
        }
    }
}

/// The slab scenarios of §7.2.
#[derive(Debug, Clone, PartialEq)]
pub enum Scenario {
    /// Simulation 1: d16 (x, y, z), d18 x, d28 z, d30 z held; gravity.
    HeldAtSix,
    /// Simulation 2: d16, d18 fixed; node 30 on the orbit of Eq. (7.10).
    Orbit,
    /// Simulation 3: nodes 16, 18, 28, 30 driven by recorded acceleration tables, starting
    /// inclined and at rest.
    Driven(DrivenTables),
}

/// The recorded accelerations of Simulation 3 (§7.2.4).
#[derive(Debug, Clone, PartialEq)]
pub struct DrivenTables {
    /// Sampling interval, s.
    pub dt: f64,
    /// For nodes 16, 18, 28, 30 and axes x, y, z: accelerations, m/s².
    pub values: Vec<[Vec<f64>; 3]>,
    /// Initial orientation of the slab.
    pub rotation: Matrix3<f64>,
}

/// Nodes driven in Simulation 3.
pub const DRIVEN_NODES: [usize; 4] = [16, 18, 28, 30];

/// Recording interval of the tables, s (§7.2.4: 5 ms).
const TABLE_DT: f64 = 5e-3;

/// The slab's initial orientation in Simulation 3: inclined 45° towards −y about the edge
/// through nodes 18 and 30 (a rotation about x).
pub fn sim3_rotation() -> Matrix3<f64> {
    *nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), -std::f64::consts::FRAC_PI_4).matrix()
}

/// Fig. 7-12(b): the full slab hung from a 2 m link at node 18 and a 3 m link at node 30
/// (parallel to x, far ends fixed), inclined 45°, released from rest with constant forces at
/// nodes 16 and 28; returns the accelerations of nodes 16, 18, 28, 30 every 5 ms.
pub fn record_driving_tables(
    axes: AxisType,
    end: f64,
    progress: &Progress,
) -> Result<DrivenTables> {
    use crate::dynamics::{Attachment, RigidBody};
    let model = slab(&SlabParameters::default());
    let body = slab_body(&model, Method::NoReduction, axes, &BOUNDARY, 0)?;
    let rot = sim3_rotation();
    let pivot = Vector3::new(0.0, 2.0, 0.0);
    let placed = |p: Vector3<f64>| pivot + rot * (p - pivot);
    let index = |n: usize| model.node_index(n);
    let node = |n: usize| -> Result<Vector3<f64>> {
        let p = model.position(index(n)?);
        Ok(placed(Vector3::new(p[0], p[1], p[2])))
    };
    let origin = placed(body.origin);
    let mut constraints: Vec<Constraint> = Vec::new();
    let (n18, n30) = (node(18)?, node(30)?);
    let far18 = n18 - Vector3::new(2.0, 0.0, 0.0);
    let far30 = n30 + Vector3::new(3.0, 0.0, 0.0);
    let short = RigidBody::rod("link18", 2.0, 1.0);
    let long = RigidBody::rod("link30", 3.0, 1.0);
    constraints.push(Constraint::Spherical(
        Attachment::Ground(far18),
        Attachment::Point {
            body: 1,
            local: Vector3::new(-1.0, 0.0, 0.0),
        },
    ));
    constraints.push(Constraint::Spherical(
        Attachment::Point {
            body: 1,
            local: Vector3::new(1.0, 0.0, 0.0),
        },
        Attachment::Node {
            body: 0,
            node: index(18)?,
        },
    ));
    constraints.push(Constraint::Spherical(
        Attachment::Node {
            body: 0,
            node: index(30)?,
        },
        Attachment::Point {
            body: 2,
            local: Vector3::new(-1.5, 0.0, 0.0),
        },
    ));
    constraints.push(Constraint::Spherical(
        Attachment::Point {
            body: 2,
            local: Vector3::new(1.5, 0.0, 0.0),
        },
        Attachment::Ground(far30),
    ));
    let mut system = System::new(
        vec![
            Body::Flexible(Box::new(body)),
            Body::Rigid(short),
            Body::Rigid(long),
        ],
        constraints,
    );
    system
        .nodal_forces
        .push((0, index(16)?, Vector3::new(-40.0, 160.0, -20.0)));
    system
        .nodal_forces
        .push((0, index(28)?, Vector3::new(60.0, -240.0, -30.0)));
    let state = system.state_at(&[
        (origin, rot),
        ((far18 + n18) / 2.0, Matrix3::identity()),
        ((n30 + far30) / 2.0, Matrix3::identity()),
    ]);
    let params = IntegratorParameters {
        end_time: end,
        output_interval: TABLE_DT,
        ..Default::default()
    };
    progress.phase("two-link pre-simulation (§7.2.4)")?;
    let sim = simulate(&system, &state, &params, progress)?;
    let mut values: Vec<[Vec<f64>; 3]> = vec![[vec![], vec![], vec![]]; 4];
    for s in &sim.samples {
        let vdot = system.accelerations(s.t, &s.state)?;
        for (i, &n) in DRIVEN_NODES.iter().enumerate() {
            let a = system.node_acceleration(0, index(n)?, &s.state, &vdot);
            for ax in 0..3 {
                values[i][ax].push(a[ax]);
            }
        }
    }
    Ok(DrivenTables {
        dt: TABLE_DT,
        values,
        rotation: rot,
    })
}

/// Boundary nodes of §7.2.
pub const BOUNDARY: [usize; 4] = [16, 18, 28, 30];

const EXTRA_GUYAN_MASTERS: [usize; 2] = [5, 11];

/// Node whose local deflections are compared (§7.2).
pub const PROBE_NODE: usize = 8;

const ORBIT_R: f64 = 4.0;

const ORBIT_T: f64 = 1.0;

/// The deformable slab for one method and axis type: the basis (nodal-fixed columns removed
/// when the frame is nodal-fixed) and the frame origin (node 16, or the mass centre). On a
/// refined `model`, Guyan's extra masters (App. B nodes 5 and 11) and the nodes of nodal-fixed
/// axes (given in App. B numbers) are taken at their App. B positions ([`slab_node`]);
/// `boundary` is in the model's own numbers.
pub fn slab_body(
    model: &FeModel,
    method: Method,
    axes: AxisType,
    boundary: &[usize],
    modes: usize,
) -> Result<FlexibleBody> {
    let nodes = reduction_nodes(model, method, boundary);
    let axes = match axes {
        AxisType::NodalFixed(nf) => AxisType::NodalFixed(NodalFixedAxes {
            origin: slab_node(model, nf.origin),
            axis_node: slab_node(model, nf.axis_node),
            plane_node: slab_node(model, nf.plane_node),
            ..nf
        }),
        other => other,
    };
    let basis = reduce(
        model,
        &ReductionRequest {
            method,
            boundary_nodes: nodes,
            modes: ModeSelection::Count(modes),
            ..Default::default()
        },
    )?;
    FlexibleBody::new(model.clone(), basis, axes)
}

/// The boundary (masters) `method` reduces the slab on: `boundary`, and for Guyan reduction
/// also App. B's nodes 5 and 11 (§7.2: as many static modes as the others have columns).
pub fn reduction_nodes(model: &FeModel, method: Method, boundary: &[usize]) -> Vec<usize> {
    let mut nodes = boundary.to_vec();
    if method == Method::Guyan {
        nodes.extend(
            EXTRA_GUYAN_MASTERS
                .iter()
                .map(|&n| slab_node(model, n))
                .filter(|n| !boundary.contains(n)),
        );
    }
    nodes
}

/// The six coordinates Simulation 1 holds (§7.2.2): d16 (x, y, z), d18 x, d28 z, d30 z, as
/// 0-based DOF of `model` (a statically determinate support).
pub fn held_at_six(model: &FeModel) -> Result<Vec<usize>> {
    let n = |app_b: usize| slab_node(model, app_b);
    let mut dofs = model.dofs_of_nodes(&[n(16)])?;
    dofs.push(model.dofs_of_nodes(&[n(18)])?[0]);
    dofs.push(model.dofs_of_nodes(&[n(28)])?[2]);
    dofs.push(model.dofs_of_nodes(&[n(30)])?[2]);
    Ok(dofs)
}

/// The 1-based node of `model` (the App. B slab or a refinement of it) at the position of App.
/// B's node `app_b_node` (Table B-1 numbering): the identity on App. B itself; on a refined
/// mesh the corners 16, 18, 28, 30, node 8 (the top-face centre) and nodes 5 and 11 keep
/// their places, exactly when the brick counts are multiples of 4, 2, 1.
pub fn slab_node(model: &FeModel, app_b_node: usize) -> usize {
    static APP_B: std::sync::OnceLock<FeModel> = std::sync::OnceLock::new();
    let app_b = APP_B.get_or_init(|| slab(&SlabParameters::default()));
    if model.node_count() == app_b.node_count() {
        return app_b_node;
    }
    let Some(target) = NodeIndex::of_number(app_b_node)
        .filter(|i| i.get() < app_b.node_count())
        .map(|i| app_b.position(i))
    else {
        return app_b_node;
    };
    let distance = |p: &[f64; 3]| (0..3).map(|d| (p[d] - target[d]).powi(2)).sum::<f64>();
    NodeIndex(
        (0..model.node_count())
            .min_by(|&a, &b| distance(&model.nodes[a]).total_cmp(&distance(&model.nodes[b])))
            .unwrap_or(0),
    )
    .number()
}

/// The scene's default boundary on `model`: App. B's nodes 16, 18, 28, 30 where they are.
pub fn default_boundary(model: &FeModel) -> Vec<usize> {
    BOUNDARY.iter().map(|&n| slab_node(model, n)).collect()
}

/// Node `node` (1-based) of the slab (body 0) held at its undeformed coordinate `axis`.
pub fn fixed(model: &FeModel, node: usize, axis: usize) -> Result<Constraint> {
    let node = model.node_index(node)?;
    Ok(Constraint::PrescribedNode {
        body: 0,
        node,
        axis,
        motion: Motion::Fixed,
        x0: model.position(node)[axis],
        v0: 0.0,
    })
}

/// Builds the system and its initial state for a scenario.
pub fn slab_system(
    scenario: &Scenario,
    body: FlexibleBody,
) -> Result<(System, crate::dynamics::State)> {
    let model = body.model.clone();
    let n = |app_b: usize| slab_node(&model, app_b);
    let index = |app_b: usize| model.node_index(slab_node(&model, app_b));
    let mut origin = body.origin;
    let mut rotation = Matrix3::identity();
    let mut constraints: Vec<Constraint> = Vec::new();
    let omega = 2.0 * std::f64::consts::PI / ORBIT_T;
    match scenario {
        Scenario::HeldAtSix => {
            for a in 0..3 {
                constraints.push(fixed(&model, n(16), a)?);
            }
            constraints.push(fixed(&model, n(18), 0)?);
            constraints.push(fixed(&model, n(28), 2)?);
            constraints.push(fixed(&model, n(30), 2)?);
        }
        Scenario::Orbit => {
            for a in 0..3 {
                constraints.push(fixed(&model, n(16), a)?);
                constraints.push(fixed(&model, n(18), a)?);
            }
            let a = ORBIT_R * omega * omega;
            let node30 = index(30)?;
            let p30 = model.position(node30);
            constraints.push(Constraint::PrescribedNode {
                body: 0,
                node: node30,
                axis: 0,
                motion: Motion::Harmonic {
                    a,
                    omega,
                    c2: 0.25,
                    sine: false,
                },
                x0: p30[0],
                v0: 0.0,
            });
            constraints.push(fixed(&model, n(30), 1)?);
            // z velocity of the closed orbit, R Ω (1 + 1/16); see the scene text.
            constraints.push(Constraint::PrescribedNode {
                body: 0,
                node: node30,
                axis: 2,
                motion: Motion::Harmonic {
                    a,
                    omega,
                    c2: 0.125,
                    sine: true,
                },
                x0: p30[2],
                v0: ORBIT_R * omega * (1.0 + 1.0 / 16.0),
            });
        }
        Scenario::Driven(tables) => {
            rotation = tables.rotation;
            let pivot = Vector3::new(0.0, 2.0, 0.0);
            origin = pivot + rotation * (origin - pivot);
            for (i, &app_b) in DRIVEN_NODES.iter().enumerate() {
                let node = index(app_b)?;
                let p = model.position(node);
                let x = pivot + rotation * (Vector3::new(p[0], p[1], p[2]) - pivot);
                for axis in 0..3 {
                    constraints.push(Constraint::PrescribedNode {
                        body: 0,
                        node,
                        axis,
                        motion: Motion::table(tables.dt, tables.values[i][axis].clone()),
                        x0: x[axis],
                        v0: 0.0,
                    });
                }
            }
        }
    }
    let system = System::new(vec![Body::Flexible(Box::new(body))], constraints);
    let mut state = system.state_at(&[(origin, rotation)]);
    if *scenario == Scenario::Orbit {
        // Initial angular velocity −Ω about y, about the line through nodes 16 and 18.
        let w = Vector3::new(0.0, -omega, 0.0);
        let rd = w.cross(&origin);
        for i in 0..3 {
            state.v[i] = rd[i];
            state.v[3 + i] = w[i];
        }
    }
    Ok((system, state))
}

/// Node `node`'s (1-based) local deflections (ξ, η, ζ) of the slab at every sample (none
/// for node 0).
pub fn probe_history(system: &System, sim: &Simulation, node: usize) -> [Vec<f64>; 3] {
    NodeIndex::of_number(node).map_or_else(Default::default, |node| {
        node_deflection_history(system, sim, 0, node)
    })
}
