//! The floating frame built in one place: inertia invariants against node-by-node sums, axis
//! conditions derived from the body's axis type, nodal-fixed columns removed by the body's
//! constructor.

use flexmodes::{
    dynamics::{AxisType, Body, FlexibleBody, InertiaInvariants, System, skew},
    fem::{SlabParameters, slab},
    reduction::{Method, ModeSelection, NodalFixedAxes, ReductionRequest, reduce},
};
use nalgebra::{DVector, Matrix3, Matrix3xX, Vector3};

use crate::common::Rng;

fn random_body(
    rng: &mut Rng,
    nodes: usize,
    k: usize,
) -> (Vec<f64>, Vec<Vector3<f64>>, Vec<Matrix3xX<f64>>) {
    let masses = (0..nodes).map(|_| 1.0 + rng.unit().abs()).collect();
    let s = (0..nodes)
        .map(|_| Vector3::new(rng.unit(), rng.unit(), rng.unit()) * 2.0)
        .collect();
    let psi = (0..nodes)
        .map(|_| Matrix3xX::from_fn(k, |_, _| 0.3 * rng.unit()))
        .collect();
    (masses, s, psi)
}

fn random_vector(rng: &mut Rng, k: usize) -> DVector<f64> {
    DVector::from_fn(k, |_, _| rng.unit())
}

#[test]
fn inertia_invariants_equal_node_by_node_sums() {
    let mut rng = Rng::new(17);
    for &(nodes, k) in &[(1, 0), (3, 1), (8, 5), (45, 12), (20, 30)] {
        let (m, s, psi) = random_body(&mut rng, nodes, k);
        let inv = InertiaInvariants::new(&m, &s, &psi);
        assert_eq!(inv.modes(), k);
        let (z, zd) = (random_vector(&mut rng, k), random_vector(&mut rng, k));
        let w = Vector3::new(rng.unit(), rng.unit(), rng.unit()) * 3.0;
        // The sums the floating-frame equations need, node by node (Eq. 3.14, 5.12).
        let mut first = Vector3::zeros();
        let mut j_bar = Matrix3::zeros();
        let mut wz = Matrix3xX::zeros(k);
        let (mut ar, mut aw, mut az) = (Vector3::zeros(), Vector3::zeros(), DVector::zeros(k));
        let mut uu = Matrix3::zeros();
        let mut p_sum = Matrix3xX::zeros(k);
        for j in 0..nodes {
            let b = s[j] + &psi[j] * &z;
            let u = &psi[j] * &zd;
            let bt = skew(&b);
            first += b * m[j];
            j_bar += bt.transpose() * bt * m[j];
            wz += bt * &psi[j] * m[j];
            p_sum += &psi[j] * m[j];
            let alpha = w.cross(&w.cross(&b)) + 2.0 * w.cross(&u);
            ar += alpha * m[j];
            aw += b.cross(&alpha) * m[j];
            az += psi[j].transpose() * alpha * m[j];
            uu += u * u.transpose() * m[j];
        }
        let scale = 1.0 + nodes as f64;
        let close = |a: f64, what: &str| {
            assert!(a <= 1e-12 * scale * scale, "{what} ({nodes}, {k}): {a:e}")
        };
        let h = inv.h(&z);
        assert_eq!(h.len(), k);
        close((inv.first_moment(&z) - first).amax(), "first moment");
        close((inv.inertia(&z) - j_bar).amax(), "inertia");
        close(
            (inv.rotation_coupling(&h) - &wz).amax(),
            "rotation coupling",
        );
        close((&inv.p_sum - &p_sum).amax(), "p_sum");
        close((inv.modal_outer(&zd, &zd) - uu).amax(), "modal outer");
        let mut gz = DVector::from_element(az.len(), f64::NAN);
        let (gr, gw) = inv.velocity_forces(
            &w,
            (&z, &zd),
            &h,
            &inv.inertia(&z),
            &mut gz,
            &mut Vec::new(),
        );
        close((gr - ar).amax(), "translational velocity forces");
        close((gw - aw).amax(), "rotational velocity forces");
        close((gz - &az).amax(), "modal velocity forces");
        // Not trivially zero: the sums are of order one.
        assert!(j_bar.amax() > 0.1 && (k == 0 || az.amax() > 1e-3));
    }
}

fn slab_body(axes: AxisType) -> FlexibleBody {
    let model = slab(&SlabParameters::default());
    let basis = reduce(
        &model,
        &ReductionRequest {
            method: Method::CraigBampton,
            boundary_nodes: vec![16, 18, 28, 30],
            modes: ModeSelection::Count(6),
            ..Default::default()
        },
    )
    .unwrap();
    FlexibleBody::new(model, basis, axes).unwrap()
}

