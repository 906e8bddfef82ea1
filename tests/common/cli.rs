//! Helpers of the command-line tests (`tests/cli.rs`, and the slow ones in `tests/slow/`):
//! the built binary run with arguments, its JSON, a fresh temporary folder.

use std::process::{Command, Output};

pub fn flexmodes(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexmodes"))
        .args(args)
        .output()
        .expect("run flexmodes")
}

pub fn json(args: &[&str]) -> serde_json::Value {
    let out = flexmodes(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON object on stdout")
}

/// A fresh empty folder, removed when the test passes.
pub fn temp_dir(name: &str) -> crate::scratch::Scratch {
    crate::scratch::Scratch::new(&format!("cli-{name}"))
}

/// The reduced matrices in `dir`, solved by nalgebra (Cholesky of M_r, then the symmetric
/// eigenproblem of L⁻¹K_rL⁻ᵀ): an eigen solver flexmodes' own path does not use. Hz, ascending.
pub fn nalgebra_hz(dir: &std::path::Path) -> Vec<f64> {
    use flexmodes::body_file::read_matrix_market;
    let read = |name: &str| {
        let mm = read_matrix_market(&dir.join(name)).unwrap();
        let mut a = nalgebra::DMatrix::<f64>::zeros(mm.rows, mm.cols);
        for (i, j, v) in mm.expanded() {
            a[(i, j)] = v;
        }
        a
    };
    let (k, m) = (read("k_r.mtx"), read("m_r.mtx"));
    let l = m.cholesky().expect("M_r positive definite").l();
    let l_inv = l.try_inverse().unwrap();
    let c = &l_inv * k * l_inv.transpose();
    let c = (&c + c.transpose()) * 0.5;
    let mut hz: Vec<f64> = c
        .symmetric_eigenvalues()
        .iter()
        .map(|&l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect();
    hz.sort_by(f64::total_cmp);
    hz
}
