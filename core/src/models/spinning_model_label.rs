//! The names of the spinning beam's models in tables and charts: `NR`, `CB 6`, and whether
//! the dynamic stiffening is in.

/// `NR` for the full beam (`modes` 0), `CB n` for Craig–Bampton with n modes.
pub fn model_name(modes: usize) -> String {
    if modes == 0 {
        "NR".to_string()
    } else {
        format!("CB {modes}")
    }
}

/// The model's label: [`model_name`], and `, no stiffening` without it.
pub fn model_label(modes: usize, stiffening: bool) -> String {
    let model = model_name(modes);
    if stiffening {
        model
    } else {
        format!("{model}, no stiffening")
    }
}