#[test]
fn the_body_constructor_places_the_frame_and_the_system_adds_axis_conditions() {
    let nf = slab_body(AxisType::NodalFixed(NodalFixedAxes::slab_default()));
    let mean = slab_body(AxisType::Mean);
    let principal = slab_body(AxisType::Principal);
    // Nodal-fixed: six columns of the 18 removed (Table 4-1), origin at node 16.
    assert_eq!(nf.modes(), 12);
    assert_eq!(mean.modes(), 18);
    let n16 = nf.model.nodes[15];
    assert!((nf.origin - Vector3::new(n16[0], n16[1], n16[2])).norm() < 1e-15);
    // Node 16's deflection is zero in every column: it is the origin.
    assert!(nf.psi_nodes[15].amax() < 1e-14);
    // Mean and principal axes: origin at the mass centre, so the first moment vanishes.
    assert!(mean.invariants.first_moment0.norm() < 1e-12 * mean.mass());
    assert!((mean.mass() - nf.mass()).abs() < 1e-12 * nf.mass());
    // The system adds six rows for a body on mean or principal axes and none otherwise.
    let rows =
        |b: FlexibleBody| System::new(vec![Body::Flexible(Box::new(b))], vec![]).constraint_rows();
    assert_eq!(rows(nf), 0);
    assert_eq!(rows(mean.clone()), 6);
    assert_eq!(rows(principal), 6);
    // The mean-axis rows hold at a state that satisfies them and not at one that does not.
    let system = System::new(vec![Body::Flexible(Box::new(mean))], vec![]);
    let mut state = system.state_at(&[(Vector3::zeros(), Matrix3::identity())]);
    assert_eq!(system.violation(0.0, &state), (0.0, 0.0));
    let Body::Flexible(fb) = &system.bodies[0] else {
        unreachable!()
    };
    // A rigid translation of the deformation field breaks Eq. 4.20: the first column of the
    // constraint modes moves node 16 in x.
    state.q[7] = 1e-3;
    let expected = (fb.p_sum().column(0) * 1e-3).amax();
    let (pos, _) = system.violation(0.0, &state);
    assert!(
        (pos - expected).abs() < 1e-15 && pos > 1e-6,
        "{pos:e} vs {expected:e}"
    );
}

#[test]
fn magnified_deflections_scale_only_the_elastic_part() {
    let body = slab_body(AxisType::NodalFixed(NodalFixedAxes::slab_default()));
    let system = System::new(vec![Body::Flexible(Box::new(body))], vec![]);
    let rot = *nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.7).matrix();
    let mut state = system.state_at(&[(Vector3::new(1.0, -2.0, 0.5), rot)]);
    let mut rng = crate::common::Rng::new(7);
    for k in 7..state.q.len() {
        state.q[k] = 0.01 * rng.unit();
    }
    for node in [0, 7, 29] {
        let full = system.node_position(0, flexmodes::fem::NodeIndex(node), &state);
        let s = |f: f64| system.node_position_scaled(0, flexmodes::fem::NodeIndex(node), &state, f);
        assert!(
            (s(1.0) - full).norm() < 1e-14,
            "scale 1 is the true position"
        );
        // Linear in the factor, and 0 is the undeformed node carried by the frame.
        assert!((s(20.0) - (s(0.0) + 20.0 * (full - s(0.0)))).norm() < 1e-12);
        let (r, a) = system.placement(0, &state);
        let zero = system.node_position_scaled(0, flexmodes::fem::NodeIndex(node), &state, 0.0);
        let local = a.transpose() * (zero - r);
        let Body::Flexible(fb) = &system.bodies[0] else {
            unreachable!()
        };
        let p = fb.model.nodes[node];
        let undeformed = Vector3::new(p[0], p[1], p[2]) - fb.origin;
        assert!(
            (local - undeformed).norm() < 1e-12,
            "node {node}: {local} vs {undeformed}"
        );
        assert!((full - zero).norm() > 1e-4, "the state deforms node {node}");
    }
    // Every node at once (the frame read once), and the largest deflection, agree with the
    // node-by-node positions.
    let Body::Flexible(fb) = &system.bodies[0] else {
        unreachable!()
    };
    let nodes = fb.s_bar.len();
    for scale in [0.0, 1.0, 20.0] {
        let all = system.node_positions_scaled(0, &state, scale);
        assert_eq!(all.len(), nodes);
        for (j, p) in all.iter().enumerate() {
            let one = system.node_position_scaled(0, flexmodes::fem::NodeIndex(j), &state, scale);
            assert!((p - one).norm() < 1e-12, "node {j} at scale {scale}");
        }
    }
    let largest = (0..nodes)
        .map(|j| {
            (system.node_position(0, flexmodes::fem::NodeIndex(j), &state)
                - system.node_position_scaled(0, flexmodes::fem::NodeIndex(j), &state, 0.0))
            .norm()
        })
        .fold(0.0, f64::max);
    let reported = system.largest_deflection(0, &state);
    assert!(largest > 1e-4 && (reported - largest).abs() < 1e-12 * largest.max(1.0));
}

