//! Dynamic stiffening of a spinning cantilever against the published rotating-beam tables
//! (Wright et al. 1982; Hodges & Rutkowski 1981), against closed forms, and against Kane et
//! al.'s spin-up computed independently by a co-rotational beam.

use flexmodes::Progress;
use flexmodes::{
    fem::{BendingPlane, SpinningBeam, SpinningBeamParameters},
    models::{
        CampbellParameters, PUBLISHED_TOLERANCE, SPIN_UP_TOLERANCE, SpinUpParameters,
        campbell_study, spin_up_reference, spin_up_study, spinning_beam_body,
    },
};
use nalgebra::Vector3;

/// NR and CB 6 with stiffening meet the published flapwise λ-table to 1e-3 for λ = 0…10,
/// and the error shrinks with the mesh (elements 10, 20, 40); without stiffening the
/// frequency stays at its value at rest, 3.5160, at every speed, more than 1e-3 away.
#[test]
fn campbell_flapwise_matches_the_published_table() {
    let mut previous = f64::INFINITY;
    for elements in [10, 20, 40] {
        let study = campbell_study(&CampbellParameters {
            beam: SpinningBeamParameters {
                elements,
                ..Default::default()
            },
            ..Default::default()
        })
        .unwrap();
        let nr = study.curve(0, true, BendingPlane::Flapwise).unwrap();
        let diff = study.published_difference(nr, 10.0);
        assert!(diff < previous, "{elements}: {diff} not below {previous}");
        previous = diff;
        if elements == 40 {
            assert!(diff < PUBLISHED_TOLERANCE, "NR {diff}");
            let cb = study.curve(6, true, BendingPlane::Flapwise).unwrap();
            let cb_diff = study.published_difference(cb, 10.0);
            assert!(cb_diff < PUBLISHED_TOLERANCE, "CB {cb_diff}");
            // A reduced model is a Ritz approximation of the full one: never below it (to
            // the eigensolver's round-off, 4e-9 here: at λ = 0 the basis holds the exact modes).
            for (c, n) in cb.mu_squared.iter().zip(&nr.mu_squared) {
                assert!(
                    c[0] >= n[0] * (1.0 - 1e-7) && c[1] >= n[1] * (1.0 - 1e-7),
                    "{c:?} {n:?}"
                );
            }
            let off = study.curve(0, false, BendingPlane::Flapwise).unwrap();
            for mu in off.mu() {
                assert!((mu[0] - 3.5160).abs() < 1e-3, "{mu:?}");
            }
            assert!(study.published_difference(off, 10.0) > 0.5);
            assert!(study.max_residual < 1e-6, "{}", study.max_residual);
        }
    }
}

/// Lagwise, the beam's transverse motion lies in the plane of rotation: its softening is
/// −Ω²M on v, so μ_lag² = μ_flap² − λ² exactly (same mesh). Without stiffening μ_lag² =
/// μ₁² − λ² reaches zero at λ = μ₁ = 3.516: unstable from λ = 4 on the grid.
#[test]
fn lagwise_without_stiffening_loses_its_frequency_at_the_first_bending_frequency() {
    let study = campbell_study(&CampbellParameters::default()).unwrap();
    let speeds = &study.parameters.speeds;
    for stiffening in [true, false] {
        let flap = study.curve(0, stiffening, BendingPlane::Flapwise).unwrap();
        let lag = study.curve(0, stiffening, BendingPlane::Lagwise).unwrap();
        for (i, l) in speeds.iter().enumerate() {
            let expected = flap.mu_squared[i][0] - l * l;
            let got = lag.mu_squared[i][0];
            assert!(
                (got - expected).abs() < 1e-7 * flap.mu_squared[i][0],
                "λ = {l}: {got} against {expected}"
            );
        }
    }
    let off = study.curve(0, false, BendingPlane::Lagwise).unwrap();
    assert_eq!(off.unstable_from(speeds), Some(4.0));
    let on = study.curve(0, true, BendingPlane::Lagwise).unwrap();
    assert_eq!(on.unstable_from(speeds), None);
}

