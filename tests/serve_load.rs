//! Thirty viewers at once (feature `serve`): `flexmodes serve` on a loopback address, thirty
//! connections to its web server (the page, the viewer's script and its 14 MB gzipped wasm,
//! each read whole) and thirty to its gRPC data server (Rerun's own client, the one the web
//! viewer runs), then three scenes published in turn from the teacher's control page. For each
//! publication, every viewer's time until it holds the whole recording; the server's resident
//! memory before and after; no connection may drop. Loopback only (127.0.0.0/8), bounded in
//! count and time. Run in CI beside the explorer's tests:
//! `cargo test --features gui,serve --test serve_load -- --nocapture` prints the numbers.
#![cfg(feature = "serve")]

use std::{
    io::{BufRead as _, BufReader, Read as _, Write as _},
    net::{TcpListener, TcpStream},
    process::{Child, ChildStdout, Command, Stdio},
    sync::{Arc, Mutex, mpsc},
    time::{Duration, Instant},
};

use re_log_channel::{DataSourceMessage, SmartMessagePayload};

/// Viewers connected at once.
const VIEWERS: usize = 30;
/// The loopback address the server binds (not 127.0.0.1: a classroom address is not either).
const ADDRESS: &str = "127.0.0.7";
const TOKEN: &str = "load-test-token-0123456789";
/// Every viewer must hold a recording this long after its publication, s.
const COMPLETE_WITHIN_S: f64 = 10.0;
/// The server's resident memory with thirty viewers and four recordings, at most, MB.
const RESIDENT_BOUND_MB: f64 = 600.0;
/// The scenes the teacher shows in turn (after `beam-modes` at start).
const SHOWN: [&str; 3] = [
    "slab-modes --method cb",
    "beam-eitelberg",
    "beam-modes --method cb",
];

fn free_port() -> u16 {
    TcpListener::bind((ADDRESS, 0))
        .and_then(|l| l.local_addr())
        .expect("a free port on the loopback address")
        .port()
}

/// The server's resident memory, MB (Linux's /proc).
fn resident_mb(pid: u32) -> f64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// One HTTP/1.1 GET read to its end: the status and the body's length.
fn get(port: u16, path: &str) -> (u16, usize) {
    let mut s = TcpStream::connect((ADDRESS, port)).expect("the web server accepts");
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {ADDRESS}:{port}\r\nAccept-Encoding: gzip\r\n\
         Connection: close\r\n\r\n"
    )
    .unwrap();
    let mut response = Vec::new();
    s.read_to_end(&mut response).expect("the whole response");
    let head_end = response
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("an HTTP header");
    let head = String::from_utf8_lossy(&response[..head_end]);
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = &response[head_end + 4..];
    let chunked = head
        .to_ascii_lowercase()
        .contains("transfer-encoding: chunked");
    let body = if chunked {
        dechunked_len(body).unwrap_or_else(|| panic!("GET {path}: a chunked body cut short"))
    } else {
        let length: usize = head
            .lines()
            .find_map(|l| {
                l.to_ascii_lowercase()
                    .strip_prefix("content-length:")
                    .map(|v| v.trim().parse().unwrap_or(0))
            })
            .unwrap_or_else(|| panic!("GET {path}: neither a length nor chunks"));
        assert_eq!(
            body.len(),
            length,
            "GET {path}: {} of {length} bytes",
            body.len()
        );
        length
    };
    (status, body)
}

/// The length of a chunked body, `None` unless it ends with its last (empty) chunk.
fn dechunked_len(mut body: &[u8]) -> Option<usize> {
    let mut total = 0;
    loop {
        let line_end = body.windows(2).position(|w| w == b"\r\n")?;
        let size_text = std::str::from_utf8(&body[..line_end]).ok()?;
        let size = usize::from_str_radix(size_text.split(';').next()?.trim(), 16).ok()?;
        body = &body[line_end + 2..];
        if size == 0 {
            return Some(total);
        }
        if body.len() < size + 2 {
            return None;
        }
        total += size;
        body = &body[size + 2..];
    }
}

/// The teacher's control page asked to show `words` (scene, then options).
fn show(port: u16, words: &str) {
    let mut parts = words.split_whitespace();
    let mut form = format!("token={TOKEN}&scene={}", parts.next().unwrap());
    while let (Some(option), Some(value)) = (parts.next(), parts.next()) {
        form.push_str(&format!("&{}={value}", option.trim_start_matches("--")));
    }
    let mut s = TcpStream::connect((ADDRESS, port)).unwrap();
    write!(
        s,
        "POST /control HTTP/1.1\r\nHost: {ADDRESS}:{port}\r\nContent-Type: \
         application/x-www-form-urlencoded\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{form}",
        form.len()
    )
    .unwrap();
    let mut answer = String::new();
    s.read_to_string(&mut answer).unwrap();
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
}

