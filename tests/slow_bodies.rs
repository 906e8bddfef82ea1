//! The slow tests: a 30 k+-DOF body meshed and assembled by codes other than flexmodes (P2
//! tetrahedra by gmsh and scikit-fem, SI units, two bores as node sets), checked against the
//! reference values SciPy computed when it was written. The body is ~15 MB, so it is not
//! committed: `.ci/run` writes it with
//!
//! ```sh
//! pip install -r assets/generate/requirements.txt
//! python3 assets/generate/make_bodies.py --large target/large-body
//! FLEXMODES_LARGE_BODY=target/large-body cargo test --test slow_bodies -- --ignored
//! ```

use std::path::PathBuf;

#[path = "external/checks.rs"]
#[allow(dead_code)]
mod checks;

fn large_body() -> PathBuf {
    let dir = std::env::var("FLEXMODES_LARGE_BODY").expect(
        "FLEXMODES_LARGE_BODY names the folder assets/generate/make_bodies.py --large wrote",
    );
    PathBuf::from(dir)
}

#[test]
#[ignore = "needs the generated 30 k+-DOF body: FLEXMODES_LARGE_BODY=DIR (see the module doc)"]
fn a_30k_dof_part_from_another_fe_code_matches_scipy() {
    let (body, reference) = checks::load(&large_body());
    assert!(
        body.model.dof_count() > 30_000,
        "{} DOF",
        body.model.dof_count()
    );
    checks::check_free_free("large link", &body, &reference);
    checks::check_mass_properties("large link", &body, &reference);
    checks::check_reductions("large link", &body, &reference);
}
