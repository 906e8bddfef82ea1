//! The matrix an error of the linear algebra names.

use std::fmt;

/// The matrix an error of the linear algebra names: what it is (`name`, as the code that
/// factors or solves it calls it), its part of a generalised eigenproblem's pencil, and where
/// several matrices share the name, whose it is (a body, a method) or where it was formed (a
/// frequency).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MatrixLabel {
    /// What the matrix is: "interior stiffness K_ii", "assembly", "Sturm shift K - σ'M".
    pub name: &'static str,
    /// The pencil's stiffness or mass, when `name` is the eigenproblem's.
    pub part: Option<PencilPart>,
    /// The body or method the matrix belongs to, or the frequency it was formed at.
    pub context: Option<LabelContext>,
}

/// One of the two matrices of a generalised eigenproblem $K\varphi = \lambda M\varphi$.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum PencilPart {
    Stiffness,
    Mass,
}

/// Whose a labelled matrix is, or where it was formed.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub enum LabelContext {
    /// The body (by its name) the matrix belongs to.
    Body(super::Name),
    /// The reduction method (by its id) the matrix belongs to.
    Method(&'static str),
    /// The frequency the matrix was formed at, Hz.
    AtHz(f64),
}

impl MatrixLabel {
    /// The label `name` with no part and no context.
    pub const fn of(name: &'static str) -> Self {
        Self {
            name,
            part: None,
            context: None,
        }
    }

    /// This label's eigenproblem's stiffness or mass.
    pub fn part(&self, part: PencilPart) -> Self {
        Self {
            part: Some(part),
            ..self.clone()
        }
    }

    /// This label, of a body.
    pub fn of_body(name: &'static str, body: impl Into<super::Name>) -> Self {
        Self {
            context: Some(LabelContext::Body(body.into())),
            ..Self::of(name)
        }
    }

    /// This label, of a reduction method (its id).
    pub fn of_method(name: &'static str, method: &'static str) -> Self {
        Self {
            context: Some(LabelContext::Method(method)),
            ..Self::of(name)
        }
    }

    /// This label, formed at a frequency (Hz).
    pub fn at_hz(name: &'static str, hz: f64) -> Self {
        Self {
            context: Some(LabelContext::AtHz(hz)),
            ..Self::of(name)
        }
    }
}

impl From<&'static str> for MatrixLabel {
    fn from(name: &'static str) -> Self {
        Self::of(name)
    }
}

impl fmt::Display for MatrixLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(LabelContext::Method(m)) = &self.context {
            write!(f, "{m} ")?;
        }
        f.write_str(self.name)?;
        match self.part {
            Some(PencilPart::Stiffness) => f.write_str(" stiffness")?,
            Some(PencilPart::Mass) => f.write_str(" mass")?,
            None => {}
        }
        match &self.context {
            Some(LabelContext::Body(body)) => write!(f, " of {body}"),
            Some(LabelContext::AtHz(hz)) => {
                write!(f, " at {hz} Hz", hz = crate::report::readable(hz, 5))
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_label_reads_as_the_sentences_it_replaced() {
        for (label, text) in [
            (
                MatrixLabel::of("interior stiffness K_ii"),
                "interior stiffness K_ii",
            ),
            (
                MatrixLabel::of("assembly").part(PencilPart::Mass),
                "assembly mass",
            ),
            (
                MatrixLabel::of_body("modal mass Ψ^T M Ψ", "slab"),
                "modal mass Ψ^T M Ψ of slab",
            ),
            (
                MatrixLabel::of_method("static saddle-point system", "cb"),
                "cb static saddle-point system",
            ),
            (
                MatrixLabel::at_hz("K - ω²M", 1234.5),
                "K - ω²M at 1234.5 Hz",
            ),
        ] {
            assert_eq!(label.to_string(), text);
        }
    }
}
