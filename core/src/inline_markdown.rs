//! The inline markdown of a report's text lines (`code`, **bold**, a leading `- ` bullet, a
//! `#` heading), cut into styled spans, so a panel that draws text itself (the explorer's side
//! panel) shows the text, not its markup.

/// How a span is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpanStyle {
    /// Body text.
    Plain,
    /// `code`: monospace.
    Code,
    /// **strong**.
    Strong,
}

/// The spans of one line, markup removed: a leading `- ` or `* ` becomes `• `; an unmatched
/// marker stays as text.
pub fn inline_spans(line: &str) -> Vec<(String, SpanStyle)> {
    // A heading (`## Mode sets`) is one strong span, its hashes gone.
    let hashes = line.chars().take_while(|&c| c == '#').count();
    if (1..=6).contains(&hashes)
        && let Some(title) = line[hashes..].strip_prefix(' ')
    {
        let title = title.replace("**", "").replace('`', "");
        return vec![(title.trim().to_string(), SpanStyle::Strong)];
    }
    let line = match line.strip_prefix("- ").or_else(|| line.strip_prefix("* ")) {
        Some(rest) => format!("• {rest}"),
        None => line.to_string(),
    };
    let mut spans: Vec<(String, SpanStyle)> = Vec::new();
    let mut push = |text: &str, style: SpanStyle| {
        if !text.is_empty() {
            spans.push((text.to_string(), style));
        }
    };
    let mut rest = line.as_str();
    while !rest.is_empty() {
        let code = rest.find('`');
        let strong = rest.find("**");
        let (at, marker, style) = match (code, strong) {
            (Some(c), Some(s)) if s < c => (s, "**", SpanStyle::Strong),
            (Some(c), _) => (c, "`", SpanStyle::Code),
            (None, Some(s)) => (s, "**", SpanStyle::Strong),
            (None, None) => {
                push(rest, SpanStyle::Plain);
                break;
            }
        };
        let inner = &rest[at + marker.len()..];
        match inner.find(marker) {
            Some(end) => {
                push(&rest[..at], SpanStyle::Plain);
                push(&inner[..end], style);
                rest = &inner[end + marker.len()..];
            }
            None => {
                push(rest, SpanStyle::Plain);
                break;
            }
        }
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_goes_and_its_text_stays() {
        use SpanStyle::*;
        assert_eq!(
            inline_spans("Body `l_bracket` (**1314** DOF)"),
            vec![
                ("Body ".into(), Plain),
                ("l_bracket".into(), Code),
                (" (".into(), Plain),
                ("1314".into(), Strong),
                (" DOF)".into(), Plain),
            ]
        );
        assert_eq!(inline_spans("- one"), vec![("• one".into(), Plain)]);
        assert_eq!(inline_spans("a ` b"), vec![("a ` b".into(), Plain)]);
        for heading in ["# Mode sets", "## Mode sets", "### **Mode** sets"] {
            assert_eq!(inline_spans(heading), vec![("Mode sets".into(), Strong)]);
        }
        // Not a heading: no space after the hashes, or more than six.
        assert_eq!(inline_spans("#5 node"), vec![("#5 node".into(), Plain)]);
        assert_eq!(inline_spans("####### x"), vec![("####### x".into(), Plain)]);
    }
}
