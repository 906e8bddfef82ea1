//! The classroom's web server: the viewer's files over HTTP, gzip-compressed where the browser
//! accepts it, and the teacher's control page ([`super::ControlPage`]) at `/control`, on a few
//! threads; everything else is 404. No request leaves the machine's own files: the page is the
//! offline one of [`super::ViewerFiles`].

use std::{net::IpAddr, sync::Arc, thread::JoinHandle};

use super::{ControlPage, MAX_CONTROL_BODY, ViewerFiles};
use crate::{Result, error::ServeError};

/// Request threads: a class loads the 14 MB viewer once per student, mostly at the start.
const THREADS: usize = 4;

/// A running web server.
pub struct WebServer {
    server: Arc<tiny_http::Server>,
    threads: Vec<JoinHandle<()>>,
}

/// Binds `address:port` first by itself, so a port in use is named as such.
pub fn check_port(
    address: IpAddr,
    port: u16,
    what: &'static str,
    option: &'static str,
) -> Result<()> {
    match std::net::TcpListener::bind((address, port)) {
        Ok(_) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::AddrInUse => Err(ServeError::PortInUse {
            address,
            port,
            what,
            option,
        }
        .into()),
        Err(e) => Err(ServeError::Bind {
            address,
            port: Some(port),
            source: Box::new(e),
        }
        .into()),
    }
}

fn header(name: &str, value: &str) -> tiny_http::Header {
    tiny_http::Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("ASCII header")
}

/// Answers a request for `/control` (a GET shows the form, a POST submits it).
fn respond_control(control: &ControlPage, mut request: tiny_http::Request) {
    let query = request
        .url()
        .split_once('?')
        .map_or(String::new(), |(_, q)| q.to_string());
    let answer = match request.method() {
        tiny_http::Method::Get => control.answer(false, &query, ""),
        tiny_http::Method::Post => {
            let mut body = String::new();
            let read = std::io::Read::read_to_string(
                &mut std::io::Read::take(request.as_reader(), MAX_CONTROL_BODY as u64 + 1),
                &mut body,
            );
            if read.is_err() || body.len() > MAX_CONTROL_BODY {
                super::ControlAnswer {
                    status: 413,
                    html: format!("a form of at most {MAX_CONTROL_BODY} bytes of UTF-8"),
                }
            } else {
                control.answer(true, &query, &body)
            }
        }
        _ => super::ControlAnswer {
            status: 405,
            html: "GET or POST".into(),
        },
    };
    let response = tiny_http::Response::from_string(answer.html)
        .with_status_code(answer.status)
        .with_header(header("Content-Type", "text/html; charset=utf-8"))
        .with_header(header("Cache-Control", "no-store"));
    let _ = request.respond(response);
}

fn respond(files: &ViewerFiles, control: Option<&ControlPage>, request: tiny_http::Request) {
    let path = request.url().split('?').next().unwrap_or("");
    if let Some(control) = control
        && (path == "/control" || path == "/control/")
    {
        return respond_control(control, request);
    }
    let accepts_gzip = request.headers().iter().any(|h| {
        h.field.equiv("Accept-Encoding") && h.value.as_str().to_ascii_lowercase().contains("gzip")
    });
    let response = match (request.method(), files.get(request.url())) {
        (tiny_http::Method::Get | tiny_http::Method::Head, Some(file)) => {
            let body = if accepts_gzip {
                &file.gzip
            } else {
                &file.plain
            };
            let mut r = tiny_http::Response::from_data(body.clone())
                .with_header(header("Content-Type", file.content_type))
                .with_header(header("Cache-Control", "no-cache"));
            if accepts_gzip {
                r = r.with_header(header("Content-Encoding", "gzip"));
            }
            r
        }
        _ => tiny_http::Response::from_string("not found").with_status_code(404),
    };
    let _ = request.respond(response);
}

impl WebServer {
    /// Serves `files` on `address:port`, and `control` at `/control` when given.
    pub fn start(
        address: IpAddr,
        port: u16,
        files: Arc<ViewerFiles>,
        control: Option<Arc<ControlPage>>,
    ) -> Result<Self> {
        check_port(address, port, "web page", "port")?;
        let server = Arc::new(tiny_http::Server::http((address, port)).map_err(|source| {
            ServeError::Bind {
                address,
                port: Some(port),
                source,
            }
        })?);
        let threads = (0..THREADS)
            .map(|_| {
                let (server, files, control) = (server.clone(), files.clone(), control.clone());
                std::thread::spawn(move || {
                    for request in server.incoming_requests() {
                        respond(&files, control.as_deref(), request);
                    }
                })
            })
            .collect();
        Ok(Self { server, threads })
    }

    /// Stops accepting requests and waits for the threads.
    pub fn stop(self) {
        for _ in &self.threads {
            self.server.unblock();
        }
        for t in self.threads {
            let _ = t.join();
        }
    }
}
