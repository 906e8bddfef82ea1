//! The slow half of `tests/reproduce/body_methods.rs`: every method on the committed external
//! bodies with checked modes, and the static compliance across an interface.

use flexmodes::{
    Progress,
    analysis::count_zero_energy_modes,
    error::CoreError as Error,
    models::{BODY_METHODS, BodyInterfaces, BodyReducer},
    reduction::{Method, ReductionError},
};

use super::checks::{self, committed_body as body, first_rbe2_interface as rbe2_interfaces};

/// Each method, ten kept modes, a rigid interface: exact zero-energy counts, every printed
/// pair's residual below 1e-8, every elastic frequency at or above SciPy's full-body one of
/// the same order (a Ritz value never lies below), Benfield–Hruda (free-interface modes for a
/// body alone) equal to SciPy's, CB and MC equal, and MacNeal–Rubin refused by name.
#[test]
fn every_method_reduces_an_external_body_with_checked_modes() {
    for name in ["steel-link", "flange-hub"] {
        let (body, reference) = body(name);
        let model = &body.model;
        let expected = checks::floats(&reference["free_free_hz"]);
        assert_eq!(expected.len(), 18, "{name}: 6 zero-energy and 12 elastic");
        let scipy_elastic = &expected[6..];
        let full = count_zero_energy_modes(model, 10).unwrap();
        assert_eq!(full.zero_modes, 6, "{name}");
        let mut reducer = BodyReducer::new(
            model,
            rbe2_interfaces(&body, &reference),
            &full,
            0.0,
            Progress::default(),
        )
        .unwrap();
        let mut cb_hz = Vec::new();
        for method in BODY_METHODS {
            let what = format!("{name} {}", method.id());
            let reduced = match reducer.reduce(method, 10) {
                Err(Error::Reduction(ReductionError::MethodNeedsContext { .. }))
                    if method == Method::MacNealRubin =>
                {
                    continue;
                }
                other => other.unwrap_or_else(|e| panic!("{what}: {e}")),
            };
            assert_ne!(method, Method::MacNealRubin, "{what}: refused with rbe2");
            // Modal truncation's boundary columns move the ring with the rest at rest: no
            // rigid-body motion of the whole body is in its space. Guyan on one rigid
            // interface is the rigid body itself.
            let (zero, size) = match method {
                Method::ModalTruncation => (0, 16),
                Method::Guyan => (6, 6),
                Method::MomentMatching => (6, 18),
                _ => (6, 16),
            };
            assert_eq!(reduced.zero_modes, zero, "{what}");
            assert_eq!(reduced.basis.size(), size, "{what}");
            assert_eq!(reduced.modes.values.len(), size, "{what}");
            for (k, r) in reduced.modes.residuals.iter().enumerate() {
                assert!(*r <= 1e-8, "{what}: pair {k} residual {r:e}");
            }
            // Ritz values: the k-th of the reduced pencil at or above the full body's k-th,
            // zero-energy modes counted (SciPy's 6 of them, then its 12 elastic).
            for (k, (r, f)) in reduced.modes.hz().iter().zip(&expected).enumerate().skip(6) {
                assert!(
                    *r >= f * (1.0 - 1e-9),
                    "{what}: Ritz value {k} at {r} Hz below the full body's {f} Hz"
                );
            }
            let hz = reduced.elastic_hz();
            match method {
                Method::BenfieldHruda => {
                    checks::assert_relative(&what, &hz, &scipy_elastic[..10], 1e-7)
                }
                Method::CraigBampton => cb_hz = hz,
                Method::ModeCondensation => checks::assert_relative(&what, &hz, &cb_hz, 1e-6),
                _ => {}
            }
        }
        assert_eq!(cb_hz.len(), 10, "{name}: CB ran before MC");
    }
}

/// The elastic static compliance across a plain interface (inertia relief, $K^+$ by a fixed
/// point on a sparse Cholesky of $K + \sigma M$, checked by $\|Kx - L_e\|$): MacNeal–Rubin,
/// whose residual-flexibility modes are computed its own way (on a 3-2-1 support), holds it
/// exactly (1e-8); Craig–Bampton approaches it as modes are kept.
#[test]
fn the_static_compliance_across_an_interface_is_macneal_rubins() {
    use flexmodes::models::InterfaceStatics;
    let (body, reference) = body("steel-link");
    let model = &body.model;
    let set = reference["cases"][0]["boundary"].as_str().unwrap();
    let full = count_zero_energy_modes(model, 10).unwrap();
    let interfaces = BodyInterfaces {
        boundary: body.node_sets[set].clone(),
        rigid: Vec::new(),
        averaging: Vec::new(),
        interface_modes: None,
    };
    let mut reducer = BodyReducer::new(model, interfaces, &full, 0.0, Progress::default()).unwrap();
    let statics = InterfaceStatics::of_full_body(
        model,
        reducer.loads().unwrap(),
        full.modes.vectors.subcols(0, 6),
        full.modes.values[6],
        &Progress::default(),
    )
    .unwrap();
    let mut error = |m: Method, k: usize| {
        let r = reducer.reduce(m, k).unwrap();
        statics.error_of(&r.basis, &r.modes, r.zero_modes)
    };
    let mr = error(Method::MacNealRubin, 10);
    assert!(mr < 1e-8, "MR {mr:e}");
    let (cb4, cb16) = (
        error(Method::CraigBampton, 4),
        error(Method::CraigBampton, 16),
    );
    assert!(cb16 < cb4 && cb16 > 1e-6, "CB {cb4:e} → {cb16:e}");
}
