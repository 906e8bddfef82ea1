//! The classroom server's parts that run without a network (feature `serve`): the students' URL,
//! the teacher's control page and its one-at-a-time publisher, and the web viewer's
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

mod control {
    use std::sync::{
        Arc, Mutex,
        mpsc::{self, Receiver},
    };
    use std::time::Duration;

    use flexmodes::serve::{ControlPage, PublishJob, PublishStatus, Publisher, html_escape};

    const TOKEN: &str = "0123456789abcdef0123456789abcdef";

    /// A page whose requests are recorded instead of published.
    fn page() -> (ControlPage, Arc<Mutex<Vec<Vec<String>>>>) {
        let asked = Arc::new(Mutex::new(Vec::new()));
        let seen = asked.clone();
        let page = ControlPage::new(
            TOKEN.into(),
            vec![("slab-modes".into(), "the <slab>".into())],
            Box::new(move |words: &[String]| {
                if words[0] != "slab-modes" {
                    return Err(format!("unknown scene `{}`", words[0]));
                }
                seen.lock().unwrap().push(words.to_vec());
                Ok(format!("queued: {}", words.join(" ")))
            }),
            Box::new(|| "idle".into()),
        );
        (page, asked)
    }

    #[test]
    fn without_the_token_nothing_is_shown_or_changed() {
        let (page, asked) = page();
        for (post, query, body) in [
            (false, "", ""),
            (false, "token=0123456789abcdef0123456789abcdee", ""),
            (false, "token=0123", ""),
            (true, "", "scene=slab-modes&method=cb"),
            (true, &format!("token={TOKEN}")[..], "scene=slab-modes"),
        ] {
            let answer = page.answer(post, query, body);
            assert_eq!(answer.status, 403, "{post} {query} {body}");
            assert!(!answer.html.contains("<form"), "{}", answer.html);
            assert!(!answer.html.contains(TOKEN));
        }
        assert!(asked.lock().unwrap().is_empty());
    }

    #[test]
    fn the_form_becomes_the_show_words_and_errors_are_named() {
        let (page, asked) = page();
        let form = page.answer(false, &format!("token={TOKEN}"), "");
        assert_eq!(form.status, 200);
        assert!(form.html.contains("the &lt;slab&gt;"), "{}", form.html);
        let ok = page.answer(
            true,
            "",
            &format!("token={TOKEN}&scene=slab-modes&method=cb%2Cmc&modes=4&axes=&body="),
        );
        assert_eq!(ok.status, 200);
        assert!(
            ok.html
                .contains("queued: slab-modes --method cb,mc --modes 4")
        );
        // The form comes back filled in with what was submitted.
        assert!(ok.html.contains(r#"<option value="slab-modes" selected>"#));
        assert!(ok.html.contains(r#"value="cb,mc">"#), "{}", ok.html);
        assert_eq!(
            asked.lock().unwrap().as_slice(),
            [["slab-modes", "--method", "cb,mc", "--modes", "4"].map(String::from)]
        );
        for (body, says) in [
            ("scene=nope", "unknown scene `nope`"),
            ("scene=slab-modes&colour=red", "unknown field `colour`"),
            ("method=cb", "no scene chosen"),
        ] {
            let answer = page.answer(true, "", &format!("token={TOKEN}&{body}"));
            assert_eq!(answer.status, 400, "{body}");
            assert!(answer.html.contains(&html_escape(says)), "{}", answer.html);
        }
        assert_eq!(asked.lock().unwrap().len(), 1);
    }

    fn job(label: &str, gate: Option<Receiver<()>>) -> PublishJob {
        PublishJob {
            label: label.into(),
            compute: Box::new(move || {
                if let Some(gate) = gate {
                    gate.recv().unwrap();
                }
                Ok(Vec::new())
            }),
        }
    }

    #[test]
    fn a_request_replaces_the_waiting_one_and_never_stacks() {
        let published = Arc::new(Mutex::new(0usize));
        let count = published.clone();
        let publisher = Publisher::start(move |_| *count.lock().unwrap() += 1, |_| {});
        let (open, gate) = mpsc::channel();
        assert_eq!(publisher.submit(job("first", Some(gate))), None);
        // The first computes (held at its gate); the next ones wait, each replacing the last.
        let computing = (0..200).any(|_| {
            std::thread::sleep(Duration::from_millis(10));
            publisher.status() == PublishStatus::Computing("first".into())
        });
        assert!(computing, "{:?}", publisher.status());
        assert_eq!(publisher.submit(job("second", None)), None);
        assert_eq!(publisher.submit(job("third", None)), Some("second".into()));
        assert_eq!(publisher.queued(), Some("third".into()));
        open.send(()).unwrap();
        let done = (0..200).any(|_| {
            std::thread::sleep(Duration::from_millis(10));
            publisher.status()
                == PublishStatus::Published {
                    label: "third".into(),
                    messages: 0,
                }
        });
        assert!(done, "{:?}", publisher.status());
        assert_eq!(
            *published.lock().unwrap(),
            2,
            "first and third, never second"
        );
        assert_eq!(publisher.queued(), None);
    }
}
