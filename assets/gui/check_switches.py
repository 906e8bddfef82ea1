#!/usr/bin/env python3
"""The explorer as a student sees a switch: run `flexmodes gui` under Xvfb, toggle a method a
few times, take a screenshot at every frame drawn after each toggle, and check that every
frame shows either the previous complete result or the new complete one, never a half-drawn
state (views empty, meshes stacked at the origin, plots without their lines).

    python3 assets/gui/check_switches.py --binary target/debug/flexmodes \
        --scene slab-sim1 --toggle gr --out target/gui-check/slab-sim1
    python3 assets/gui/check_switches.py --body tests/bodies/steel-link/body.toml \
        --simulate bore_a --toggle cb --repeat 1 --out target/gui-check/steel-link

Needs Xvfb and a Vulkan or GL driver that runs without a GPU (Debian: xvfb,
mesa-vulkan-drivers) and Pillow. The screenshots stay in --out; a summary goes to
--out/summary.json. With --progressive the explorer shows each result as it arrives (its
old behaviour) and the check passes only if it catches half-drawn frames: a check that
cannot fail proves nothing.

Exit status: 0 when every frame is whole (or, with --progressive, when half-drawn frames
were caught), 1 otherwise.
"""

import argparse
import glob
import json
import os
import re
import select
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import switch_frames  # noqa: E402

# Two pictures of one complete result differ by at most this (animation: bodies move in
# their lanes, the time cursor moves; measured up to 0.014 on slab-modes and the L-bracket,
# 0.38 on slab-sim1); a switch's before and after differ by 0.2–1.2 (0.20 unticking GR on
# the L-bracket, whose frequencies are thin bars in one grouped chart; 0.31–0.34 unticking
# CB on slab-modes). A frame belongs to a picture within min(SAME, half the switch's change)
# of it.
SAME = 0.4
# A switch must change the picture by at least this to be judged: ten times the noise
# within one picture on the scenes CI checks.
CHANGE = 0.14


def fail(message):
    print(f"check_switches: FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def start_xvfb(size):
    """A private X server on a display it picks itself; returns (display, process).

    Xvfb chooses a free display and writes its number to a pipe (`-displayfd`) once it accepts
    clients: no guessing of free numbers, and a lock file left by a server that died is
    recognised as stale by Xvfb itself (a check that skipped every display with a lock file ran
    out of displays on a machine whose /tmp kept the locks of killed servers)."""
    if shutil.which("Xvfb") is None:
        fail("Xvfb is not installed (Debian: apt-get install xvfb mesa-vulkan-drivers)")
    read, write = os.pipe()
    log = tempfile.TemporaryFile()
    proc = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write), "-screen", "0", f"{size}x24",
         "-extension", "Composite", "-nolisten", "tcp"],
        pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=log)
    os.close(write)
    number = b""
    deadline = time.time() + 30
    while not number.endswith(b"\n") and time.time() < deadline:
        ready, _, _ = select.select([read], [], [], 0.5)
        if ready:
            chunk = os.read(read, 16)
            if not chunk:
                break
            number += chunk
    os.close(read)
    if not number.strip().isdigit():
        proc.kill()
        proc.wait()
        log.seek(0)
        said = log.read().decode(errors="replace").strip()[-2000:]
        fail(f"Xvfb did not start (exit {proc.poll()}); it said:\n{said}")
    return f":{number.strip().decode()}", proc


def stop_xvfb(proc):
    """Stops a server start_xvfb started, letting it remove its lock file and socket."""
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


def run_explorer(args, display):
    if os.path.isdir(args.out):
        shutil.rmtree(args.out)
    os.makedirs(args.out)
    # A body file opens the `modes` scene on it, driven through a node set with --simulate.
    opened = [args.scene] if args.body is None else ["--body", args.body]
    if args.simulate is not None:
        opened += ["--simulate", args.simulate, "--interval", str(args.interval)]
    command = [
        args.binary, "gui", *opened, "--window-size", args.window,
        "--screenshot", os.path.join(args.out, "final.png"),
    ]
    if args.toggle != "none":
        command += [
            "--toggle", args.toggle, "--repeat", str(args.repeat), "--pause", str(args.pause),
            "--frames", args.out, "--frame-every-ms", "1", "--frame-count", str(args.frames),
        ]
    if args.progressive:
        command.append("--progressive-switch")
    if args.theme:
        command += ["--theme", args.theme]
    env = dict(os.environ, DISPLAY=display)
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")
    print("running:", " ".join(command), flush=True)
    start = time.time()
    done = subprocess.run(command, env=env, capture_output=True, text=True,
                          timeout=args.timeout)
    log = done.stdout + done.stderr
    with open(os.path.join(args.out, "explorer.log"), "w") as f:
        f.write(log)
    if done.returncode != 0 or not os.path.exists(os.path.join(args.out, "final.png")):
        print(log[-3000:], file=sys.stderr)
        fail(f"the explorer exited with {done.returncode} and no final screenshot")
    return log, time.time() - start


def measured(log):
    """The numbers the explorer printed: switch times and memory."""
    out = {}
    m = re.search(r"from toggle to the new recording shown \(all of it in the viewer\), s: (.*)",
                  log)
    if m:
        out["toggle_to_shown_s"] = [float(x) for x in m.group(1).split(",") if x.strip()]
    m = re.search(r"resident memory, MiB: (\d+) after the first recording, (\d+) after the "
                  r"last \((\d+) shown[^)]*\), peak (\d+); growth (\d+) MiB; run cache ([\d.]+) of "
                  r"its (\d+) MiB bound", log)
    if m:
        keys = ["first_mib", "last_mib", "shown", "peak_mib", "growth_mib", "cache_mib",
                "cache_bound_mib"]
        out["memory"] = dict(zip(keys, [float(x) for x in m.groups()]))
    return out