/// The unit geometric stiffness of rate² is the one the closed-form tension gives: its
/// energy on a transverse field v is ∫N v'² dx with N = ρA((r+L)² − (r+x)²)/2, checked on
/// v = x² (exact for the element's cubic; the element's constant N, the mean of the exact
/// one, against the exact N: an error of order h², 16 times smaller for 4 times the
/// elements). The tangential load of θ̈ stresses a straight beam not at all.
#[test]
fn centrifugal_geometric_stiffness_is_the_tension_of_the_spinning_beam() {
    let mut errors = Vec::new();
    for elements in [20, 80] {
        let p = SpinningBeamParameters {
            hub_radius: 2.0,
            elements,
            ..Default::default()
        };
        let beam = SpinningBeam::new(&p, BendingPlane::Lagwise);
        let cases = beam.unit_geometric_stiffnesses().unwrap();
        let kg = cases[0].as_ref().unwrap();
        assert!(cases[1].is_none(), "θ̈ stresses a straight beam axially");
        let (r, l, rho) = (p.hub_radius, p.length, p.mass_per_length);
        // v = x², θ = 2x at each free node.
        let le = l / elements as f64;
        let mut v = nalgebra::DVector::zeros(beam.dim());
        for j in 1..=elements {
            let x = j as f64 * le;
            v[3 * (j - 1) + 1] = x * x;
            v[3 * (j - 1) + 2] = 2.0 * x;
        }
        let energy = (v.transpose() * kg * &v)[(0, 0)];
        // ∫₀ᴸ ρA((r+L)² − (r+x)²)/2 · 4x² dx.
        let a = (r + l).powi(2);
        let exact = 2.0
            * rho
            * (a * l.powi(3) / 3.0
                - (r * r * l.powi(3) / 3.0 + r * l.powi(4) / 2.0 + l.powi(5) / 5.0));
        errors.push((energy - exact).abs() / exact);
    }
    assert!(errors[0] < 5e-3 && errors[1] < 2e-4, "{errors:?}");
    assert!(errors[0] / errors[1] > 12.0, "{errors:?}");
}

/// The driven beam's combination with stiffening is K + θ̈G + θ̇²(H + K_σ,1) on the full
/// body and Ψᵀ(…)Ψ on a reduced one (its stiffness projected once), and a copy without
/// stiffening drops exactly the K_σ term.
#[test]
fn the_driven_beam_combines_its_geometric_stiffness() {
    use flexmodes::dynamics::{Combination, DrivenFrameBody, stiffening_coefficients};
    let p = SpinningBeamParameters::default();
    let (beam, body) = spinning_beam_body(&p).unwrap();
    assert!(body.has_stiffening());
    let kg = beam.unit_geometric_stiffnesses().unwrap()[0]
        .clone()
        .unwrap();
    let (rate, acc) = (3.0, 0.7);
    let c = Combination {
        k: 1.0,
        g: acc,
        h: rate * rate,
        sigma: stiffening_coefficients(rate, acc, Vector3::zeros()),
        ..Default::default()
    };
    let x = nalgebra::DVector::from_fn(beam.dim(), |i, _| ((i as f64) * 0.37).sin());
    let expected = &beam.k * &x + &beam.g * &x * acc + (&beam.h + &kg) * &x * (rate * rate);
    let got = nalgebra::DVector::from_vec(body.mul(c, x.as_slice()));
    assert!((&got - &expected).amax() < 1e-12 * expected.amax());
    let plain = nalgebra::DVector::from_vec(body.dense_copy(false).unwrap().mul(c, x.as_slice()));
    let dropped = &got - &plain - &kg * &x * (rate * rate);
    assert!(dropped.amax() < 1e-12 * expected.amax());
    // A reduced body on three columns: its product is Ψᵀ(A)Ψ z.
    let psi = faer::Mat::from_fn(beam.dim(), 3, |i, j| ((i * (j + 2)) as f64 * 0.11).cos());
    let reduced = DrivenFrameBody::reduced(&body, psi.as_ref()).unwrap();
    assert!(reduced.has_stiffening());
    let z = [0.3, -1.0, 2.0];
    let psi_n = nalgebra::DMatrix::from_fn(beam.dim(), 3, |i, j| psi[(i, j)]);
    let full_x = &psi_n * nalgebra::DVector::from_column_slice(&z);
    let full_y = nalgebra::DVector::from_vec(body.mul(c, full_x.as_slice()));
    let expected = psi_n.transpose() * full_y;
    let got = nalgebra::DVector::from_vec(reduced.mul(c, &z));
    assert!((&got - &expected).amax() < 1e-10 * expected.amax());
}

