//! §5.3.3: the plank hung under four rigid links by spherical joints, falling until the chains
//! straighten, on nodal-fixed or mean axes; its mirror symmetry about x = 2 m is the measure.

use nalgebra::{Matrix3, Rotation3, Vector3};

use crate::{
    Result,
    analysis::mirror_defect_history,
    dynamics::{
        Attachment, AxisType, Body, Constraint, FlexibleBody, RigidBody, Simulation, State, System,
    },
    fem::{Direction, FeModel, NodeIndex},
    reduction::{
        Method, ModeSelection, NodalFixedAxes, ReductionRequest, TableConfiguration, reduce,
    },
};

/// The §5.3.3 set-up as stored in `assets/thesis/plank-5-3-3.toml`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlankSetup {
    /// Length of each rigid link, m.
    pub link_length: f64,
    /// Mass of each rigid link, kg.
    pub link_mass: f64,
    /// The loaded node, 1-based.
    pub force_node: usize,
    /// The downward force at it, N.
    pub force: f64,
    /// The top front corners the chains hold, 1-based.
    pub hanging_nodes: [usize; 2],
    /// How far the plank falls before the chains straighten, m (≈ 0.5 s of free fall).
    pub drop: f64,
}

/// The set-up, read once from the embedded asset.
pub fn plank_setup() -> &'static PlankSetup {
    static SETUP: std::sync::OnceLock<PlankSetup> = std::sync::OnceLock::new();
    SETUP.get_or_init(|| crate::assets::parameters("thesis/plank-5-3-3.toml"))
}

/// The plane of mirror symmetry, x = 2 m.
pub const MID_X: f64 = 2.0;

/// The §5.3.3 nodal-fixed frame: origin node 8, ξ through node 14, η-plane through node 23.
pub fn plank_nodal_fixed() -> NodalFixedAxes {
    NodalFixedAxes {
        origin: 8,
        axis_node: 14,
        plane_node: 23,
        configuration: TableConfiguration::new(Direction::X, Direction::Y),
    }
}

/// One variant of the study: method and axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variant {
    /// Reduction method.
    pub method: Method,
    /// Axis type.
    pub axes: AxisType,
}

/// Boundary nodes for reduced plank bases: the two joints and the loaded node (two nodes alone
/// leave the rotation about the line through them free).
pub const PLANK_BOUNDARY: [usize; 3] = [3, 15, 22];

/// The plank body for a variant.
pub fn plank_body(model: &FeModel, v: Variant, modes: usize) -> Result<FlexibleBody> {
    let basis = reduce(
        model,
        &ReductionRequest {
            method: v.method,
            boundary_nodes: PLANK_BOUNDARY.to_vec(),
            modes: ModeSelection::Count(modes),
            ..Default::default()
        },
    )?;
    FlexibleBody::new(model.clone(), basis, v.axes)
}

/// The plank, four links and six spherical joints, at rest with each chain folded
/// symmetrically so the plank falls [`PlankSetup::drop`] before the chains straighten.
pub fn plank_system(body: FlexibleBody) -> Result<(System, State)> {
    let model = body.model.clone();
    let origin = body.origin;
    let top = |node: usize| -> Result<Vector3<f64>> {
        let p = model.position(model.node_index(node)?);
        Ok(Vector3::new(p[0], p[1], p[2]))
    };
    let setup = plank_setup();
    let [left, right] = setup.hanging_nodes;
    let (c, f) = (top(left)?, top(right)?);
    // Anchors above the top corners, the chain's elbow pushed outward (mirror images).
    let length = setup.link_length;
    let height = 2.0 * length - setup.drop;
    let half = height / 2.0;
    let out = (length * length - half * half).sqrt();
    let a = c + Vector3::new(0.0, 0.0, height);
    let b = c + Vector3::new(-out, 0.0, half);
    let d = f + Vector3::new(0.0, 0.0, height);
    let e = f + Vector3::new(out, 0.0, half);
    let mut bodies = vec![Body::Flexible(Box::new(body))];
    let mut placements = vec![(origin, Matrix3::identity())];
    let mut joints = Vec::new();
    let ends = Vector3::new(length / 2.0, 0.0, 0.0);
    for (i, (p0, p1)) in [(a, b), (b, c), (d, e), (e, f)].into_iter().enumerate() {
        let dir = (p1 - p0).normalize();
        let rot = Rotation3::rotation_between(&Vector3::x(), &dir).unwrap_or_else(|| {
            Rotation3::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI)
        });
        bodies.push(Body::Rigid(RigidBody::rod(
            &format!("link{}", i + 1),
            length,
            setup.link_mass,
        )));
        placements.push(((p0 + p1) / 2.0, *rot.matrix()));
    }
    let link = |k: usize, end: f64| Attachment::Point {
        body: k,
        local: ends * end,
    };
    joints.push(Constraint::Spherical(Attachment::Ground(a), link(1, -1.0)));
    joints.push(Constraint::Spherical(link(1, 1.0), link(2, -1.0)));
    joints.push(Constraint::Spherical(
        link(2, 1.0),
        Attachment::Node {
            body: 0,
            node: model.node_index(left)?,
        },
    ));
    joints.push(Constraint::Spherical(Attachment::Ground(d), link(3, -1.0)));
    joints.push(Constraint::Spherical(link(3, 1.0), link(4, -1.0)));
    joints.push(Constraint::Spherical(
        link(4, 1.0),
        Attachment::Node {
            body: 0,
            node: model.node_index(right)?,
        },
    ));
    let mut system = System::new(bodies, joints);
    system.nodal_forces.push((
        0,
        model.node_index(setup.force_node)?,
        Vector3::new(0.0, 0.0, -setup.force),
    ));
    let state = system.state_at(&placements);
    Ok((system, state))
}

/// x of nodes 3 and 15 and the symmetry defect $|x_3 + x_{15} - 2x_{mid}|$ per sample.
pub fn symmetry_history(system: &System, sim: &Simulation) -> [Vec<f64>; 3] {
    let [left, right] = plank_setup().hanging_nodes.map(NodeIndex::of_number);
    match (left, right) {
        (Some(a), Some(b)) => mirror_defect_history(system, sim, 0, (a, b), MID_X),
        _ => Default::default(),
    }
}
