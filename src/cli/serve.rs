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
    use std::{sync::Arc, time::Instant};

    use crate::{
        scenes,
        serve::{
            Classroom, ViewerFiles, WebServer, check_port, data_url, file_messages, origin,
            page_url, scene_messages,
        },
    };

    let ServeArgs {
        scenes: ids,
        files,
        bind,
        port,
        grpc_port,
        theme,
        options,
    } = arguments;
    // Everything that can fail on the input fails before a port is taken.
    let ids: Vec<String> = if ids.is_empty() && files.is_empty() {
        scenes::all_ids()
    } else {
        ids
    };
    let found = ids
        .iter()
        .map(|id| scenes::find(id))
        .collect::<Result<Vec<_>>>()?;
    let recordings = files
        .iter()
        .map(|f| file_messages(f))
        .collect::<Result<Vec<_>>>()?;
    let opts = options.into_scene_options()?;
    check_port(bind, grpc_port, "data server", "grpc-port")?;
    check_port(bind, port, "web page", "port")?;

    let started = Instant::now();
    let viewer = Arc::new(ViewerFiles::load()?);
    let (plain, gzipped) = viewer.sizes();
    eprintln!(
        "web viewer: {:.1} MB, {:.1} MB gzipped ({:.1} s)",
        plain as f64 / 1e6,
        gzipped as f64 / 1e6,
        started.elapsed().as_secs_f64()
    );
    let shared = shared_address(bind);
    let mut origins = vec![origin(shared, port), origin(bind, port)];
    if bind.is_unspecified() {
        origins.push(format!("http://*:{port}"));
    }
    let classroom = Classroom::start(bind, grpc_port, origins)?;
    let web = WebServer::start(bind, port, viewer)?;
    for messages in recordings {
        classroom.publish(messages);
    }
    for scene in &found {
        let t = Instant::now();
        classroom.publish(scene_messages(scene, &opts, None)?);
        eprintln!(
            "{}: published ({:.1} s)",
            scene.info.id,
            t.elapsed().as_secs_f64()
        );
    }
    let data = data_url(shared, grpc_port);
    println!(
        "open in a browser: {}",
        page_url(shared, port, &data, theme.map(super::arguments::Theme::id))
    );
    if bind.is_loopback() {
        println!("(this machine only: --bind ADDRESS lets a classroom network in)");
    }
    println!("commands: show SCENE [--method cb,mc] [--modes N] …, list, quit (or Ctrl-C)");

    read_commands(&classroom)?;
    web.stop();
    drop(classroom);
    eprintln!("stopped");
    Ok(())
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
/// `quit`, Ctrl-C, SIGTERM; each `show` publishes its scene to every viewer.
#[cfg(feature = "serve")]
fn read_commands(classroom: &crate::serve::Classroom) -> Result<()> {
    use clap::Parser as _;
    use std::{io::BufRead as _, sync::mpsc};

    use crate::{scenes, serve::scene_messages};

    enum Event {
        Line(String),
        Stop,
    }
    let (tx, rx) = mpsc::channel();
    let stop = tx.clone();
    ctrlc::set_handler(move || {
        let _ = stop.send(Event::Stop);
    })
    .map_err(|e| crate::Error::InvalidOption {
        scene: "serve".into(),
        reason: format!("cannot catch Ctrl-C: {e}"),
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
    let mut shown = 0;
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
                    println!("{:<18} {}", s.info.id, s.info.summary);
                }
            }
            Some("show") => {
                let result = Show::try_parse_from(&words[1..])
                    .map_err(|e| e.to_string())
                    .and_then(|show| {
                        let scene = scenes::find(&show.scene).map_err(|e| e.to_string())?;
                        let opts = show
                            .options
                            .into_scene_options()
                            .map_err(|e| e.to_string())?;
                        shown += 1;
                        scene_messages(&scene, &opts, Some(format!("shown-{shown}")))
                            .map_err(|e| e.to_string())
                    });
                match result {
                    Ok(messages) => {
                        classroom.publish(messages);
                        println!("showing: {}", words[1..].join(" "));
                    }
                    Err(e) => eprintln!("error: {e}"),
                }
            }
            Some(other) => eprintln!("unknown command `{other}`: show, list, quit"),
        }
    }
    Ok(())
}