/// A state off the rest position: random deformation and velocities of every coordinate,
/// Euler parameters left unit.
fn stirred(
    system: &System,
    rest: &flexmodes::dynamics::State,
    rng: &mut Rng,
) -> flexmodes::dynamics::State {
    let mut s = rest.clone();
    for (b, body) in system.bodies.iter().enumerate() {
        let (qo, _) = system.offsets(b);
        for i in 7..body.position_count() {
            s.q[qo + i] += 1e-3 * rng.unit();
        }
    }
    for v in s.v.iter_mut() {
        *v = rng.unit();
    }
    s
}

#[test]
fn block_eliminated_accelerations_equal_the_dense_regularised_solve() {
    use flexmodes::dynamics::{Attachment, Constraint};
    use flexmodes::models;
    let mut rng = Rng::new(41);
    let slab_model = slab(&SlabParameters::default());
    let plank_model = flexmodes::fem::plank(&SlabParameters::default());
    let mut systems = Vec::new();
    for method in [Method::NoReduction, Method::CraigBampton, Method::Guyan] {
        for axes in [
            AxisType::Mean,
            AxisType::Principal,
            AxisType::NodalFixed(NodalFixedAxes::slab_default()),
        ] {
            let body =
                models::slab_body(&slab_model, method, axes, &models::SLAB_BOUNDARY, 6).unwrap();
            for scenario in [models::Scenario::HeldAtSix, models::Scenario::Orbit] {
                systems.push(models::slab_system(&scenario, body.clone()).unwrap());
            }
        }
    }
    for (method, axes) in [
        (Method::NoReduction, AxisType::Mean),
        (Method::CraigBampton, AxisType::Mean),
        (
            Method::NoReduction,
            AxisType::NodalFixed(models::plank_nodal_fixed()),
        ),
    ] {
        let variant = models::PlankVariant { method, axes };
        let body = models::plank_body(&plank_model, variant, 6).unwrap();
        systems.push(models::plank_system(body).unwrap());
    }
    // Redundant constraints: the plank's first joint twice (the saddle-point system is then
    // singular and its pseudo-inverse is taken).
    let (mut redundant, state) = systems.last().unwrap().clone();
    assert!(matches!(
        redundant.constraints[2],
        Constraint::Spherical(
            _,
            Attachment::Node {
                body: 0,
                node: flexmodes::fem::NodeIndex(2)
            }
        )
    ));
    redundant.constraints.push(redundant.constraints[2].clone());
    systems.push((redundant, state));
    assert_eq!(systems.len(), 3 * 3 * 2 + 3 + 1);
    for (i, (system, rest)) in systems.iter().enumerate() {
        for t in [0.0, 0.3] {
            let s = stirred(system, rest, &mut rng);
            let fast = system.accelerations(t, &s).unwrap();
            let dense = system.accelerations_dense(t, &s).unwrap();
            assert_eq!(fast.len(), dense.len());
            let diff = (&fast - &dense).amax();
            assert!(
                diff <= 1e-8 * dense.amax().max(1.0),
                "system {i} at t = {t}: |Δv̇| = {diff:e} of {:e}",
                dense.amax()
            );
        }
    }
}

#[test]
fn a_refined_slab_keeps_the_scenario_nodes_at_their_app_b_places() {
    use flexmodes::models::{default_boundary, slab_node};
    let app_b = slab(&SlabParameters::default());
    for bricks in [[4, 2, 1], [8, 4, 2], [12, 6, 3]] {
        let refined = slab(&SlabParameters::refined(bricks).unwrap());
        for n in [5, 8, 11, 16, 18, 28, 30] {
            let m = slab_node(&refined, n);
            assert_eq!(
                refined.nodes[m - 1],
                app_b.nodes[n - 1],
                "{bricks:?}: App. B node {n} mapped to node {m}"
            );
        }
        let corners = SlabParameters::refined(bricks).unwrap().bottom_corners();
        assert_eq!(default_boundary(&refined), corners.to_vec());
    }
    // App. B itself is numbered as Table B-1.
    assert_eq!(slab_node(&app_b, 8), 8);
    // Node 8 is the top-face centre.
    assert_eq!(app_b.nodes[7], [2.0, 1.0, 1.0]);
}
