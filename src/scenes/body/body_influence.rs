//! The `modes` scene's influence table: which of a body's free-free modes carry most across
//! its interfaces (Gregory's coefficients, Spanos–Tsuha Eq. 44), beside their order by
//! frequency.

use serde_json::{Value, json};

use crate::{
    models::{BALANCED_MODES_PER_VECTOR, BALANCED_ZETA},
    reduction::ModalInfluence,
    report::{Cell, Table, sig},
};

/// Modes ranked for `kept` kept modes: as many as balanced truncation balances for `kept`
/// vectors, so the solve is shared.
pub fn influence_count(kept: usize) -> usize {
    (BALANCED_MODES_PER_VECTOR * kept).max(kept + 8)
}

/// Modes listed in the table (all are in the JSON).
const LISTED: usize = 12;

/// The table, its JSON and a sentence for the text: the body's lowest elastic modes (as many
/// as balanced truncation balances for `kept` vectors, so the solve is shared) ranked by
/// influence from the interface loads at ζ = [`BALANCED_ZETA`].
pub fn influence_table(
    (hz, influence): &(Vec<f64>, ModalInfluence),
    count: usize,
    kept: usize,
) -> (Table, Value, String) {
    let ranking = influence.ranking();
    let top = influence.sigma[ranking[0]];
    let mut table = Table::new(&["rank", "free-free mode", "Hz", "influence / largest"]);
    for (rank, &i) in ranking.iter().take(LISTED).enumerate() {
        let relative = influence.sigma[i] / top;
        table.push(vec![
            Cell::number((rank + 1) as f64, format!("{}", rank + 1)),
            Cell::number((i + 1) as f64, format!("{}", i + 1)),
            Cell::number(hz[i], format!("{:.6}", hz[i])),
            Cell::number(
                relative,
                flexmodes_core::report::readable(relative, 3).to_string(),
            ),
        ]);
    }
    let lowest_in_top = ranking.iter().take(kept).filter(|&&i| i < kept).count();
    let json = json!({
        "zeta": BALANCED_ZETA,
        "hz": hz.iter().map(|&f| sig(f)).collect::<Vec<_>>(),
        "sigma": influence.sigma.iter().map(|&s| sig(s)).collect::<Vec<_>>(),
        "ranking": ranking.iter().map(|i| i + 1).collect::<Vec<_>>(),
        "closeness": sig(influence.closeness),
    });
    let text = format!(
        "Modal influence across the interfaces (Gregory's coefficient, Spanos–Tsuha Eq. 44, \
         of the {count} lowest elastic free-free modes from the interface loads to their \
         work-conjugate displacements, ζ = {BALANCED_ZETA}; Eq. 45's closeness {:.2}, the \
         approximation holding where it is far below 1): {lowest_in_top} of the {kept} most influential \
         modes are among the {kept} lowest.",
        influence.closeness
    );
    (table, json, text)
}
