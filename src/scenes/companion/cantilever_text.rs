//! The cantilever variants' text: what the scene shows and the claims it checks.

use crate::{
    analysis::{MAC_ACCURATE, ModePair},
    models::{
        BAND_HZ, CANTILEVER_METHODS as AVAILABLE, CantileverStudy,
        WITTEVEEN_INTEREST_HZ as INTEREST_HZ,
    },
    reduction::Method,
};

/// The scene's text above its tables.
pub(super) fn scene_text(study: &CantileverStudy, tables: &str) -> String {
    let params = &study.params;
    format!(
        "# cantilever-variants\n\n\
         Witteveen, *World J. Mech.* 2 (2012) §4: a beam structure clamped at the origin (N–mm–t \
         units, E = 210 000 N/mm², G = 80 000 N/mm², ρ = 7.8e-9 t/mm³), 12-DOF Euler–Bernoulli \
         frame elements of ≈ {el} mm, lumped mass, {dofs} DOF. His Fig. 1 is missing, so the \
         geometry is ours: a **bottom section** of 100 × 10 mm (100 mm across, y), \
         {l1:.0} mm along x; an **overhanging beam** of 100 × 5 mm, {l2:.0} mm long, rooted at \
         {root:.0} % of the bottom section and pointing {dir} (100 mm side {wide}). \
         **A** is the free end of the bottom section (six I/O DOF), **B** its middle (z). The \
         overhang is the part no I/O DOF sees. Calibrated against the printed frequencies by a \
         grid search over lengths, root and orientation (table below).\n\n\
         **Bases** (14 vectors each, built once on variant 1): **CB** = 7 constraint modes of \
         the I/O DOF + 7 fixed-interface modes; **MM** = block Krylov about s₀ = 0, \
         [K⁻¹B₁, K⁻¹MK⁻¹B₁] by block Arnoldi in the M-inner product with re-orthogonalisation \
         ({deflated} columns deflated); **BT** = the 14 dominant eigenvectors (Euclidean) of the \
         position block of the controllability gramian with D = 1e-4·K, computed exactly in \
         modal coordinates. We use this second-order form because it is what Witteveen ran \
         (SBPOR): a Ritz basis that the changed supports can be applied to; first-order \
         balancing of states (Spanos–Tsuha) gives no displacement basis. \
         **Variants** are applied to the reduced models only: held DOF by the null space of \
         their rows of V, the 250 kg added as m·v·v^T, v the row of V at A's x.\n\n\
         **Measures**: static error = max over the bottom section of |ũ − u| in the direction \
         of interest over max |u|; modes of the full model up to {band} Hz paired with the \
         reduced mode of best MAC (Eq. 43, on all DOF: mm and rad together, as the gramian \
         sees them); frequency error (f̃ − f)/f (Eq. 42); ✗ marks MAC < 0.95. The charts \
         \"Δf %\" and \"MAC\" show them by mode number, one bar per method in the methods' \
         colours: CB blue, MM olive, BT brown (no legend: wherever it sat, it covered \
         bars).\n\n\
         {tables}",
        el = params.element_length,
        dofs = study.frame.model.dof_count(),
        deflated = study.deflated,
        l1 = params.bottom_length,
        l2 = params.overhang_length,
        root = 100.0 * params.root_fraction,
        dir = match params.direction {
            crate::fem::OverhangDirection::Sideways => "sideways (+y)",
            crate::fem::OverhangDirection::Upwards => "upwards (+z)",
        },
        wide = if params.wide_along_x {
            "along x"
        } else {
            "across x"
        },
        band = BAND_HZ,
    )
}

/// The paper's conclusions, each checked on our numbers.
pub(super) fn claims_text(study: &CantileverStudy) -> String {
    let mut out = statics_claims(study);
    out.push_str(&modal_claims(study));
    out
}

fn verdict(ok: bool) -> &'static str {
    if ok { "**holds**" } else { "**does not hold**" }
}

/// The variants' mode pairs, per method.
type VariantPairs<'a> = Vec<&'a Vec<(Method, Vec<ModePair>)>>;

/// Statics: CB and MM exact, BT not.
fn statics_claims(study: &CantileverStudy) -> String {
    let mut out = String::new();
    let static_of = |case: &str, m: Method| {
        study
            .statics
            .iter()
            .find(|c| c.id == case)
            .and_then(|c| c.error(m))
    };
    for (case, text) in [
        ("lc1", "LC 1: CB and MM accurate, BT not"),
        ("lc2", "LC 2: CB and MM exact, BT highly inaccurate"),
        (
            "v2",
            "variant 2 statics: CB and MM accurate, BT significant errors",
        ),
    ] {
        if let (Some(cb), Some(mm), Some(bt)) = (
            static_of(case, Method::CraigBampton),
            static_of(case, Method::MomentMatching),
            static_of(case, Method::BalancedTruncation),
        ) {
            out.push_str(&format!(
                "- {text}: CB {cb}, MM {mm}, BT {bt} — {}.\n",
                verdict(cb < 1e-8 && mm < 1e-8 && bt > 0.01),
                cb = flexmodes_core::report::readable(cb, 2),
                mm = flexmodes_core::report::readable(mm, 2),
                bt = flexmodes_core::report::readable(bt, 2)
            ));
        }
    }
    out
}