/// Lines the server prints, until one starts with `prefix`.
fn line_starting(lines: &mut BufReader<ChildStdout>, prefix: &str) -> String {
    let mut line = String::new();
    loop {
        line.clear();
        let n = lines.read_line(&mut line).expect("the server's output");
        assert!(n > 0, "the server stopped before printing `{prefix}`");
        if line.starts_with(prefix) {
            return line.trim().to_string();
        }
    }
}

/// What one viewer received: the arrival time of each message, and whether its connection
/// ended.
#[derive(Default)]
struct Viewer {
    arrivals: Vec<Instant>,
    dropped: Option<String>,
}

fn stop(mut server: Child) {
    if let Some(stdin) = server.stdin.as_mut() {
        let _ = stdin.write_all(b"quit\n");
    }
    let deadline = Instant::now() + Duration::from_secs(20);
    while Instant::now() < deadline {
        if let Ok(Some(_)) = server.try_wait() {
            return;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let _ = server.kill();
}

/// Thirty page loads at once, each read whole: the wall time of all, each one's (sorted),
/// and the bytes read.
fn load_pages(port: u16) -> (f64, Vec<f64>, usize) {
    let started = Instant::now();
    let loads: Vec<_> = (0..VIEWERS)
        .map(|_| {
            std::thread::spawn(move || {
                let t = Instant::now();
                let sizes: Vec<(u16, usize)> = ["/", "/re_viewer.js", "/re_viewer_bg.wasm"]
                    .iter()
                    .map(|path| get(port, path))
                    .collect();
                (t.elapsed().as_secs_f64(), sizes)
            })
        })
        .collect();
    let mut page_s = Vec::new();
    let mut page_bytes = 0;
    for load in loads {
        let (s, sizes) = load.join().expect("a page load");
        for (status, bytes) in sizes {
            assert_eq!(status, 200);
            page_bytes += bytes;
        }
        page_s.push(s);
    }
    let pages_s = started.elapsed().as_secs_f64();
    page_s.sort_by(f64::total_cmp);

    (pages_s, page_s, page_bytes)
}

/// Thirty viewers connected through Rerun's own gRPC client, each counting the messages it
/// receives on its own thread until `done` is dropped.
struct Viewers {
    /// Keeps the client's runtime alive while the viewers read.
    _runtime: tokio::runtime::Runtime,
    viewers: Vec<Arc<Mutex<Viewer>>>,
    readers: Vec<std::thread::JoinHandle<()>>,
    done: mpsc::Sender<()>,
}

impl Viewers {
    fn connect(grpc_port: u16) -> Self {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .unwrap();
        let handle = re_async::AsyncRuntimeHandle::new_native(runtime.handle().clone());
        let uri: re_uri::ProxyUri = format!("rerun+http://{ADDRESS}:{grpc_port}/proxy")
            .parse()
            .unwrap();
        let viewers: Vec<Arc<Mutex<Viewer>>> = (0..VIEWERS)
            .map(|_| Arc::new(Mutex::new(Viewer::default())))
            .collect();
        let (done_tx, done_rx) = mpsc::channel::<()>();
        let done_rx = Arc::new(Mutex::new(done_rx));
        let readers: Vec<_> = viewers
            .iter()
            .map(|viewer| {
                let receiver = re_grpc_client::read::stream(&handle, uri.clone());
                let (viewer, done) = (viewer.clone(), done_rx.clone());
                std::thread::spawn(move || {
                    loop {
                        if !matches!(
                            done.lock().unwrap().try_recv(),
                            Err(mpsc::TryRecvError::Empty)
                        ) {
                            return;
                        }
                        let Ok(message) = receiver.recv_timeout(Duration::from_millis(50)) else {
                            continue;
                        };
                        let mut v = viewer.lock().unwrap();
                        match message.payload {
                            SmartMessagePayload::Msg(DataSourceMessage::LogMsg(_)) => {
                                v.arrivals.push(Instant::now());
                            }
                            SmartMessagePayload::Quit(why) => {
                                v.dropped = Some(why.map_or("closed".into(), |e| e.to_string()));
                                return;
                            }
                            _ => {}
                        }
                    }
                })
            })
            .collect();
        Self {
            _runtime: runtime,
            viewers,
            readers,
            done: done_tx,
        }
    }

    /// Messages each viewer holds.
    fn counts(&self) -> Vec<usize> {
        self.viewers
            .iter()
            .map(|v| v.lock().unwrap().arrivals.len())
            .collect()
    }

    /// Waits until the recording published at start reached every viewer whole (it is kept
    /// for late joiners).
    fn wait_for_first_recording(&self) {
        let deadline = Instant::now() + Duration::from_secs(60);
        let mut previous = Vec::new();
        loop {
            std::thread::sleep(Duration::from_millis(500));
            let now = self.counts();
            if now == previous && now.iter().all(|&c| c > 0 && c == now[0]) {
                return;
            }
            assert!(
                Instant::now() < deadline,
                "the first recording never settled: {now:?}"
            );
            previous = now;
        }
    }

    /// Shows `words` from the control page and waits until every viewer holds the whole
    /// publication: its messages, the time the server took, and the median and slowest
    /// viewer's time after publication, s.
    fn show_and_time(
        &self,
        port: u16,
        lines: &mut BufReader<ChildStdout>,
        words: &'static str,
    ) -> (&'static str, usize, f64, f64, f64) {
        let before = self.counts();
        let asked = Instant::now();
        show(port, words);
        let showing = line_starting(lines, "showing:");
        let published = Instant::now();
        let messages: usize = showing
            .rsplit_once('(')
            .and_then(|(_, tail)| tail.split_whitespace().next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("no message count in `{showing}`"));
        let deadline = published + Duration::from_secs_f64(COMPLETE_WITHIN_S);
        let mut latest = Vec::new();
        for (k, viewer) in self.viewers.iter().enumerate() {
            let wanted = before[k] + messages;
            loop {
                {
                    let v = viewer.lock().unwrap();
                    assert!(v.dropped.is_none(), "viewer {k} dropped: {:?}", v.dropped);
                    if v.arrivals.len() >= wanted {
                        let last = v.arrivals[wanted - 1];
                        latest.push(last.saturating_duration_since(published).as_secs_f64());
                        break;
                    }
                }
                assert!(
                    Instant::now() < deadline,
                    "`{words}`: viewer {k} holds {} of {messages} messages {COMPLETE_WITHIN_S} s \
                     after publication",
                    viewer.lock().unwrap().arrivals.len() - before[k]
                );
                std::thread::sleep(Duration::from_millis(20));
            }
        }
        latest.sort_by(f64::total_cmp);
        (
            words,
            messages,
            published.duration_since(asked).as_secs_f64(),
            latest[latest.len() / 2],
            latest[latest.len() - 1],
        )
    }

    /// Stops the readers; none may have dropped.
    fn close(self) {
        drop(self.done);
        for r in self.readers {
            r.join().unwrap();
        }
        for (k, v) in self.viewers.iter().enumerate() {
            assert!(
                v.lock().unwrap().dropped.is_none(),
                "viewer {k} dropped: {:?}",
                v.lock().unwrap().dropped
            );
        }
    }
}

#[test]
fn thirty_viewers_receive_every_recording_whole_and_none_drops() {
    let (port, grpc_port) = (free_port(), free_port());
    let mut server = Command::new(env!("CARGO_BIN_EXE_flexmodes"))
        .args([
            "serve",
            "beam-modes",
            "--bind",
            ADDRESS,
            "--control-token",
            TOKEN,
        ])
        .args([
            "--port",
            &port.to_string(),
            "--grpc-port",
            &grpc_port.to_string(),
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("flexmodes serve starts");
    let pid = server.id();
    let mut lines = BufReader::new(server.stdout.take().unwrap());
    line_starting(&mut lines, "commands:");
    let idle_mb = resident_mb(pid);

    let (pages_s, page_s, page_bytes) = load_pages(port);
    let viewers = Viewers::connect(grpc_port);
    viewers.wait_for_first_recording();
    let table: Vec<_> = SHOWN
        .into_iter()
        .map(|words| viewers.show_and_time(port, &mut lines, words))
        .collect();
    let loaded_mb = resident_mb(pid);
    viewers.close();
    stop(server);

    println!(
        "{VIEWERS} page loads at once: {:.1} MB in {pages_s:.2} s (per viewer median {:.2} s, \
         slowest {:.2} s)",
        page_bytes as f64 / 1e6,
        page_s[page_s.len() / 2],
        page_s[page_s.len() - 1]
    );
    println!(
        "| shown | messages | computed, s | every viewer whole after publication, s (median / slowest) |"
    );
    println!("|---|---|---|---|");
    for (words, messages, computed, median, slowest) in &table {
        println!("| {words} | {messages} | {computed:.2} | {median:.3} / {slowest:.3} |");
    }
    println!(
        "server resident memory: {idle_mb:.0} MB before the viewers, {loaded_mb:.0} MB with \
         {VIEWERS} viewers and four recordings (bound {RESIDENT_BOUND_MB:.0} MB)"
    );
    assert!(
        loaded_mb <= RESIDENT_BOUND_MB,
        "the server holds {loaded_mb:.0} MB, more than {RESIDENT_BOUND_MB} MB"
    );
}
