//! A 512 k-DOF part meshed and assembled by codes other than flexmodes (the large link of
//! `assets/generate/make_bodies.py`, P2 tetrahedra by gmsh and scikit-fem, SI units), checked
//! against the references SciPy computed through CHOLMOD when it was written. It takes ~25 min
//! to write on two cores and ~9 GB while its references are solved, so it lives in its own
//! test binary, which CI builds and does not run:
//!
//! ```sh
//! python3 assets/generate/make_bodies.py --large target/huge/link-500k --h 0.00105 \
//!     --no-cases --cholmod
//! python3 assets/generate/rbe2_reference.py --cholmod --modes=20 target/huge/link-500k bore_a
//! FLEXMODES_HUGE_BODY=target/huge/link-500k cargo test --release --test huge_body -- --ignored
//! ```

use flexmodes::reduction::ReductionRequest;
use std::path::PathBuf;

#[path = "external/checks.rs"]
#[allow(dead_code)]
mod checks;

#[test]
#[ignore = "needs the generated 512 k-DOF link: FLEXMODES_HUGE_BODY=DIR (see the module doc)"]
fn half_a_million_dof_part_reduces_with_a_rigid_interface_like_cholmod_and_arpack() {
    use flexmodes::{
        analysis::{reduced_modes, zero_energy_below, zero_energy_threshold_hz},
        reduction::{
            InteriorProblem, Method, ModeSelection, RigidInterface, SolverPath, reduce_interior,
        },
    };
    let dir =
        PathBuf::from(std::env::var("FLEXMODES_HUGE_BODY").expect(
            "FLEXMODES_HUGE_BODY names the folder make_bodies.py --large … --h 0.00105 wrote",
        ));
    let (body, reference) = checks::load(&dir);
    let model = &body.model;
    assert!(model.dof_count() >= 500_000, "{} DOF", model.dof_count());
    // Free-free: Lanczos, its Sturm count, against ARPACK through CHOLMOD.
    checks::check_free_free("512 k link", &body, &reference);
    // Craig–Bampton on bore_a tied rigidly to its centroid, against SciPy's transformed body
    // (CHOLMOD solves, ARPACK fixed-interface modes, LAPACK on the reduced matrices).
    let rbe2: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("rbe2_reference.json")).unwrap())
            .unwrap();
    let case = &rbe2["cases"][0];
    let modes = case["modes"].as_u64().unwrap() as usize;
    let set = case["interfaces"][0].as_str().unwrap();
    let (boundary, sets) = body
        .boundary_with_interfaces(&[format!("rbe2:{set}")])
        .unwrap();
    let interfaces: Vec<RigidInterface> = sets
        .iter()
        .map(|s| RigidInterface::at_centroid(model, &s.name, &s.nodes).unwrap())
        .collect();
    let mut problem = InteriorProblem::new(model, &boundary, SolverPath::Auto)
        .unwrap()
        .with_rigid_interfaces(&interfaces)
        .unwrap();
    let basis = reduce_interior(
        &mut problem,
        &ReductionRequest::of(Method::CraigBampton).modes(ModeSelection::Count(modes)),
    )
    .unwrap();
    assert_eq!(basis.size(), 6 + modes);
    let eig = reduced_modes(model, &basis).unwrap();
    let all = eig.hz();
    let zero = zero_energy_below(&all, zero_energy_threshold_hz(model));
    assert_eq!(zero, 6, "one rigid interface: six zero-energy modes");
    let expected = checks::floats(&case["cb_hz"]);
    let count = (all.len() - zero).min(expected.len() - 6);
    assert!(count >= 20, "{count} elastic pairs compared");
    checks::assert_relative(
        "512 k link rbe2 CB",
        &all[zero..zero + count],
        &expected[6..6 + count],
        1e-6,
    );
}
