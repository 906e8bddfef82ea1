//! Seeded property tests of the dense kernels, looped over sizes with size-scaled tolerances.

use faer::Mat;
use flexmodes::linalg::{generalized_eigen, max_abs, principal_angles, solve_lyapunov};

use crate::common::Rng;

fn random(rng: &mut Rng, r: usize, c: usize) -> Mat<f64> {
    Mat::from_fn(r, c, |_, _| rng.unit())
}

fn spd(rng: &mut Rng, n: usize, shift: f64) -> Mat<f64> {
    let a = random(rng, n, n);
    let mut s = a.transpose() * &a;
    for i in 0..n {
        s[(i, i)] += shift;
    }
    s
}

#[test]
fn generalized_eigen_residual_and_mass_normalisation() {
    let mut rng = Rng::new(11);
    for n in [1, 2, 5, 12, 30, 60] {
        let k = spd(&mut rng, n, 0.0);
        let m = spd(&mut rng, n, 1.0);
        let e = generalized_eigen(k.as_ref(), m.as_ref(), "test").unwrap();
        let lam = Mat::from_fn(n, n, |i, j| if i == j { e.values[i] } else { 0.0 });
        let res = &k * &e.vectors - &m * &e.vectors * &lam;
        let tol = 1e-11 * n as f64 * max_abs(k.as_ref()).max(1.0) * max_abs(e.vectors.as_ref());
        assert!(max_abs(res.as_ref()) < tol, "n = {n}");
        let mm = e.vectors.transpose() * &m * &e.vectors;
        let id = Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 });
        assert!(max_abs((&mm - &id).as_ref()) < 1e-10 * n as f64, "n = {n}");
        assert!(e.values.windows(2).all(|w| w[0] <= w[1]));
    }
}

#[test]
fn lyapunov_solves_stable_systems() {
    let mut rng = Rng::new(5);
    for n in [1, 3, 8, 20, 40] {
        // A = -(SPD) + skew: eigenvalues in the open left half-plane.
        let s = spd(&mut rng, n, 0.5);
        let w = random(&mut rng, n, n);
        let a = -&s + (&w - w.transpose());
        let b = random(&mut rng, n, 2);
        let q = &b * b.transpose();
        let x = solve_lyapunov(a.as_ref(), q.as_ref()).unwrap();
        let res = &a * &x + &x * a.transpose() + &q;
        assert!(
            max_abs(res.as_ref()) < 1e-9 * n as f64 * max_abs(q.as_ref()),
            "n = {n}"
        );
        assert!(max_abs((&x - x.transpose()).as_ref()) < 1e-12 * max_abs(x.as_ref()).max(1.0));
    }
}

#[test]
fn principal_angles_of_known_subspaces() {
    let mut rng = Rng::new(9);
    for n in [3, 10, 40] {
        let a = random(&mut rng, n, 2);
        let mix = random(&mut rng, 2, 2);
        let b = &a * &mix;
        let angles = principal_angles(a.as_ref(), b.as_ref()).unwrap();
        assert!(angles.iter().all(|&t| t < 1e-7), "n = {n}: {angles:?}");
        // Orthogonal subspaces: e1 vs e2.
        let e1 = Mat::from_fn(n, 1, |i, _| if i == 0 { 1.0 } else { 0.0 });
        let e2 = Mat::from_fn(n, 1, |i, _| if i == 1 { 1.0 } else { 0.0 });
        let t = principal_angles(e1.as_ref(), e2.as_ref()).unwrap();
        assert!((t[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }
}
