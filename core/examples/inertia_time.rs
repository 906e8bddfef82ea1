//! The Sturm count's two routes on a refined slab (profiling aid): the multifrontal inertia
//! count that keeps no factor against the stored supernodal LDLᵀ, their times, counts and the
//! values the first holds at most. `cargo run --release --example inertia_time -- NX` meshes
//! NX × NX/2 × NX/4 bricks (40: 28 k DOF, 60: 91 k DOF).

use flexmodes_core::fem::{SlabParameters, slab};
use flexmodes_core::linalg::{
    IndefiniteFactor, SymbolicFactor, multifrontal_inertia, nested_dissection,
};
use std::time::Instant;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(40);
    let model = slab(&SlabParameters {
        bricks: [n, n / 2, n / 4],
        ..Default::default()
    });
    let sigma = 1e7;
    let a = model.k.shifted(&model.m, sigma);
    let coords = model.dof_positions();
    let order = nested_dissection(a.as_faer(), &coords);
    let symbolic = SymbolicFactor::analyse_ordered(a.as_faer(), order.as_deref()).unwrap();
    println!("dof {} factor entries {}", a.dim(), symbolic.factor_nnz());
    for _ in 0..2 {
        let t = Instant::now();
        let i = multifrontal_inertia(&a, &symbolic).unwrap().unwrap();
        let lean = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let f = IndefiniteFactor::factor(a.clone(), &symbolic, "x").unwrap();
        let neg = f.negative_pivots();
        let full = t.elapsed().as_secs_f64();
        println!(
            "lean {lean:.2} s ({} neg, growth {:.2e}, peak {}), faer {full:.2} s ({neg} neg)",
            i.negative, i.growth, i.peak_entries
        );
    }
}
