//! A dual-spin assembly in the spirit of Spanos–Tsuha's Galileo example (their §4, whose
//! model and figures are not in the paper): a flexible "rotor" of radial booms on a hub, a
//! flexible "stator" column grounded at its base carrying the rotor on top and a rigid
//! "platform" on a side arm. The booms give many low-frequency modes, most of which put no
//! net force or moment on the hub and so are not seen from the actuator or the sensors.

use super::{FeModel, FrameSection, NodeIndex, frame_of_sections};
use crate::error::MeshError;
use crate::{Result, linalg::MassMatrix};

/// Dimensions (m), sections and masses of the assembly, SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct DualSpinParameters {
    /// Number of booms, evenly spaced around the hub in the x-y plane.
    pub booms: usize,
    /// Boom length, m.
    pub boom_length: f64,
    /// Elements per boom.
    pub boom_elements: usize,
    /// Boom section: out-of-plane (z) and in-plane extents, m.
    pub boom_section: [f64; 2],
    /// Column height from the ground to the hub, m.
    pub column_height: f64,
    /// Elements of the column.
    pub column_elements: usize,
    /// Column section (square side), m.
    pub column_side: f64,
    /// Where the platform arm leaves the column, as a fraction of its height from the ground.
    pub arm_root_fraction: f64,
    /// Arm length along x, m.
    pub arm_length: f64,
    /// Elements of the arm.
    pub arm_elements: usize,
    /// Arm section (z and y extents), m.
    pub arm_section: [f64; 2],
    /// Platform mass, kg, and its moments of inertia about its attachment node, kg m².
    pub platform_mass: f64,
    /// Platform inertia about x, y, z through its node, kg m².
    pub platform_inertia: [f64; 3],
    /// The articulation: the rotor turned about z relative to the stator, rad (a frozen
    /// configuration of the hinge).
    pub rotor_angle: f64,
}

impl Default for DualSpinParameters {
    fn default() -> Self {
        Self {
            booms: 8,
            boom_length: 3.0,
            boom_elements: 8,
            boom_section: [0.010, 0.030],
            column_height: 2.0,
            column_elements: 8,
            column_side: 0.08,
            arm_root_fraction: 0.5,
            arm_length: 1.0,
            arm_elements: 4,
            arm_section: [0.06, 0.04],
            platform_mass: 40.0,
            platform_inertia: [3.0, 3.0, 3.0],
            rotor_angle: 0.0,
        }
    }
}

/// The components and how their nodes map to the assembly (0-based nodes throughout).
#[derive(Debug, Clone)]
pub struct DualSpin {
    /// The rotor: hub (local node 0) and booms; free-free.
    pub rotor: FeModel,
    /// Assembly node of each rotor node.
    pub rotor_nodes: Vec<usize>,
    /// The stator: column from the ground (local node 0) to the hub, and the arm.
    pub stator: FeModel,
    /// Assembly node of each stator node.
    pub stator_nodes: Vec<usize>,
    /// The whole assembly as one body with the platform's mass on its node (the reference
    /// built without component synthesis), ground node not yet held.
    pub assembly: FeModel,
    /// Assembly node of the hub (the rotor–stator interface, where the motor acts).
    pub hub: usize,
    /// Assembly node of the platform (where the rigid platform is attached and sensed).
    pub platform: usize,
    /// Assembly node of the ground (the column's base, held).
    pub ground: usize,
    /// Local stator node of the hub.
    pub stator_hub: usize,
    /// Local stator node of the platform.
    pub stator_platform: usize,
    /// The platform's 6 × 6 mass about its node (diagonal).
    pub platform_mass: [f64; 6],
}

/// A frame element of the rotor: its node pair, local y direction and section.
type RotorElement = ([usize; 2], [f64; 3], usize);

/// The rotor's nodes (the hub at the origin, then each boom's) and its elements (node pair,
/// local y direction, section), every boom in the x-y plane.
fn rotor_geometry(p: &DualSpinParameters) -> (Vec<[f64; 3]>, Vec<RotorElement>) {
    let mut rotor_xyz = vec![[0.0, 0.0, 0.0]];
    let mut rotor_el = Vec::new();
    for b in 0..p.booms {
        let angle = p.rotor_angle + 2.0 * std::f64::consts::PI * b as f64 / p.booms as f64;
        let (c, s) = (angle.cos(), angle.sin());
        let mut prev = 0;
        for k in 1..=p.boom_elements {
            let r = p.boom_length * k as f64 / p.boom_elements as f64;
            rotor_xyz.push([r * c, r * s, 0.0]);
            let this = rotor_xyz.len() - 1;
            rotor_el.push(([prev, this], [0.0, 0.0, 1.0], 0));
            prev = this;
        }
    }
    (rotor_xyz, rotor_el)
}

