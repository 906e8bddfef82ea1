//! `flexmodes serve`: the classroom in the browser (crate::serve), wired to the terminal: the
//! scenes published at start, the URL printed, then the teacher's commands read line by line
//! until `quit`, Ctrl-C or SIGTERM.

use super::arguments::ServeArgs;
use crate::Result;

#[cfg(not(feature = "serve"))]
pub(super) fn run(_arguments: ServeArgs) -> Result<()> {
    Err(crate::error::ServeError::NotBuilt.into())
}

#[cfg(feature = "serve")]
pub(super) fn run(arguments: ServeArgs) -> Result<()> {
    use std::{
        sync::{Arc, atomic::AtomicUsize},
        time::Instant,
    };

    use crate::{
        error::ServeError,
        scenes,
        serve::{
            Classroom, ControlPage, PublishStatus, Publisher, WebServer, check_port, file_messages,
            new_control_token, origin, scene_messages,
        },
    };

    let ServeArgs {
        scenes: ids,
        files,
        bind,
        port,
        grpc_port,
        theme,
        control_token,
        options,
    } = arguments;
    // Everything that can fail on the input fails before a port is taken.
    let ids = if ids.is_empty() && files.is_empty() {
        scenes::all_ids()
    } else {
        ids
    };
    let found: Vec<_> = ids.into_iter().map(scenes::get).collect();
    let recordings = files
        .iter()
        .map(|f| file_messages(f))
        .collect::<Result<Vec<_>>>()?;
    let opts = options.into_scene_options()?;
    let token = match control_token {
        Some(t) => checked_token(t)?,
        None => new_control_token().map_err(|source| ServeError::NoRandomToken { source })?,
    };
    check_port(bind, grpc_port, "data server", "grpc-port")?;
    check_port(bind, port, "web page", "port")?;

    let viewer = load_viewer()?;
    let shared = shared_address(bind);
    let mut origins = vec![origin(shared, port), origin(bind, port)];
    if bind.is_unspecified() {
        origins.push(format!("http://*:{port}"));
    }
    let classroom = Arc::new(Classroom::start(bind, grpc_port, origins)?);
    let publisher = {
        let classroom = classroom.clone();
        Arc::new(Publisher::start(
            move |m| classroom.publish(m),
            |status| match status {
                PublishStatus::Published { label, messages } => {
                    println!("showing: {label} ({messages} messages)")
                }
                PublishStatus::Failed(label, e) => eprintln!("error: {label}: {e}"),
                _ => {}
            },
        ))
    };
    let shown = Arc::new(AtomicUsize::new(0));
    let control = {
        let (apply_to, status_of, shown) = (publisher.clone(), publisher.clone(), shown.clone());
        Arc::new(ControlPage::new(
            token.clone(),
            scenes::all()
                .iter()
                .map(|s| (s.id.to_string(), s.info.summary.to_string()))
                .collect(),
            Box::new(move |words| show_request(&apply_to, &shown, words)),
            Box::new(move || status_text(&status_of)),
        ))
    };
    let web = WebServer::start(bind, port, viewer, Some(control.clone()))?;
    for messages in recordings {
        classroom.publish(messages);
    }
    for scene in &found {
        let t = Instant::now();
        classroom.publish(scene_messages(scene, &opts, None)?);
        eprintln!(
            "{}: published ({:.1} s)",
            scene.id,
            t.elapsed().as_secs_f64()
        );
    }
    print_addresses(bind, shared, (port, grpc_port), theme, &token);

    read_commands(&publisher, &shown)?;
    web.stop();
    drop(control);
    drop(publisher);
    drop(classroom);
    eprintln!("stopped");
    Ok(())
}

/// The web viewer's files, their sizes said.
#[cfg(feature = "serve")]
fn load_viewer() -> Result<std::sync::Arc<crate::serve::ViewerFiles>> {
    let started = std::time::Instant::now();
    let viewer = std::sync::Arc::new(crate::serve::ViewerFiles::load()?);
    let (plain, gzipped) = viewer.sizes();
    eprintln!(
        "web viewer: {:.1} MB, {:.1} MB gzipped ({:.1} s)",
        plain as f64 / 1e6,
        gzipped as f64 / 1e6,
        started.elapsed().as_secs_f64()
    );
    Ok(viewer)
}

/// Where students open the page (its data on `grpc_port`) and where the teacher steers.
#[cfg(feature = "serve")]
fn print_addresses(
    bind: std::net::IpAddr,
    shared: std::net::IpAddr,
    (port, grpc_port): (u16, u16),
    theme: Option<super::arguments::Theme>,
    token: &str,
) {
    use crate::serve::{data_url, origin, page_url};
    let data = data_url(shared, grpc_port);
    println!(
        "open in a browser: {}",
        page_url(shared, port, &data, theme.map(super::arguments::Theme::id))
    );
    if bind.is_loopback() {
        println!("(this machine only: --bind ADDRESS lets a classroom network in)");
    }
    println!(
        "control page (the teacher's: whoever has the token steers every viewer): \
         {}/control?token={token}",
        origin(shared, port)
    );
    println!("commands: show SCENE [--method cb,mc] [--modes N] …, list, quit (or Ctrl-C)");
}

