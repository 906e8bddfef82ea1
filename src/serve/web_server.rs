//! The classroom's web server: the viewer's files over HTTP, gzip-compressed where the browser
//! accepts it, on a few threads; everything else is 404. No request leaves the machine's own
//! files: the page is the offline one of [`super::ViewerFiles`].

use std::{net::IpAddr, sync::Arc, thread::JoinHandle};

use super::ViewerFiles;
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
            address: address.to_string(),
            port,
            what,
            option,
        }
        .into()),
        Err(e) => Err(ServeError::Bind {
            address: address.to_string(),
            reason: e.to_string(),
        }
        .into()),
    }
}

fn header(name: &str, value: &str) -> tiny_http::Header {
    tiny_http::Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("ASCII header")
}

fn respond(files: &ViewerFiles, request: tiny_http::Request) {
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
    /// Serves `files` on `address:port`.
    pub fn start(address: IpAddr, port: u16, files: Arc<ViewerFiles>) -> Result<Self> {
        check_port(address, port, "web page", "port")?;
        let server =
            Arc::new(
                tiny_http::Server::http((address, port)).map_err(|e| ServeError::Bind {
                    address: format!("{address}:{port}"),
                    reason: e.to_string(),
                })?,
            );
        let threads = (0..THREADS)
            .map(|_| {
                let (server, files) = (server.clone(), files.clone());
                std::thread::spawn(move || {
                    for request in server.incoming_requests() {
                        respond(&files, request);
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
