//! `flexmodes bench`: the driven body's sizes, every method on a body, the export against
//! SciPy's peer, meshes against DOF, and the scenes' speed against accuracy.

use std::path::PathBuf;

use super::{arguments::BenchArgs, stderr::progress};
use crate::{
    Error, Progress, Result, TerminalProgress, body_file::ImportedBody, record::Recorder,
    scenes::SceneId,
};

/// What `bench --all` measures, in this order.
const BENCH_ALL: [SceneId; 3] = [SceneId::SlabModes, SceneId::SlabSim1, SceneId::SlabSim2];

/// `flexmodes bench`: the driven body's sizes, every method on a body, the export against
/// SciPy's peer, meshes against DOF, or the scenes' speed against accuracy.
pub(super) fn bench(mut args: BenchArgs, threads: &[usize]) -> Result<()> {
    let body = args.body.take();
    let sizes = args.sizes.take();
    match (body, sizes) {
        (Some(body), _) if args.scenes.as_slice() == ["simulate"] => driven_sizes(args, body),
        (Some(body), _) if !args.scenes.is_empty() => body_modes(args, body),
        (Some(body), _) => export_peer(args, body),
        (None, Some(sizes)) => size_bench(args, &sizes, threads),
        (None, None) => scenes(args),
    }
}

/// `bench simulate --body --drive`: the full driven body's cost against DOF.
fn driven_sizes(args: BenchArgs, body: PathBuf) -> Result<()> {
    let BenchArgs {
        drive,
        larger,
        modes,
        json,
        ..
    } = args;
    let drive = drive.ok_or_else(|| Error::InvalidOption {
        option: "--drive",
        scene: None,
        reason: "bench simulate needs --drive rbe2:SET".into(),
    })?;
    let mut files = vec![body.display().to_string()];
    files.extend(larger.iter().map(|p| p.display().to_string()));
    let parameters = crate::bench::driven_size_parameters(drive);
    let handle = Progress::new();
    let bar = TerminalProgress::start(&handle, "bench simulate");
    let (value, text) = crate::bench::bench_driven_sizes(
        &files,
        &parameters,
        modes.first().copied().unwrap_or(10),
        &handle,
    )?;
    drop(bar);
    if json {
        println!("{value}");
    } else {
        println!("# bench simulate --body {}\n\n{text}", files.join(","));
    }
    Ok(())
}

/// `bench modes --body`: every method and kept-mode count on a user's body.
fn body_modes(args: BenchArgs, body: PathBuf) -> Result<()> {
    let BenchArgs {
        scenes: ids,
        boundary,
        modes,
        method,
        band,
        tolerance,
        interface_modes,
        save,
        json,
        ..
    } = args;
    if ids.as_slice() != ["modes"] {
        return Err(Error::InvalidOption {
            option: "SCENES",
            scene: None,
            reason: "with --body, bench takes the scene `modes` or `simulate` (or \
                     none: the export bench)"
                .into(),
        });
    }
    let loaded = ImportedBody::load(&body.display().to_string())?;
    let defaults = crate::models::BodyComparisonParameters::default();
    let parameters = crate::models::BodyComparisonParameters {
        boundary,
        interface_modes,
        methods: if method.is_empty() {
            defaults.methods
        } else {
            method
        },
        modes: if modes.is_empty() {
            defaults.modes
        } else {
            modes
        },
        band_hz: band,
        tolerance,
    };
    let handle = Progress::new();
    let bar = TerminalProgress::start(&handle, "bench modes --body");
    let (value, text, recording) = crate::bench::bench_body_modes(&loaded, &parameters, &handle)?;
    drop(bar);
    if let Some(path) = &save {
        Recorder::default().save(&recording, path)?;
        progress(&format!("wrote {}", path.display()));
    }
    if json {
        println!("{value}");
    } else {
        println!("# bench modes --body {}\n\n{text}", body.display());
    }
    Ok(())
}

/// `bench --body`: `export --method cb` as a whole process against SciPy's peer script.
fn export_peer(args: BenchArgs, body: PathBuf) -> Result<()> {
    let BenchArgs {
        boundary,
        modes,
        peer,
        repeats,
        json,
        save,
        ..
    } = args;
    if save.is_some() {
        return Err(Error::InvalidOption {
            option: "--save",
            scene: None,
            reason: "the export bench writes no recording: --save goes with `bench modes --body`"
                .into(),
        });
    }
    let modes = match modes.as_slice() {
        [] => 10,
        [k] => *k,
        _ => {
            return Err(Error::InvalidOption {
                option: "--modes",
                scene: None,
                reason: "the export bench takes one --modes count".into(),
            });
        }
    };
    let boundary = match boundary {
        Some(b) => b,
        None => {
            let loaded = ImportedBody::load(&body.display().to_string())?;
            let nodes = loaded.default_interface_nodes()?.to_vec();
            // The peer takes a set name: the body's default interface.
            let name = loaded
                .node_sets
                .iter()
                .find(|(_, v)| **v == nodes)
                .map(|(k, _)| k.clone())
                .ok_or_else(|| Error::InvalidOption {
                    option: "--boundary",
                    scene: None,
                    reason: "name the interface node set with --boundary".into(),
                })?;
            vec![name]
        }
    };
    let (value, text) = crate::bench::bench_export(&crate::bench::ExportBenchParameters {
        body,
        boundary,
        modes,
        repeats: repeats.unwrap_or(3) as usize,
        peer,
    })?;
    if json {
        println!("{value}");
    } else {
        println!("{text}");
    }
    Ok(())
}

