//! The classroom server's pure parts (feature `serve`): the students' URL and the web viewer's
//! page made to work offline. Built beside the explorer's tests
//! (`cargo test --features gui,serve --test gui --test serve`), so CI compiles no second
//! test harness of the whole crate for them; the server itself is checked in headless
//! Chromium by `assets/serve/check_serve.py`.
#![cfg(feature = "serve")]

use flexmodes::serve::{offline_index, page_url};

#[test]
fn the_data_address_is_one_query_value() {
    let u = page_url(
        "127.0.0.2".parse().unwrap(),
        9090,
        "rerun+http://127.0.0.2:9876/proxy",
        Some("light"),
    );
    assert_eq!(
        u,
        "http://127.0.0.2:9090/?url=rerun%2Bhttp%3A%2F%2F127.0.0.2%3A9876%2Fproxy\
         &renderer=webgl&theme=light"
    );
}

#[test]
fn the_page_loses_its_font_links_and_nothing_else() {
    let page = r#"<head>
    <link rel="icon" href="favicon.ico" />
    <link rel="preconnect" href="https://fonts.googleapis.com" />
    <link rel="preconnect" href="https://fonts.gstatic.com" crossorigin />
    <link
      href="https://fonts.googleapis.com/css2?family=Inter:wght@100;500&display=swap"
      rel="stylesheet"
    />
    <title>Rerun Viewer</title>
        let handle = new wasm_bindgen.WebHandle(options);
        function on_app_started(handle) { window._handle = handle; }"#;
    let out = offline_index(page).unwrap();
    assert!(out.contains("WebHandle(options); window._handle = handle;"));
    assert!(out.contains("{ window._handle = handle || window._handle; }"));
    assert!(!out.contains("fonts."), "{out}");
    assert!(out.contains(r#"<link rel="icon" href="favicon.ico" />"#));
    assert!(out.contains("<title>Rerun Viewer</title>"));
}