/// Builds the assembly: 3-D Euler–Bernoulli frame elements, lumped mass, steel
/// (E = 210 GPa, G = 80 GPa, ρ = 7800 kg/m³).
pub fn dual_spin(p: &DualSpinParameters) -> Result<DualSpin> {
    let (e, g, rho) = (210e9, 80e9, 7800.0);
    if p.booms < 2 || p.boom_elements == 0 || p.column_elements < 2 || p.arm_elements == 0 {
        return Err(MeshError::DualSpinTooSmall.into());
    }
    // Rotor: hub at the origin, booms in the x-y plane; local y of a boom is global z, so
    // `boom_section[0]` is its out-of-plane (flap) thickness.
    let (rotor_xyz, rotor_el) = rotor_geometry(p);
    let boom = FrameSection::rectangle(p.boom_section[0], p.boom_section[1], e, g, rho);
    let rotor = frame_of_sections(
        "rotor",
        rotor_xyz.clone(),
        &rotor_el,
        std::slice::from_ref(&boom),
    )?;
    // Stator: column from the ground up to the hub, then the arm along x.
    let h = p.column_height;
    let mut stator_xyz: Vec<[f64; 3]> = (0..=p.column_elements)
        .map(|k| [0.0, 0.0, -h + h * k as f64 / p.column_elements as f64])
        .collect();
    let mut stator_el: Vec<([usize; 2], [f64; 3], usize)> = (0..p.column_elements)
        .map(|k| ([k, k + 1], [1.0, 0.0, 0.0], 0))
        .collect();
    let stator_hub = p.column_elements;
    let root = ((p.arm_root_fraction * p.column_elements as f64).round() as usize)
        .clamp(1, p.column_elements - 1);
    let z_root = stator_xyz[root][2];
    let mut prev = root;
    for k in 1..=p.arm_elements {
        stator_xyz.push([p.arm_length * k as f64 / p.arm_elements as f64, 0.0, z_root]);
        let this = stator_xyz.len() - 1;
        stator_el.push(([prev, this], [0.0, 0.0, 1.0], 1));
        prev = this;
    }
    let stator_platform = stator_xyz.len() - 1;
    let column = FrameSection::rectangle(p.column_side, p.column_side, e, g, rho);
    let arm = FrameSection::rectangle(p.arm_section[0], p.arm_section[1], e, g, rho);
    let stator = frame_of_sections(
        "stator",
        stator_xyz.clone(),
        &stator_el,
        &[column.clone(), arm.clone()],
    )?;
    // Assembly numbering: the rotor's nodes first (hub = 0), then the stator's except its
    // top, which is the hub.
    let rotor_nodes: Vec<usize> = (0..rotor_xyz.len()).collect();
    let mut stator_nodes = Vec::with_capacity(stator_xyz.len());
    let mut next = rotor_xyz.len();
    for k in 0..stator_xyz.len() {
        if k == stator_hub {
            stator_nodes.push(0);
        } else {
            stator_nodes.push(next);
            next += 1;
        }
    }
    let mut xyz = rotor_xyz;
    for (k, &global) in stator_nodes.iter().enumerate() {
        if global >= xyz.len() {
            xyz.push(stator_xyz[k]);
        }
    }
    let mut elements = rotor_el.clone();
    for &([a, b], up, s) in &stator_el {
        elements.push(([stator_nodes[a], stator_nodes[b]], up, s + 1));
    }
    let mut assembly =
        frame_of_sections("dual-spin assembly", xyz, &elements, &[boom, column, arm])?;
    let [ix, iy, iz] = p.platform_inertia;
    let m = p.platform_mass;
    let platform_mass = [m, m, m, ix, iy, iz];
    let platform = stator_nodes[stator_platform];
    let ground = stator_nodes[0];
    add_lumped(&mut assembly, platform, &platform_mass)?;
    Ok(DualSpin {
        rotor,
        rotor_nodes,
        stator,
        stator_nodes,
        assembly,
        hub: 0,
        platform,
        ground,
        stator_hub,
        stator_platform,
        platform_mass,
    })
}

/// Adds a diagonal 6 × 6 mass to a node of a body with a lumped mass matrix.
pub fn add_lumped(model: &mut FeModel, node: usize, mass: &[f64; 6]) -> Result<()> {
    let per = model.dofs.per_node();
    match &mut model.m {
        MassMatrix::Lumped(v) if per == 6 && node < model.nodes.len() => {
            for (d, m) in mass.iter().enumerate() {
                v[node * per + d] += m;
            }
            Ok(())
        }
        _ => Err(MeshError::NotALumpedFrameNode {
            body: (&model.name).into(),
            node: NodeIndex(node).number(),
            nodes: model.nodes.len(),
        }
        .into()),
    }
}
