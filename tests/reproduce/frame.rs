//! Bodies with six DOF per node through the one DOF map: 3-D Euler–Bernoulli frames against
//! beam theory, their rigid motions, and Craig–Bampton on a single clamped node.

use faer::{Mat, Side, linalg::solvers::Solve};
use flexmodes::reduction::{Method, ReductionRequest, reduce};
use flexmodes::{
    fem::{DofMap, FeModel, FrameSection, NodeDof, frame},
    linalg::max_abs,
    reduction::{ModeSelection, Partition, fixed_interface_modes},
};

const E: f64 = 210e9;
const G: f64 = 80e9;
const RHO: f64 = 7800.0;

fn section() -> FrameSection {
    FrameSection::rectangle(0.02, 0.01, E, G, RHO)
}

/// A straight cantilever along x from the origin, `n` elements, length `l` (m).
fn cantilever(n: usize, l: f64) -> FeModel {
    let nodes = (0..=n)
        .map(|i| [l * i as f64 / n as f64, 0.0, 0.0])
        .collect();
    let elements: Vec<_> = (0..n).map(|e| ([e, e + 1], [0.0, 1.0, 0.0])).collect();
    frame("cantilever", nodes, &elements, &section()).unwrap()
}

#[test]
fn a_bent_frame_has_six_rigid_motions_in_the_null_space_of_k() {
    // An L-shaped frame with a skew member, so no element is aligned with every axis.
    let nodes = vec![
        [0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 0.4, 0.1],
        [1.2, 0.8, 0.5],
    ];
    let up = [0.0, 0.0, 1.0];
    let elements = vec![
        ([0, 1], up),
        ([1, 2], up),
        ([2, 3], up),
        ([3, 4], [1.0, 0.0, 0.0]),
    ];
    let model = frame("bent", nodes, &elements, &section()).unwrap();
    assert_eq!(model.dofs, DofMap::frame_3d());
    assert_eq!(model.dof_count(), 30);
    assert_eq!(model.spatial_dim(), 3);
    let r = model.rigid_body_modes();
    assert_eq!(r.ncols(), 6);
    let kr = model.k.mul(r.as_ref());
    let rel = max_abs(kr.as_ref()) / (model.k.max_abs() * max_abs(r.as_ref()));
    assert!(rel < 1e-12, "{rel:e}");
    // Exactly six zero eigenvalues: the frame is connected.
    let eig = model
        .k_dense()
        .self_adjoint_eigenvalues(Side::Lower)
        .unwrap();
    let top = eig.last().copied().unwrap();
    assert_eq!(eig.iter().filter(|&&v| v.abs() < 1e-9 * top).count(), 6);
    assert!(eig[0] > -1e-9 * top);
    assert_eq!(model.dof_label(5 * 6 - 1), "node 5 θz");
    assert_eq!(
        model.dofs.locate(9),
        (1, NodeDof::Rotation(flexmodes::fem::Direction::X))
    );
}

#[test]
fn cantilever_tip_deflections_match_beam_theory() {
    let (n, l) = (8, 1.2);
    let model = cantilever(n, l);
    let s = section();
    // Clamp node 1 (all six DOF) and solve K_ii u = f for each tip load.
    let part = Partition::new(&model, &[1]).unwrap();
    let k = model.k_dense();
    let kii = Mat::from_fn(part.i.len(), part.i.len(), |a, b| k[(part.i[a], part.i[b])]);
    let llt = kii.llt(Side::Lower).unwrap();
    let tip = |dof: NodeDof| model.dofs.index(n, dof).unwrap();
    let cases = [
        // (load DOF, load, expected displacement of the same DOF): Euler–Bernoulli elements
        // are exact at the nodes for end loads.
        (
            NodeDof::Translation(flexmodes::fem::Direction::X),
            1e3,
            1e3 * l / (E * s.area),
        ),
        (
            NodeDof::Translation(flexmodes::fem::Direction::Y),
            10.0,
            10.0 * l.powi(3) / (3.0 * E * s.iz),
        ),
        (
            NodeDof::Translation(flexmodes::fem::Direction::Z),
            10.0,
            10.0 * l.powi(3) / (3.0 * E * s.iy),
        ),
        (
            NodeDof::Rotation(flexmodes::fem::Direction::X),
            5.0,
            5.0 * l / (G * s.torsion),
        ),
    ];
    for (dof, load, expected) in cases {
        let mut f = Mat::<f64>::zeros(part.i.len(), 1);
        let row = part.i.iter().position(|&d| d == tip(dof)).unwrap();
        f[(row, 0)] = load;
        let u = llt.solve(&f);
        let got = u[(row, 0)];
        assert!(
            (got - expected).abs() < 1e-9 * expected,
            "{dof:?}: {got:e} vs {expected:e}"
        );
    }
    // Bending about the two axes differs by (height/width)² = 1/4 in stiffness.
    assert!((s.iy / s.iz - 0.25).abs() < 1e-12);
}

#[test]
fn one_clamped_six_dof_node_restrains_the_frame_and_craig_bampton_runs_on_it() {
    let (n, l) = (40, 1.0);
    let model = cantilever(n, l);
    let s = section();
    // A single node restrains a body whose nodes carry rotations (a solid's needs three).
    let part = Partition::new(&model, &[1]).unwrap();
    assert_eq!(part.b.len(), 6);
    let fi = fixed_interface_modes(&model, &part).unwrap();
    let hz = fi.hz();
    // First bending mode of a cantilever: (1.8751²/2π) √(EI/(ρA L⁴)), in the stiff plane and
    // the soft one; lumped masses with 40 elements are within 0.5 %.
    let f1 = |i: f64| {
        1.875104_f64.powi(2) / (2.0 * std::f64::consts::PI)
            * (E * i / (RHO * s.area * l.powi(4))).sqrt()
    };
    let soft = f1(s.iy);
    let stiff = f1(s.iz);
    assert!((hz[0] - soft).abs() < 5e-3 * soft, "{} vs {soft}", hz[0]);
    let closest = hz.iter().copied().fold(f64::INFINITY, |b, f| {
        if (f - stiff).abs() < (b - stiff).abs() {
            f
        } else {
            b
        }
    });
    assert!(
        (closest - stiff).abs() < 5e-3 * stiff,
        "{closest} vs {stiff}"
    );
    let cb = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[1])
            .modes(ModeSelection::Count(4)),
    )
    .unwrap();
    assert_eq!(cb.size(), 6 + 4);
    // The constraint modes of a single clamped node are the six rigid motions.
    let r = model.rigid_body_modes();
    let angles = flexmodes::linalg::principal_angles(cb.psi.subcols(0, 6), r.as_ref()).unwrap();
    assert_eq!(angles.len(), 6);
    assert!(angles.iter().all(|&a| a < 1e-8), "{angles:?}");
}
