//! The slab's mode results, shared by the App. B mesh (`slab_modes.rs`) and a refined one
//! (`slab_refined.rs`).

use serde_json::{Map, Value, json};

use crate::report::sig_vec;

/// The slab's mode results shared by the App. B mesh and a refined one: the free-free and
/// fixed-interface frequencies (Hz), and each method's reduced frequencies and basis size.
pub(super) fn insert_mode_results(
    r: &mut Map<String, Value>,
    (free_free_hz, fixed_interface_hz): (&[f64], &[f64]),
    reduced: Map<String, Value>,
    sizes: Map<String, Value>,
) {
    r.insert("free_free_hz".into(), json!(sig_vec(free_free_hz)));
    r.insert(
        "fixed_interface_hz".into(),
        json!(sig_vec(fixed_interface_hz)),
    );
    r.insert("reduced_hz".into(), Value::Object(reduced));
    r.insert("basis_size".into(), Value::Object(sizes));
}
