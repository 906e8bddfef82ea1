//! The teacher's control page, `/control`: the explorer's controls (scene, methods, modes,
//! boundary, axes, integrator, refine, end time, body) as an HTML form. Only a request that
//! carries the server's token is answered with the form or changes what the class sees; any
//! other gets 403 and changes nothing. A request that does not parse, or names an unknown
//! scene, is answered with the error by name and changes nothing.

use std::fmt::Write as _;

use crate::scenes::{self, SceneOption};

/// The form's fields beside the scene, each passed on as the command-line option of the same
/// name; the form shows each option's hint and the scenes that take it, from the scenes'
/// table.
pub const CONTROL_FIELDS: [SceneOption; 8] = [
    SceneOption::Method,
    SceneOption::Modes,
    SceneOption::Boundary,
    SceneOption::Axes,
    SceneOption::Integrator,
    SceneOption::Refine,
    SceneOption::EndTime,
    SceneOption::Body,
];

/// A field's name in the form: its option without the dashes (`end-time`).
fn field_name(option: SceneOption) -> &'static str {
    option.flag().trim_start_matches("--")
}

/// Largest form body read, bytes.
pub const MAX_CONTROL_BODY: usize = 16 * 1024;

/// How a request for the control page was answered.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ControlAnswer {
    /// HTTP status: 200, 400 (a request that does not parse), 403 (no or a wrong token), 405,
    /// 413 (a body over [`MAX_CONTROL_BODY`]).
    pub status: u16,
    /// The HTML page.
    pub html: String,
}

/// Turns a teacher's request (`show` words: the scene, then options) into a queued recording,
/// or says why not; called only for requests that carry the token.
pub type ControlApply = dyn Fn(&[String]) -> Result<String, String> + Send + Sync;

/// The control page of one server.
pub struct ControlPage {
    token: String,
    scenes: Vec<(String, String)>,
    apply: Box<ControlApply>,
    status: Box<dyn Fn() -> String + Send + Sync>,
}

/// A new random token: 128 bits from the operating system, as 32 hexadecimal digits.
pub fn new_control_token() -> std::io::Result<String> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(std::io::Error::other)?;
    Ok(bytes.iter().fold(String::with_capacity(32), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    }))
}

/// `&`, `<`, `>`, `"` and `'` escaped for HTML text and attribute values.
pub fn html_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Compares without stopping at the first difference.
fn same_token(given: &str, token: &str) -> bool {
    given.len() == token.len()
        && given
            .bytes()
            .zip(token.bytes())
            .fold(0u8, |acc, (a, b)| acc | (a ^ b))
            == 0
}

impl ControlPage {
    /// The page for `token`, offering `scenes` (id, summary); `apply` queues a request,
    /// `status` says what was published last.
    pub fn new(
        token: String,
        scenes: Vec<(String, String)>,
        apply: Box<ControlApply>,
        status: Box<dyn Fn() -> String + Send + Sync>,
    ) -> Self {
        Self {
            token,
            scenes,
            apply,
            status,
        }
    }

    /// Answers `GET /control?token=…` with the form and `POST /control` (a form body with the
    /// token) by queuing the request; `query` is the URL's query string, `body` the form body.
    pub fn answer(&self, post: bool, query: &str, body: &str) -> ControlAnswer {
        let fields: Vec<(String, String)> =
            form_urlencoded::parse(if post { body } else { query }.as_bytes())
                .map(|(k, v)| (k.into_owned(), v.into_owned()))
                .collect();
        let token_given = fields
            .iter()
            .find(|(k, _)| k == "token")
            .map(|(_, v)| v.as_str());
        if !token_given.is_some_and(|t| same_token(t, &self.token)) {
            return ControlAnswer {
                status: 403,
                html: page(
                    "forbidden",
                    "<p class=\"error\">forbidden: the control page needs the token printed in \
                     the teacher's terminal (or given with <code>--control-token</code>). \
                     Nothing was changed.</p>",
                ),
            };
        }
        if !post {
            return self.form(200, "", &[]);
        }
        match self.words(&fields) {
            Err(e) => self.form(
                400,
                &format!("<p class=\"error\">{}</p>", html_escape(&e)),
                &fields,
            ),
            Ok(words) => match (self.apply)(&words) {
                Ok(done) => self.form(
                    200,
                    &format!("<p class=\"ok\">{}</p>", html_escape(&done)),
                    &fields,
                ),
                Err(e) => self.form(
                    400,
                    &format!("<p class=\"error\">{}</p>", html_escape(&e)),
                    &fields,
                ),
            },
        }
    }