/// Kane's beam at 4 and 10 rad/s: NR and CB 6 with stiffening within 5 % of the
/// co-rotational reference's peak over 0–20 s; without stiffening at 10 rad/s the model
/// diverges after the hub passes the first bending frequency (3.80 rad/s).
#[test]
fn kanes_spin_up_with_stiffening_follows_the_nonlinear_reference() {
    let study = spin_up_study(&SpinUpParameters::default(), &Progress::new()).unwrap();
    // ω₁ = μ₁√(EI/ρAL⁴) with the published μ₁ = 3.5160 at rest (four decimals).
    let unit = study.parameters.beam.frequency_unit();
    assert!(
        (study.first_frequency / unit - 3.5160).abs() < 1e-4,
        "{}",
        study.first_frequency / unit
    );
    for run in &study.runs {
        let reference = spin_up_reference(run.rate).unwrap();
        assert!(reference.len() > 300, "the reference is written");
        if run.stiffening {
            assert!(run.divergence.is_none(), "{}", run.label());
            assert_eq!(run.times.len(), 401);
            let d = run.difference(&reference);
            assert!(
                d < SPIN_UP_TOLERANCE,
                "{} at {}: {d}",
                run.label(),
                run.rate
            );
        }
    }
    let diverged = study
        .runs
        .iter()
        .find(|r| r.rate == 10.0 && r.modes == 0 && !r.stiffening)
        .unwrap()
        .divergence
        .expect("the unstiffened beam diverges at 10 rad/s");
    let passed = diverged.rate_passed_first_frequency.unwrap();
    assert!(diverged.time > passed && diverged.rate > study.first_frequency);
}

/// A user's body with CalculiX's preloaded stiffness (the steel lever of
/// assets/generate/spun_body.py, spun at 1 000 rad/s about z through its root): the full
/// body's spinning frequencies at 1 000 and 2 000 rad/s equal CalculiX's own prestressed
/// frequencies to 2e-4 (the stiffening scaled with the rate² from the one preloaded run), CB
/// with 12 modes within 2e-3; without stiffening the first frequency stays below CalculiX's
/// by more than its spin's share.
#[test]
fn a_calculix_body_spins_at_calculix_frequencies() {
    use flexmodes::{
        body_file::ImportedBody,
        models::{BodyCampbellParameters, body_campbell},
        reduction::Method,
    };
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bodies/spun-lever");
    let body = ImportedBody::load(&format!("{dir}/body.toml")).unwrap();
    let preload = body
        .preload
        .as_ref()
        .expect("the body file has a [preload]");
    assert!((preload.load.rate - 1000.0).abs() < 1e-9);
    assert_eq!(preload.held.len(), 27, "the root's 9 nodes held");
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(format!("{dir}/reference.json")).unwrap())
            .unwrap();
    let ccx: Vec<Vec<f64>> = serde_json::from_value(reference["spinning_hz"].clone()).unwrap();
    let parameters = BodyCampbellParameters {
        drive: "rbe2:root".into(),
        axis: [0.0, 0.0, 1.0],
        axis_point: None,
        rates: vec![1000.0, 2000.0],
        count: 6,
        models: vec![(Method::CraigBampton, 12)],
        stiffening: true,
        full: true,
        residual_vectors: false,
    };
    let on = body_campbell(&body, &parameters, &Progress::new()).unwrap();
    assert!(on.stiffened);
    for (r, rate_hz) in ccx.iter().enumerate() {
        for (m, &expected) in rate_hz.iter().take(6).enumerate() {
            let ascending = |v: &[f64]| {
                let mut v = v.to_vec();
                v.sort_by(f64::total_cmp);
                v
            };
            let full = ascending(&on.curves[0].hz[r])[m];
            assert!(
                (full - expected).abs() < 2e-4 * expected,
                "NR rate {r} mode {m}: {full} {expected}"
            );
            let cb = ascending(&on.curves[1].hz[r])[m];
            assert!(
                (cb - expected).abs() < 2e-3 * expected,
                "CB rate {r} mode {m}: {cb} {expected}"
            );
        }
    }
    let off = body_campbell(
        &body,
        &BodyCampbellParameters {
            stiffening: false,
            models: vec![],
            ..parameters.clone()
        },
        &Progress::new(),
    )
    .unwrap();
    assert!(!off.stiffened);
    assert!(
        off.curves[0].hz[1][0] < 0.9 * ccx[1][0],
        "{}",
        off.curves[0].hz[1][0]
    );
    // A spin about another axis is not the one CalculiX preloaded: named, not used.
    let tilted = body_campbell(
        &body,
        &BodyCampbellParameters {
            axis: [0.0, 1.0, 0.0],
            models: vec![],
            ..parameters
        },
        &Progress::new(),
    )
    .unwrap_err();
    assert!(
        tilted
            .to_string()
            .contains("[preload] was written for another spin"),
        "{tilted}"
    );
}

