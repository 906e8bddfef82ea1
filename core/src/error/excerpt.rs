//! Text an error quotes from a file or a command line.

/// Text an error quotes from what a user gave (a field of a matrix file's line, a token on
/// the command line, the last line a peer wrote): at most [`Excerpt::MAX_CHARS`]
/// characters, so a line of a binary file read as text, or a megabyte without a newline,
/// makes a one-line message. Longer text keeps its first characters and ends in `…`.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Excerpt(Box<str>);

impl Excerpt {
    /// The most characters an excerpt keeps (the cut one, `…`, included).
    pub const MAX_CHARS: usize = 80;
}

impl From<&str> for Excerpt {
    fn from(text: &str) -> Self {
        // A character at index MAX_CHARS: the text is longer than MAX_CHARS, and keeps the
        // MAX_CHARS - 1 characters before the one at MAX_CHARS - 1.
        let mut starts = text.char_indices().map(|(i, _)| i);
        match (starts.nth(Self::MAX_CHARS - 1), starts.next()) {
            (Some(end), Some(_)) => {
                let mut cut = String::with_capacity(end + '…'.len_utf8());
                cut.push_str(&text[..end]);
                cut.push('…');
                Self(cut.into())
            }
            _ => Self(text.into()),
        }
    }
}

super::str_newtype::str_newtype!(Excerpt);

#[cfg(test)]
mod tests {
    use super::*;

    /// Text up to the limit is kept whole; longer text keeps MAX_CHARS - 1 characters and
    /// `…`, cut between characters (multi-byte ones included), never inside one.
    #[test]
    fn an_excerpt_keeps_short_text_and_cuts_long_text_between_characters() {
        for ch in ['a', 'é', '∞', '𝄞'] {
            for len in [0, 1, Excerpt::MAX_CHARS - 1, Excerpt::MAX_CHARS] {
                let text: String = std::iter::repeat_n(ch, len).collect();
                let e = Excerpt::from(text.as_str());
                assert_eq!(e.as_str(), text, "{ch} × {len}");
            }
            for len in [Excerpt::MAX_CHARS + 1, 10 * Excerpt::MAX_CHARS, 100_000] {
                let text: String = std::iter::repeat_n(ch, len).collect();
                let e = Excerpt::from(text.as_str());
                assert_eq!(e.chars().count(), Excerpt::MAX_CHARS, "{ch} × {len}");
                assert!(e.ends_with('…'));
                let kept: String = std::iter::repeat_n(ch, Excerpt::MAX_CHARS - 1).collect();
                assert!(e.starts_with(&kept));
            }
        }
    }
}
