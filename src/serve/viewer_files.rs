//! The embedded Rerun web viewer's files as the classroom serves them: the viewer's page made
//! to work offline (its links to Google's web fonts dropped: the viewer draws with its own
//! fonts), and each file gzip-compressed once at start, for browsers that accept it (the wasm:
//! 41.7 MB plain, ~14 MB gzipped, a third of the traffic per student).

use std::{collections::BTreeMap, io::Write as _};

use crate::{Result, error::ServeError};

/// One file of the viewer.
#[derive(Debug)]
pub struct ViewerFile {
    /// Its MIME type.
    pub content_type: &'static str,
    /// The bytes.
    pub plain: Vec<u8>,
    /// The bytes gzip-compressed.
    pub gzip: Vec<u8>,
}

/// The web viewer's files by URL path.
#[derive(Debug)]
pub struct ViewerFiles {
    files: BTreeMap<&'static str, ViewerFile>,
}

fn asset_error(what: &'static str) -> crate::Error {
    ServeError::Viewer { what, source: None }.into()
}

/// [`asset_error`] with the library's error behind it.
fn asset_error_from(
    what: &'static str,
    source: impl Into<Box<dyn std::error::Error + Send + Sync>>,
) -> crate::Error {
    ServeError::Viewer {
        what,
        source: Some(source.into()),
    }
    .into()
}

/// The viewer's page without anything it would fetch from the internet (the `<link>`s to
/// Google's fonts, preconnects and the stylesheet, cut out) and with its handle on `window`
/// from the start. Refuses a page that still names a font host afterwards, or that no longer
/// creates its handle where expected.
pub fn offline_index(html: &str) -> Result<String> {
    let mut out = html.to_string();
    while let Some(host) = out.find("fonts.g") {
        let start = out[..host]
            .rfind("<link")
            .ok_or_else(|| asset_error("a font host outside a <link> element"))?;
        let end = out[host..]
            .find("/>")
            .map(|e| host + e + 2)
            .ok_or_else(|| asset_error("an unclosed <link> element"))?;
        out.replace_range(start..end, "");
    }
    if out.contains("fonts.googleapis") || out.contains("fonts.gstatic") {
        return Err(asset_error("the page still links web fonts"));
    }
    // The viewer's handle as soon as it exists (the stock page sets `window._handle` only once
    // `start()` resolves, which a page streaming from a server never waits for): a test and a
    // teacher's console read the active recording and whether it panicked from it.
    // `on_app_started` then overwrites it with what `start()` resolves to, `undefined`: kept.
    const STARTED: &str = "window._handle = handle;";
    let at = out
        .find(STARTED)
        .ok_or_else(|| asset_error("the page no longer sets `window._handle`"))?;
    out.replace_range(
        at..at + STARTED.len(),
        "window._handle = handle || window._handle;",
    );
    const CREATE: &str = "let handle = new wasm_bindgen.WebHandle(options);";
    let at = out
        .find(CREATE)
        .ok_or_else(|| asset_error("the page no longer creates `WebHandle(options)`"))?;
    out.insert_str(at + CREATE.len(), " window._handle = handle;");
    Ok(out)
}

fn gzip(bytes: &[u8]) -> Result<Vec<u8>> {
    let mut gz = flate2::write::GzEncoder::new(
        Vec::with_capacity(bytes.len() / 3),
        flate2::Compression::new(6),
    );
    gz.write_all(bytes)
        .and_then(|_| gz.finish())
        .map_err(|e| asset_error_from("gzip", e))
}

impl ViewerFiles {
    /// The embedded viewer's files, the page made offline, each compressed (the files in
    /// parallel).
    pub fn load() -> Result<Self> {
        let data = re_web_viewer_server::WebViewerData::load(None)
            .map_err(|e| asset_error_from("its files do not load", e))?;
        let index = offline_index(
            std::str::from_utf8(data.index_html())
                .map_err(|e| asset_error_from("index.html is not UTF-8", e))?,
        )?;
        let sources: Vec<(&'static str, &'static str, Vec<u8>)> = vec![
            ("/", "text/html; charset=utf-8", index.into_bytes()),
            ("/favicon.ico", "image/x-icon", data.favicon().to_vec()),
            (
                "/apple-touch-icon.png",
                "image/png",
                data.apple_touch_icon().to_vec(),
            ),
            ("/sw.js", "text/javascript", data.sw_js().to_vec()),
            (
                "/re_viewer.js",
                "text/javascript",
                data.viewer_js().to_vec(),
            ),
            (
                "/re_viewer_bg.wasm",
                "application/wasm",
                data.viewer_wasm().to_vec(),
            ),
            (
                "/signed-in.html",
                "text/html; charset=utf-8",
                data.signed_in_html().to_vec(),
            ),
            (
                "/signed-out.html",
                "text/html; charset=utf-8",
                data.signed_out_html().to_vec(),
            ),
        ];
        let compressed: Vec<Result<(&'static str, ViewerFile)>> = std::thread::scope(|s| {
            let jobs: Vec<_> = sources
                .into_iter()
                .map(|(path, content_type, plain)| {
                    s.spawn(move || {
                        let gzip = gzip(&plain)?;
                        Ok((
                            path,
                            ViewerFile {
                                content_type,
                                plain,
                                gzip,
                            },
                        ))
                    })
                })
                .collect();
            jobs.into_iter()
                .map(|j| {
                    j.join()
                        .unwrap_or_else(|_| Err(asset_error("gzip panicked")))
                })
                .collect()
        });
        let mut files = BTreeMap::new();
        for c in compressed {
            let (path, file) = c?;
            files.insert(path, file);
        }
        Ok(Self { files })
    }

    /// The file at a URL path (`/index.html` is `/`), without its query.
    pub fn get(&self, path: &str) -> Option<&ViewerFile> {
        let path = path.split(['?', '#']).next().unwrap_or("/");
        let path = if path == "/index.html" { "/" } else { path };
        self.files.get(path)
    }

    /// Bytes of every file, plain and gzipped.
    pub fn sizes(&self) -> (usize, usize) {
        self.files
            .values()
            .fold((0, 0), |(p, g), f| (p + f.plain.len(), g + f.gzip.len()))
    }
}