/// flexmodes' own bricks against CalculiX's own stress stiffening, each code assembling its
/// body: the steel lever of assets/generate/spun_body.py (100 × 10 × 5 mm, 12 × 2 × 2 C3D8,
/// mm-t-s, root face clamped, spun about z through the root's centre) meshed by flexmodes'
/// brick mesh with its consistent mass; the centrifugal unit case solved statically on the
/// clamped mesh, its element stresses made into a geometric stiffness
/// ([`unit_case_stiffnesses`](flexmodes::dynamics::unit_case_stiffnesses)), the spin
/// softening $-\Omega^2 M$ across the axis. At 1 000 and 2 000 rad/s, against CalculiX's
/// prestressed `*FREQUENCY` (reference.json): the six lowest frequencies within 1e-4 (6e-6 to
/// 9e-5 measured), and what the spin adds to f² within 1.5 % for the bending modes (0.2 to
/// 1.2 % measured); the fifth mode's spin share, 0.17 % of its frequency, is 16 % above
/// CalculiX's (3e-4 of the frequency; not explained yet). Without the geometric stiffness
/// the first is 10 % low at 2 000 rad/s.
#[test]
fn flexmodes_bricks_stiffen_as_calculix_does() {
    use flexmodes::{
        dynamics::{CaseSupport, unit_case_stiffnesses},
        fem::{BrickElements, SlabParameters, slab},
        linalg::generalized_eigen,
    };
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bodies/spun-lever");
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(format!("{dir}/reference.json")).unwrap())
            .unwrap();
    let rates: Vec<f64> = serde_json::from_value(reference["rates_rad_s"].clone()).unwrap();
    let ccx: Vec<Vec<f64>> = serde_json::from_value(reference["spinning_hz"].clone()).unwrap();
    let size = [100.0, 10.0, 5.0];
    let p = SlabParameters {
        size,
        bricks: [12, 2, 2],
        youngs_modulus: 210_000.0,
        poisson_ratio: 0.3,
        total_mass: 7.85e-9 * size.iter().product::<f64>(),
        consistent_mass: true,
    };
    let model = slab(&p);
    // CalculiX's lever is centred on y and z; the axis runs through its root's centre.
    let origin = Vector3::new(0.0, size[1] / 2.0, size[2] / 2.0);
    let n = model.dof_count();
    let held: Vec<usize> = (0..n).filter(|&d| model.nodes[d / 3][0] == 0.0).collect();
    assert_eq!(held.len(), 27, "the root's 9 nodes");
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let k_sigma = unit_case_stiffnesses(
        &model,
        &BrickElements::of_slab(&p),
        origin,
        &CaseSupport::Held(held.clone()),
        &[2],
    )
    .unwrap()
    .remove(0)
    .expect("spin about z stresses the lever");
    let (k, m, ks) = (model.k.to_dense(), model.m.to_dense(), k_sigma.to_dense());
    let spinning = |rate: f64, stiffened: bool| -> Vec<f64> {
        let w2 = rate * rate;
        let k_eff = faer::Mat::from_fn(free.len(), free.len(), |i, j| {
            let (a, b) = (free[i], free[j]);
            let softening = if a % 3 != 2 { -m[(a, b)] } else { 0.0 };
            k[(a, b)] + w2 * (softening + if stiffened { ks[(a, b)] } else { 0.0 })
        });
        let m_ff = faer::Mat::from_fn(free.len(), free.len(), |i, j| m[(free[i], free[j])]);
        let pairs = generalized_eigen(k_eff.as_ref(), m_ff.as_ref(), "spun lever").unwrap();
        pairs
            .values
            .iter()
            .take(6)
            .map(|l| l.sqrt() / (2.0 * std::f64::consts::PI))
            .collect()
    };
    // At rest the two codes' bodies agree (CalculiX's own matrices give the same six to
    // 6 digits, assets/bodies/spun-lever); what the spin adds, f² − f₀², is compared.
    let rest = spinning(0.0, true);
    for (rate, expected) in rates.iter().zip(&ccx) {
        let hz = spinning(*rate, true);
        for (mode, ((ours, theirs), f0)) in hz.iter().zip(expected).zip(&rest).enumerate() {
            let share = (ours * ours - f0 * f0) / (theirs * theirs - f0 * f0) - 1.0;
            let (frequency_tolerance, share_tolerance) = if mode == 4 {
                (3e-4, 0.2)
            } else {
                (1e-4, 0.015)
            };
            assert!(
                (ours - theirs).abs() < frequency_tolerance * theirs
                    && share.abs() < share_tolerance,
                "{rate} rad/s, mode {mode}: {ours} Hz against CalculiX's {theirs} (at rest \
                 {f0}): the spin's share off by {share:.2e}"
            );
        }
    }
    let unstiffened = spinning(rates[1], false)[0];
    assert!(
        unstiffened < 0.9 * ccx[1][0],
        "without the geometric stiffness: {unstiffened} Hz against {}",
        ccx[1][0]
    );
}