/// A teacher's command: `show SCENE [options]`.
#[cfg(feature = "serve")]
#[derive(clap::Parser)]
#[command(no_binary_name = true)]
struct Show {
    scene: String,
    #[command(flatten)]
    options: super::arguments::OptionArgs,
}

/// The address students reach: the bound one, or for 0.0.0.0 this machine's address on its
/// default route (a UDP "connect" sends nothing).
#[cfg(feature = "serve")]
fn shared_address(bind: std::net::IpAddr) -> std::net::IpAddr {
    use std::net::{IpAddr, Ipv4Addr};
    if bind.is_unspecified() {
        std::net::UdpSocket::bind((Ipv4Addr::UNSPECIFIED, 0))
            .and_then(|s| s.connect((Ipv4Addr::new(192, 0, 2, 1), 9)).map(|_| s))
            .and_then(|s| s.local_addr())
            .map(|a| a.ip())
            .unwrap_or(IpAddr::V4(Ipv4Addr::LOCALHOST))
    } else {
        bind
    }
}

/// The teacher's commands read line by line from the terminal (`show`, `list`, `quit`) until
/// `quit`, Ctrl-C, SIGTERM; each `show` is queued like the control page's requests.
#[cfg(feature = "serve")]
fn read_commands(
    publisher: &crate::serve::Publisher,
    shown: &std::sync::atomic::AtomicUsize,
) -> Result<()> {
    use std::{io::BufRead as _, sync::mpsc};

    use crate::scenes;

    enum Event {
        Line(String),
        Stop,
    }
    let (tx, rx) = mpsc::channel();
    let stop = tx.clone();
    ctrlc::set_handler(move || {
        let _ = stop.send(Event::Stop);
    })
    .map_err(|e| crate::error::ServeError::NoInterruptHandler {
        source: Box::new(e),
    })?;
    std::thread::spawn(move || {
        for line in std::io::stdin().lock().lines() {
            let Ok(line) = line else { break };
            if tx.send(Event::Line(line)).is_err() {
                break;
            }
        }
        // End of input (a server started without a terminal) keeps serving.
    });
    while let Ok(event) = rx.recv() {
        let line = match event {
            Event::Stop => break,
            Event::Line(l) => l,
        };
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.first().copied() {
            None => {}
            Some("quit" | "exit") => break,
            Some("list") => {
                for s in scenes::all() {
                    println!("{:<18} {}", s.id, s.info.summary);
                }
            }
            Some("show") => {
                let words: Vec<String> = words[1..].iter().map(|w| w.to_string()).collect();
                match show_request(publisher, shown, &words) {
                    Ok(queued) => println!("{queued}"),
                    Err(e) => eprintln!("error: {e}"),
                }
            }
            Some(other) => eprintln!("unknown command `{other}`: show, list, quit"),
        }
    }
    Ok(())
}

/// A teacher's `show` request (the scene, then options), checked and queued: it replaces a
/// request still waiting, never stacks. Returns what was queued, or why not.
#[cfg(feature = "serve")]
fn show_request(
    publisher: &crate::serve::Publisher,
    shown: &std::sync::atomic::AtomicUsize,
    words: &[String],
) -> std::result::Result<String, String> {
    use clap::Parser as _;

    use crate::{
        scenes,
        serve::{PublishJob, scene_messages},
    };

    // clap's first line names the problem; the rest points at `--help`, which a page has not.
    let show = Show::try_parse_from(words)
        .map_err(|e| e.to_string().lines().next().unwrap_or_default().to_string())?;
    let scene = scenes::find(&show.scene).map_err(|e| e.to_string())?;
    let opts = show
        .options
        .into_scene_options()
        .map_err(|e| e.to_string())?;
    let n = shown.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
    let label = words.join(" ");
    let replaced = publisher.submit(PublishJob {
        label: label.clone(),
        compute: Box::new(move || scene_messages(&scene, &opts, Some(format!("shown-{n}")))),
    });
    Ok(match replaced {
        Some(old) => format!("queued: {label} (instead of the waiting `{old}`)"),
        None => format!("queued: {label}"),
    })
}

/// What the class sees, or is about to, in words.
#[cfg(feature = "serve")]
fn status_text(publisher: &crate::serve::Publisher) -> String {
    use crate::serve::PublishStatus;

    let now = match publisher.status() {
        PublishStatus::Idle => "the scenes published at start".to_string(),
        PublishStatus::Computing(l) => format!("computing `{l}`"),
        PublishStatus::Published { label, .. } => format!("showing `{label}`"),
        PublishStatus::Failed(l, e) => format!("`{l}` failed: {e}"),
    };
    match publisher.queued() {
        Some(next) => format!("{now}; next: `{next}`"),
        None => now,
    }
}

/// A control token given on the command line: URL-safe characters, at least 16 of them.
#[cfg(feature = "serve")]
fn checked_token(token: String) -> Result<String> {
    if token.len() >= 16
        && token
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"-_.~".contains(&b))
    {
        Ok(token)
    } else {
        Err(crate::error::ServeError::ControlToken {
            length: token.chars().count(),
        }
        .into())
    }
}