def check_switch(number, paths):
    """Classifies each frame of one switch as before, after or half-drawn."""
    summaries = [switch_frames.summary(p) for p in paths]
    before, after = summaries[0], summaries[-1]
    change = switch_frames.distance(after, before)
    same = min(SAME, 0.5 * change)
    frames = []
    for p, s in zip(paths, summaries):
        d_before = switch_frames.distance(s, before)
        d_after = switch_frames.distance(s, after)
        if d_before <= same and d_before <= d_after:
            state = "before"
        elif d_after <= same:
            state = "after"
        else:
            state = "half-drawn"
        frames.append({"frame": os.path.basename(p), "to_before": round(d_before, 3),
                       "to_after": round(d_after, 3), "state": state})
    problems = []
    if change < CHANGE:
        problems.append(f"the switch changed too little to judge ({change:.2f})")
    if any(f["state"] != "after" for f in frames[-3:]):
        problems.append("the series ended before the new picture was steady")
    half = [f["frame"] for f in frames if f["state"] == "half-drawn"]
    states = [f["state"] for f in frames if f["state"] != "half-drawn"]
    flips = sum(1 for a, b in zip(states, states[1:]) if a == "after" and b == "before")
    line = "".join({"before": "b", "after": "a", "half-drawn": "X"}[f["state"]] for f in frames)
    print(f"switch {number}: {len(frames)} frames {line}  (before→after {change:.2f}, "
          f"threshold {same:.2f}, worst frame "
          f"{max(min(f['to_before'], f['to_after']) for f in frames):.2f})")
    return {"switch": number, "change": round(change, 3), "frames": frames,
            "half_drawn": half, "flips_back": flips, "problems": problems}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--binary", default="target/debug/flexmodes")
    p.add_argument("--scene", default="slab-sim1")
    p.add_argument("--body", help="open the `modes` scene on this body file instead of --scene")
    p.add_argument("--simulate", help="with --body: drive this node set (`gui --simulate`)")
    p.add_argument("--interval", type=float, default=0.1,
                   help="with --simulate: the simulated interval, s")
    p.add_argument("--toggle", default="gr",
                   help="the method to toggle; `none`: the first picture alone (final.png), "
                        "for the chart check in another theme")
    p.add_argument("--repeat", type=int, default=2)
    p.add_argument("--pause", type=float, default=8.0,
                   help="seconds between a result shown and the next toggle")
    # Software rendering takes 40–58 frames to show a switched recording whole on this 2-core
    # machine (toggle to shown 14–26 s); 60 frames left a switch without the three steady
    # frames the check needs, so a slow run failed although every frame was clean.
    p.add_argument("--frames", type=int, default=100, help="frames kept per toggle")
    p.add_argument("--window", default="1280x800")
    p.add_argument("--theme", choices=["light", "dark"],
                   help="the viewer's theme (default: the explorer's own choice)")
    # The pointer starts at the screen's centre: outside the window (at the top left), so it
    # hovers no plot (a hover tooltip coming and going changes the picture).
    p.add_argument("--screen", default="2600x1800")
    p.add_argument("--display", help="use this X display instead of a private Xvfb")
    p.add_argument("--out", default="target/gui-check")
    p.add_argument("--timeout", type=float, default=900)
    p.add_argument("--progressive", action="store_true",
                   help="the old behaviour: pass only if half-drawn frames are caught")
    p.add_argument("--max-growth-mib", type=float,
                   help="fail when resident memory grows by more than this")
    args = p.parse_args()

    xvfb = None
    display = args.display
    if display is None:
        display, xvfb = start_xvfb(args.screen)
    try:
        log, wall = run_explorer(args, display)
    finally:
        if xvfb is not None:
            stop_xvfb(xvfb)
    numbers = measured(log)
    switches = []
    if args.toggle == "none":
        print(f"ok: the first picture in {wall:.0f} s: {args.out}/final.png")
        return
    for n in range(1, args.repeat + 1):
        paths = sorted(glob.glob(os.path.join(args.out, f"switch-{n:02}-*.png")))
        if len(paths) < 5:
            fail(f"switch {n}: only {len(paths)} frames were saved")
        switches.append(check_switch(n, paths))
    summary = {"scene": args.scene, "toggle": args.toggle, "progressive": args.progressive,
               "wall_s": round(wall, 1), **numbers, "switches": switches}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(f"explorer ran {wall:.0f} s; toggle to shown, s: "
          f"{numbers.get('toggle_to_shown_s')}; memory: {numbers.get('memory')}")

    problems = [f"switch {s['switch']}: {p}" for s in switches for p in s["problems"]]
    half = sum(len(s["half_drawn"]) for s in switches)
    flips = sum(s["flips_back"] for s in switches)
    total = sum(len(s["frames"]) for s in switches)
    if args.progressive:
        if half + flips == 0:
            fail(f"the progressive switch showed no half-drawn frame in {total}: the check "
                 "cannot tell")
        print(f"ok: the check caught {half} half-drawn frame(s) of {total} in the "
              "progressive switch")
        return
    if problems:
        fail("; ".join(problems))
    if half or flips:
        fail(f"{half} half-drawn frame(s) of {total}, {flips} flip(s) back to the old "
             f"picture; screenshots in {args.out}")
    growth = numbers.get("memory", {}).get("growth_mib")
    if args.max_growth_mib is not None and growth is not None and growth > args.max_growth_mib:
        fail(f"resident memory grew by {growth:.0f} MiB (bound {args.max_growth_mib:.0f})")
    print(f"ok: {total} frames over {len(switches)} switches, each the previous or the new "
          f"complete picture; screenshots in {args.out}")


if __name__ == "__main__":
    main()