/// The worst frequency error below the band of interest of method `m` on variant `v`, and
/// its mode (1-based).
fn worst_below(pairs: &VariantPairs<'_>, v: usize, m: Method) -> Option<(usize, f64)> {
    let (_, p) = pairs.get(v)?.iter().find(|(mm, _)| *mm == m)?;
    p.iter()
        .enumerate()
        .filter(|(_, q)| q.full_hz <= INTEREST_HZ)
        .map(|(k, q)| (k + 1, q.frequency_error.abs()))
        .fold(None, |b: Option<(usize, f64)>, x| match b {
            Some(y) if y.1 >= x.1 => Some(y),
            _ => Some(x),
        })
}

/// The modes of variant `v` that method `m` does not reproduce (MAC below accurate).
fn missed(pairs: &VariantPairs<'_>, v: usize, m: Method) -> Vec<String> {
    pairs
        .get(v)
        .and_then(|ms| ms.iter().find(|(mm, _)| *mm == m))
        .map(|(_, p)| {
            p.iter()
                .enumerate()
                .filter(|(_, q)| q.mac < MAC_ACCURATE)
                .map(|(k, q)| format!("{} ({:.1} Hz, MAC {:.2})", k + 1, q.full_hz, q.mac))
                .collect()
        })
        .unwrap_or_default()
}

/// The modal claims: each variant's worst errors and missed modes, and the paper's named
/// verdicts.
fn modal_claims(study: &CantileverStudy) -> String {
    let pairs: VariantPairs<'_> = study.variants.iter().map(|v| &v.pairs).collect();
    let full_hz: Vec<&Vec<f64>> = study.variants.iter().map(|v| &v.band_hz).collect();
    let worst_below = |v: usize, m: Method| worst_below(&pairs, v, m);
    let missed = |v: usize, m: Method| missed(&pairs, v, m);
    let mut out = String::new();
    for v in 0..pairs.len() {
        let name = v + 1;
        let mut parts = Vec::new();
        for m in AVAILABLE {
            if let Some((k, e)) = worst_below(v, m) {
                let miss = missed(v, m);
                parts.push(format!(
                    "{} worst {:.2} % (mode {k}){}",
                    m.id().to_uppercase(),
                    100.0 * e,
                    if miss.is_empty() {
                        String::new()
                    } else {
                        format!(", MAC < 0.95 on mode {}", miss.join(", "))
                    }
                ));
            }
        }
        out.push_str(&format!(
            "- Variant {name} up to {INTEREST_HZ} Hz ({} modes in the band up to {BAND_HZ} Hz): \
             {}.\n",
            full_hz.get(v).map(|h| h.len()).unwrap_or(0),
            parts.join("; ")
        ));
    }
    // Named claims.
    if let (Some(cb), Some(mm), Some(bt)) = (
        worst_below(0, Method::CraigBampton),
        worst_below(0, Method::MomentMatching),
        worst_below(0, Method::BalancedTruncation),
    ) {
        out.push_str(&format!(
            "- \"Variant 1: BT gives the most accurate results up to 200 Hz\": {}; \"MM has a \
             considerable error on one mode\": its worst is {:.2} % on mode {}.\n",
            verdict(bt.1 <= cb.1 && bt.1 <= mm.1),
            100.0 * mm.1,
            mm.0
        ));
    }
    if let (Some(cb), Some(mm), Some(bt)) = (
        worst_below(1, Method::CraigBampton),
        worst_below(1, Method::MomentMatching),
        worst_below(1, Method::BalancedTruncation),
    ) {
        out.push_str(&format!(
            "- \"Variant 2: CB excellent, MM worse, BT worst\": CB {:.2} %, MM {:.2} %, BT \
             {:.2} % — {}.\n",
            100.0 * cb.1,
            100.0 * mm.1,
            100.0 * bt.1,
            verdict(cb.1 < 0.01 && cb.1 <= mm.1 && mm.1 <= bt.1)
        ));
    }
    let bt_missed: Vec<String> = (0..pairs.len())
        .map(|v| {
            let m = missed(v, Method::BalancedTruncation);
            format!(
                "variant {}: {}",
                v + 1,
                if m.is_empty() {
                    "none".into()
                } else {
                    m.join(", ")
                }
            )
        })
        .collect();
    out.push_str(&format!(
        "- \"BT misses modes the I/O DOF do not see (bottom torsion, the 145 Hz mode)\": BT's \
         modes with MAC < 0.95 — {}.\n",
        bt_missed.join("; ")
    ));
    out
}