    /// The `show` words of a submitted form: the scene, then `--FIELD VALUE` for each field
    /// filled in; an unknown field or a missing scene is named.
    fn words(&self, fields: &[(String, String)]) -> Result<Vec<String>, String> {
        let mut scene = None;
        let mut words = Vec::new();
        for (k, v) in fields {
            let v = v.trim();
            match k.as_str() {
                "token" => {}
                "scene" => scene = Some(v.to_string()),
                field if CONTROL_FIELDS.iter().any(|&o| field_name(o) == field) => {
                    if !v.is_empty() {
                        words.push(format!("--{field}"));
                        words.push(v.to_string());
                    }
                }
                other => {
                    let known: Vec<&str> = CONTROL_FIELDS.map(field_name).to_vec();
                    return Err(format!(
                        "unknown field `{other}` (the form has scene, {})",
                        known.join(", ")
                    ));
                }
            }
        }
        match scene {
            Some(s) if !s.is_empty() => {
                words.insert(0, s);
                Ok(words)
            }
            _ => Err("no scene chosen".into()),
        }
    }

    /// The form, filled in with the request just submitted (`submitted`), so the teacher
    /// changes one control at a time.
    fn form(&self, status: u16, message: &str, submitted: &[(String, String)]) -> ControlAnswer {
        let value = |name: &str| {
            submitted
                .iter()
                .find(|(k, _)| k == name)
                .map_or("", |(_, v)| v.as_str())
        };
        let mut html = String::new();
        let _ = write!(
            html,
            "<p>Now: {}</p>{message}<form method=\"post\" action=\"/control\">\
             <input type=\"hidden\" name=\"token\" value=\"{}\">\
             <label>scene <select name=\"scene\">",
            html_escape(&(self.status)()),
            html_escape(&self.token)
        );
        for (id, summary) in &self.scenes {
            let selected = if value("scene") == id {
                " selected"
            } else {
                ""
            };
            let _ = write!(
                html,
                "<option value=\"{0}\"{selected}>{0} — {1}</option>",
                html_escape(id),
                html_escape(summary)
            );
        }
        html.push_str("</select></label>");
        for option in CONTROL_FIELDS {
            let field = field_name(option);
            let takers: Vec<&str> = scenes::all()
                .iter()
                .filter(|s| option.offered_by(&s.info.controls))
                .map(|s| s.id.as_str())
                .collect();
            let _ = write!(
                html,
                "<label title=\"taken by {}\">{field} <input name=\"{field}\" placeholder=\"{}\" \
                 value=\"{}\"></label>",
                html_escape(&takers.join(", ")),
                html_escape(&option.hint()),
                html_escape(value(field))
            );
        }
        html.push_str("<button type=\"submit\">show to the class</button></form>");
        ControlAnswer {
            status,
            html: page("flexmodes: the teacher's controls", &html),
        }
    }
}

/// A whole page around `body`.
fn page(title: &str, body: &str) -> String {
    format!(
        "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\"><title>{0}</title><style>\
         body{{font-family:sans-serif;max-width:44rem;margin:2rem auto;padding:0 1rem}}\
         label{{display:block;margin:.5rem 0}}input,select{{width:100%;padding:.3rem}}\
         .error{{color:#b00020}}.ok{{color:#1b5e20}}button{{margin-top:1rem;padding:.5rem 1rem}}\
         </style></head><body><h1>{0}</h1>{1}</body></html>",
        html_escape(title),
        body
    )
}
