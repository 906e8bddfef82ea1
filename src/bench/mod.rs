//! `flexmodes bench`: speed against accuracy, measured in one run on this machine against
//! peers measured in the same run. Timings are reported, never asserted.

mod bench_point;
mod body_bench;
mod driven_size_bench;
mod eigensolver_bench;
mod export_bench;
mod mode_bench;
mod pareto;
mod simulation_bench;
mod simulation_bench_text;
mod simulation_size_bench;
mod size_bench;
mod spin_up_bench;

pub use crate::analysis::{pareto_flags, three_digits};
pub use bench_point::{BenchPoint, LOOSE_ATOL, LOOSE_RTOL};
pub use body_bench::bench_body_modes;
pub use driven_size_bench::{DrivenSizePoint, bench_driven_sizes, driven_size_parameters};
pub use eigensolver_bench::bench_eigensolvers;
pub use export_bench::{ExportBenchParameters, bench_export};
pub use mode_bench::{COMPARED_MODES, ModeBenchPoint, bench_modes};
pub use pareto::mark_pareto;
pub use simulation_bench::{BENCH_SCHEMES, bench_simulation};
pub(crate) use simulation_bench::{MODE_SWEEP, bench_scenario};
pub use simulation_size_bench::{SIZES_RUN_S, bench_sim_sizes};
pub use size_bench::{BENCH_MODES, SizeBench, bench_sizes, growth_exponent, parse_sizes};
pub use spin_up_bench::{STABLE_RATE, bench_spin_up};
