#!/usr/bin/env python3
"""Memory over switches, as the issue states it: run `flexmodes gui` under Xvfb, toggle a
method 50 times on slab-sim1 (one recomputation and one new recording in the viewer each),
and check

  1. the resident size grows by no more than the run cache's stated bound over the 50
     switches (everything counted: our heap, the embedded viewer's, the graphics driver's);
  2. the Rust heap (ours and the viewer's, counted by the accounting allocator the binary
     installs) grows by no more than --heap-mib from the first switch on: a viewer that kept
     each recording it was handed (slab-sim1's is a few MB) would exceed it within ten.

    python3 assets/gui/check_memory.py --binary target/debug/flexmodes \
        --out target/gui-check/memory

Needs Xvfb and a software Vulkan driver that does not leak per frame: Mesa 22.3's lavapipe
compiles a new shader for every draw whose uniforms it inlines and never frees it (measured
here: 2.5 MiB per frame, +1.3 GB over 50 switches); `assets/gui/install_software_vulkan.sh`
installs Mesa from bookworm-backports on Debian 12. The explorer's log goes to
--out/explorer.log and the numbers to --out/summary.json.

Exit status: 0 when both bounds hold, 1 otherwise.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_switches import start_xvfb, stop_xvfb  # noqa: E402


def fail(message):
    print(f"check_memory: FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def series(log, label):
    """A comma-separated MiB series the explorer printed after `label`."""
    m = re.search(re.escape(label) + r", MiB: ([\d, ]+)", log)
    if not m:
        return None
    return [float(x) for x in m.group(1).split(",") if x.strip()]


def mesa_version():
    try:
        done = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "mesa-vulkan-drivers"],
                              capture_output=True, text=True)
        return done.stdout.strip() or None
    except OSError:
        return None


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--binary", default="target/debug/flexmodes")
    p.add_argument("--scene", default="slab-sim1")
    p.add_argument("--toggle", default="gr")
    p.add_argument("--switches", type=int, default=50)
    p.add_argument("--heap-mib", type=float, default=16.0,
                   help="allowed growth of the Rust heap from the first switch to the last")
    p.add_argument("--window", default="1280x800")
    p.add_argument("--screen", default="2600x1800")
    p.add_argument("--display", help="use this X display instead of a private Xvfb")
    p.add_argument("--out", default="target/gui-check/memory")
    p.add_argument("--timeout", type=float, default=900)
    args = p.parse_args()

    if os.path.isdir(args.out):
        shutil.rmtree(args.out)
    os.makedirs(args.out)
    display, xvfb = (args.display, None) if args.display else start_xvfb(args.screen)
    command = [
        args.binary, "gui", args.scene, "--window-size", args.window,
        "--screenshot", os.path.join(args.out, "final.png"),
        "--toggle", args.toggle, "--repeat", str(args.switches),
    ]
    env = dict(os.environ, DISPLAY=display)
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")
    print("running:", " ".join(command), flush=True)
    start = time.time()
    try:
        done = subprocess.run(command, env=env, capture_output=True, text=True,
                              timeout=args.timeout)
    finally:
        if xvfb is not None:
            stop_xvfb(xvfb)
    log = done.stdout + done.stderr
    with open(os.path.join(args.out, "explorer.log"), "w") as f:
        f.write(log)
    if done.returncode != 0:
        print(log[-3000:], file=sys.stderr)
        fail(f"the explorer exited with {done.returncode}")

    resident = series(log, "resident memory after each recording shown")
    heap = series(log, "Rust heap (ours and the viewer's) after each recording shown")
    bound = re.search(r"run cache ([\d.]+) of its (\d+) MiB bound", log)
    if resident is None or heap is None or bound is None:
        print(log[-3000:], file=sys.stderr)
        fail("the explorer did not print its memory series (is the binary built with "
             "--features gui, whose accounting allocator counts the heap?)")
    if len(resident) != args.switches + 1 or len(heap) != len(resident):
        fail(f"{len(resident)} resident and {len(heap)} heap samples for "
             f"{args.switches + 1} recordings shown")
    cache_bound = float(bound.group(2))
    resident_growth = resident[-1] - resident[0]
    heap_growth = heap[-1] - heap[1]
    summary = {
        "scene": args.scene, "switches": args.switches, "seconds": time.time() - start,
        "mesa_vulkan_drivers": mesa_version(),
        "resident_mib": resident, "heap_mib": heap,
        "resident_growth_mib": resident_growth, "cache_bound_mib": cache_bound,
        "heap_growth_from_first_switch_mib": heap_growth, "heap_bound_mib": args.heap_mib,
    }
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(f"{args.switches} switches on {args.scene} (Mesa {summary['mesa_vulkan_drivers']}): "
          f"resident {resident[0]:.0f} -> {resident[-1]:.0f} MiB (growth {resident_growth:.0f}, "
          f"bound {cache_bound:.0f}); Rust heap {heap[0]:.0f} -> {heap[1]:.0f} after the first "
          f"switch -> {heap[-1]:.0f} MiB (growth {heap_growth:+.1f} from the first switch, "
          f"bound {args.heap_mib:.0f})")
    if resident_growth > cache_bound:
        fail(f"resident memory grew {resident_growth:.0f} MiB over {args.switches} switches, "
             f"more than the cache's bound of {cache_bound:.0f} MiB (a graphics driver that "
             f"leaks per frame? see this script's help)")
    if heap_growth > args.heap_mib:
        fail(f"the Rust heap grew {heap_growth:.1f} MiB from the first switch to the last "
             f"(bound {args.heap_mib:.0f}): something keeps each recording")
    print("check_memory: both bounds hold")


if __name__ == "__main__":
    main()