/// `bench slab-modes|slab-sim1|slab-sim2 --sizes`: cost against DOF.
fn size_bench(args: BenchArgs, sizes: &str, threads: &[usize]) -> Result<()> {
    let BenchArgs {
        scenes: ids,
        json,
        save,
        repeats,
        eigensolver,
        pairs,
        ..
    } = args;
    let ids = parse_scene_ids(&ids)?;
    if !eigensolver.is_empty() && ids.iter().any(|id| *id != SceneId::SlabModes) {
        return Err(Error::InvalidOption {
            option: "--eigensolver",
            scene: None,
            reason: "--eigensolver times the free slab's pairs: `bench slab-modes --sizes`".into(),
        });
    }
    let simulation = match ids.as_slice() {
        [id @ (SceneId::SlabSim1 | SceneId::SlabSim2)] => Some(*id),
        _ if ids.iter().all(|id| *id == SceneId::SlabModes) => None,
        _ => {
            return Err(Error::InvalidOption {
                option: "SCENES",
                scene: None,
                reason: "--sizes times slab-modes, or one of slab-sim1 and slab-sim2".into(),
            });
        }
    };
    let meshes = crate::bench::parse_sizes(sizes)?;
    let bench = match &simulation {
        Some(id) => {
            let handle = Progress::new();
            let bar = TerminalProgress::start(&handle, &format!("bench {id} --sizes"));
            let bench = crate::bench::bench_sim_sizes(id.as_str(), &meshes, &handle)?;
            drop(bar);
            bench
        }
        None if !eigensolver.is_empty() => {
            crate::bench::bench_eigensolvers(&meshes, &eigensolver, pairs.unwrap_or(50), &|s| {
                progress(s)
            })?
        }
        None => {
            crate::bench::bench_sizes(&meshes, threads, repeats.map_or(1, |r| r as usize), &|s| {
                progress(s)
            })?
        }
    };
    let title = simulation.unwrap_or(SceneId::SlabModes);
    if let Some(path) = &save {
        Recorder::default().save(&bench.recording, path)?;
        progress(&format!("wrote {}", path.display()));
    }
    if json {
        println!("{}", bench.value);
    } else {
        println!("# bench {title} --sizes {sizes}\n\n{}", bench.table);
    }
    Ok(())
}

/// `bench [SCENES]`: speed against accuracy of the slab scenes.
fn scenes(args: BenchArgs) -> Result<()> {
    let BenchArgs {
        scenes: ids,
        all,
        json,
        save,
        integrator,
        refine,
        repeats,
        ..
    } = args;
    let ids = if all {
        BENCH_ALL.to_vec()
    } else {
        parse_scene_ids(&ids)?
    };
    if !integrator.is_empty() && !ids.is_empty() && ids.iter().all(|id| *id == SceneId::SlabModes) {
        return Err(Error::InvalidOption {
            option: "--integrator",
            scene: Some(SceneId::SlabModes.as_str()),
            reason: "--integrator applies to the simulation benches only".into(),
        });
    }
    if save.is_some() && ids.len() > 1 {
        return Err(Error::InvalidOption {
            option: "--save",
            scene: None,
            reason: "--save writes the charts of one simulation bench: name one scene".into(),
        });
    }
    let ids = if ids.is_empty() {
        vec![SceneId::SlabSim1]
    } else {
        ids
    };
    let count = ids.len();
    for (k, id) in ids.into_iter().enumerate() {
        let handle = Progress::new();
        let bar = TerminalProgress::start(&handle, &format!("bench {id} ({} of {count})", k + 1));
        let (value, table, recording) = if id == SceneId::SlabModes {
            crate::bench::bench_modes(refine, &handle)?
        } else if id == SceneId::SpinUp {
            crate::bench::bench_spin_up(repeats.unwrap_or(3) as usize, &handle)?
        } else {
            crate::bench::bench_simulation(
                id.as_str(),
                &integrator,
                refine,
                repeats.unwrap_or(3) as usize,
                &handle,
            )?
        };
        drop(bar);
        if let Some(path) = &save {
            Recorder::default().save(&recording, path)?;
        }
        if json {
            println!("{value}");
        } else {
            println!("# bench {id}\n\n{table}");
        }
    }
    Ok(())
}

/// Scene ids as typed on the command line, each checked (a typo fails before anything runs).
fn parse_scene_ids(ids: &[String]) -> Result<Vec<SceneId>> {
    ids.iter().map(|id| id.parse()).collect()
}
