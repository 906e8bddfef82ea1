#!/usr/bin/env python3
"""`flexmodes serve` checked as a person would use it: start the server on a free loopback
port, open its URL in Debian's headless Chromium (software rendering: SwiftShader through
ANGLE, the viewer's WebGL renderer), wait until the viewer reports the served recording active
and has not panicked, stop the mode animation at a phase, take a screenshot and count each
shown method's colour in it. Exits non-zero with the reason when anything fails; keeps the
screenshot.

    apt-get install chromium; python3 -m pip install -r assets/serve/requirements.txt
    cargo build --release --features serve
    python3 assets/serve/check_serve.py --binary target/release/flexmodes --bind 127.0.0.2 \\
        --theme light --out target/serve-light.png

No traffic leaves the loopback range: the server binds a 127.x address, Chromium runs with
its background networking off, and the page links nothing outside (the server strips the
web-font links).
"""

import argparse
import base64
import colorsys
import io
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

import websocket
from PIL import Image

# The methods' colours (src/scenes/mode_visuals.rs, method_color; a Rust test keeps the two
# equal).
PALETTE = {
    "nr": (120, 120, 150),
    "gr": (230, 120, 0),
    "mt": (210, 50, 50),
    "cb": (40, 110, 230),
    "mc": (30, 150, 60),
    "eit": (160, 70, 200),
    "mr": (220, 60, 140),
    "bh": (0, 150, 160),
    "mm": (150, 150, 0),
    "bt": (150, 90, 40),
}


def fail(message):
    print(f"check_serve: FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def free_port(address):
    with socket.socket() as s:
        s.bind((address, 0))
        return s.getsockname()[1]


class Cdp:
    """A minimal Chrome DevTools Protocol client on one page target."""

    def __init__(self, ws_url):
        self.ws = websocket.create_connection(ws_url, timeout=120)
        self.next_id = 0

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            reply = json.loads(self.ws.recv())
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    fail(f"{method}: {reply['error']}")
                return reply.get("result", {})

    def evaluate(self, expression):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True)
        if "exceptionDetails" in result:
            return None
        return result.get("result", {}).get("value")


def refused(binary, args, says, code_wanted=True):
    """`flexmodes serve ARGS` exits non-zero at once, naming `says`, with no stack trace."""
    done = subprocess.run([binary, "serve", *args], capture_output=True, text=True, timeout=120,
                          stdin=subprocess.DEVNULL)
    if done.returncode == 0 or says not in done.stderr or "panicked" in done.stderr:
        fail(f"serve {' '.join(args)}: exit {done.returncode}, stderr {done.stderr!r}; "
             f"wanted an error naming {says!r}")
    print(f"refused as it should: serve {' '.join(args)} -> {done.stderr.strip()}")


def bad_input(binary, address):
    """A port in use, an unknown scene, a control token too short, a missing and a corrupt
    recording."""
    with socket.socket() as held:
        held.bind((address, 0))
        held.listen()
        port = held.getsockname()[1]
        refused(binary, ["slab-modes", "--bind", address, "--port", str(port),
                         "--grpc-port", str(free_port(address))], "in use")
    refused(binary, ["no-such-scene", "--bind", address], "no-such-scene")
    refused(binary, ["slab-modes", "--bind", address, "--control-token", "short"],
            "--control-token")
    with tempfile.TemporaryDirectory() as tmp:
        missing = os.path.join(tmp, "missing.rrd")
        refused(binary, ["--file", missing, "--bind", address], "missing.rrd")
        # A recording's header with garbage behind it (Rerun's own `rrd verify` passes it).
        good = os.path.join(tmp, "good.rrd")
        subprocess.run([binary, "record", "beam-modes", "--save", good], check=True,
                       capture_output=True)
        data = bytearray(open(good, "rb").read())
        for k in range(64, len(data), 7):
            data[k] ^= 0x5A
        corrupt = os.path.join(tmp, "corrupt.rrd")
        open(corrupt, "wb").write(bytes(data))
        refused(binary, ["--file", corrupt, "--bind", address], "corrupt.rrd")


def printed_url(server, prefix):
    """The URL ending the first line the server prints that starts with `prefix`."""
    while True:
        line = server.stdout.readline()
        if not line:
            fail(f"the server stopped before printing `{prefix}`: {server.stderr.read()}")
        if line.startswith(prefix):
            return line.rsplit(" ", 1)[1].strip()


ACTIVE = "window._handle.get_active_recording_id() ?? null"


def http_status(request):
    """The HTTP status and body of `request` (urllib raises on 4xx: caught)."""
    try:
        with urllib.request.urlopen(request, timeout=30) as r:
            return r.status, r.read().decode()
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode()


def check_control(args, control_url, debug_port, cdp):
    """The teacher's control page: without the token 403 and the view unchanged; requests that
    do not parse named on the page; with the token, the form filled and submitted in a second
    tab of the same browser and the viewer following within `--control-within` seconds."""
    base = control_url.split("?", 1)[0]
    before = cdp.evaluate(ACTIVE)
    for what, request in [
        ("GET without the token", urllib.request.Request(base)),
        ("GET with a wrong token", urllib.request.Request(base + "?token=0123456789abcdef0123")),
        ("POST without the token", urllib.request.Request(
            base, data=b"scene=beam-modes&method=cb", method="POST")),
    ]:
        status, _ = http_status(request)
        if status != 403:
            fail(f"control page, {what}: HTTP {status}, wanted 403")
    time.sleep(3.0)
    if cdp.evaluate(ACTIVE) != before:
        fail(f"the view changed after requests without the token ({before} -> "
             f"{cdp.evaluate(ACTIVE)})")
    print("control page without the token: 403 (GET, a wrong token, POST), the view unchanged")
    token = control_url.split("token=", 1)[1]
    for form, says in [("scene=no-such-scene", "unknown scene `no-such-scene`"),
                       ("scene=beam-modes&modes=x", "invalid value"),
                       ("scene=beam-modes&colour=red", "unknown field `colour`")]:
        status, page = http_status(urllib.request.Request(
            base, data=f"token={token}&{form}".encode(), method="POST"))
        if status != 400 or says not in page.replace("&#39;", "'"):
            fail(f"control page, `{form}`: HTTP {status}, wanted 400 naming {says!r}")
    time.sleep(1.0)
    if cdp.evaluate(ACTIVE) != before:
        fail("the view changed after requests that do not parse")
    print("control page refuses by name: an unknown scene, a bad value, an unknown field")
    tab = json.load(urllib.request.urlopen(urllib.request.Request(
        f"http://127.0.0.1:{debug_port}/json/new?{control_url}", method="PUT")))
    control = Cdp(tab["webSocketDebuggerUrl"])
    for _ in range(100):
        if control.evaluate("document.readyState === 'complete' && !!document.querySelector('form')"):
            break
        time.sleep(0.1)
    else:
        fail("the control page did not load in Chromium")
    control.evaluate(
        f"document.querySelector('select[name=scene]').value = {json.dumps(args.control_scene)};"
        "document.querySelector('input[name=method]').value = 'cb';"
        "document.querySelector('form').submit(); true")
    submitted = time.time()
    cdp.call("Page.bringToFront")
    followed = None
    while time.time() - submitted < 60:
        now = cdp.evaluate(ACTIVE)
        if now and now != before and args.control_scene in now:
            followed = time.time() - submitted
            break
        time.sleep(0.1)
    answer = control.evaluate(
        "(document.querySelector('.ok') || document.querySelector('.error') || {}).textContent")
    if followed is None:
        fail(f"the viewer did not follow the control page within 60 s (the page says {answer!r})")
    print(f"control page in Chromium: {answer!r}; the viewer followed to {now} in {followed:.1f} s")
    shot = base64.b64decode(control.call("Page.captureScreenshot", format="png")["data"])
    stem = os.path.splitext(args.out)[0]
    open(f"{stem}-control.png", "wb").write(shot)
    if followed > args.control_within:
        fail(f"the viewer followed after {followed:.1f} s, more than {args.control_within} s")


def show_recording(cdp, wanted, tries=40):
    """Makes `wanted` the viewer's active recording, or fails naming what it shows.

    The viewer's handle does nothing, silently, when it is asked while a frame holds the app
    (or before the recording is in its store): it is asked again until it shows the recording.
    """
    shown = None
    for _ in range(tries):
        cdp.evaluate(f"window._handle.set_active_recording_id({json.dumps(wanted)})")
        time.sleep(0.25)
        shown = cdp.evaluate("window._handle.get_active_recording_id() ?? null")
        if shown == wanted:
            return
    fail(f"the viewer did not show {wanted} after {tries} requests (it shows {shown})")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--binary", required=True, help="flexmodes built with --features serve")
    p.add_argument("--bind", default="127.0.0.1")
    p.add_argument("--scene", default="slab-modes")
    p.add_argument("--methods", default="gr,cb,mc",
                   help="the scene's reduced models; the full model (nr) is counted too")
    p.add_argument("--theme", choices=["dark", "light"], default="dark")
    p.add_argument("--phase", type=float, default=0.25, help="the mode animation's phase, 0-1")
    p.add_argument("--share", type=float, default=0.002,
                   help="least fraction of the screenshot's pixels each method's colour covers")
    p.add_argument("--out", default="serve-check.png")
    p.add_argument("--timeout", type=float, default=240.0)
    p.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    p.add_argument("--control", action="store_true",
                   help="also drive the teacher's control page: refused without the token, "
                        "followed with it")
    p.add_argument("--control-scene", default="beam-modes",
                   help="the scene the control page shows")
    p.add_argument("--control-within", type=float, default=2.0,
                   help="most seconds from the form's submission to the viewer showing it")
    p.add_argument("--every-scene", action="store_true",
                   help="serve every scene and show each in turn: active, no panic")
    p.add_argument("--bad-input", action="store_true",
                   help="first check that bad input is refused by name")
    args = p.parse_args()
    if not args.bind.startswith("127."):
        fail(f"--bind {args.bind}: the check stays on the loopback range (127.x)")
    if args.bad_input:
        bad_input(args.binary, args.bind)
    port, grpc_port = free_port(args.bind), free_port(args.bind)
    started = time.time()
    server = subprocess.Popen(
        [args.binary, "serve",
         *([] if args.every_scene else [args.scene, "--method", args.methods]),
         "--bind", args.bind, "--port", str(port), "--grpc-port", str(grpc_port),
         "--theme", args.theme],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    url = printed_url(server, "open in a browser: ")
    served = time.time() - started
    print(f"serve: {url} after {served:.1f} s")
    control_url = printed_url(server, "control page")

    profile = tempfile.mkdtemp(prefix="check-serve-")
    debug_port = free_port("127.0.0.1")
    chromium = subprocess.Popen(
        [args.chromium, "--headless=new", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--no-sandbox", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--disable-quic",
         "--disable-default-apps", "--window-size=1280,800", f"--user-data-dir={profile}",
         f"--remote-debugging-port={debug_port}", "about:blank"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        target = None
        for _ in range(100):
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{debug_port}/json") as r:
                    pages = [t for t in json.load(r) if t["type"] == "page"]
                if pages:
                    target = pages[0]["webSocketDebuggerUrl"]
                    break
            except OSError:
                pass
            time.sleep(0.2)
        if target is None:
            fail("chromium's remote-debugging port never answered")
        cdp = Cdp(target)
        cdp.call("Page.enable")
        cdp.call("Emulation.setDeviceMetricsOverride", width=1280, height=800,
                 deviceScaleFactor=1, mobile=False)
        cdp.call("Emulation.setEmulatedMedia",
                 features=[{"name": "prefers-color-scheme", "value": args.theme}])
        cdp.call("Page.navigate", url=url)
        opened = time.time()
        state = None
        while time.time() - opened < args.timeout:
            state = cdp.evaluate(
                "window._handle ? {rec: window._handle.get_active_recording_id() ?? null, "
                "panicked: window._handle.has_panicked()} : null")
            if state and state["panicked"]:
                fail(f"the viewer panicked: {cdp.evaluate('window._handle.panic_message()')}")
            if state and state["rec"]:
                break
            time.sleep(1.0)
        else:
            fail(f"no active recording after {args.timeout:.0f} s (last state {state})")
        recording = state["rec"]
        active = time.time() - started
        print(f"viewer: recording {recording} active {active:.1f} s after serve started")
        if args.every_scene:
            listed = subprocess.run([args.binary, "list"], capture_output=True, text=True,
                                    check=True).stdout.splitlines()
            ids = [line.split()[0] for line in listed if line.strip()]
            # The viewer follows each recording as it arrives: wait for the last one.
            last, shown = f"flexmodes-{ids[-1]}", None
            for _ in range(480):
                shown = cdp.evaluate("window._handle.get_active_recording_id() ?? null")
                if shown == last:
                    break
                time.sleep(0.25)
            else:
                fail(f"the viewer never reached the last recording {last} (it shows {shown})")
            print(f"viewer: every recording arrived {time.time() - started:.1f} s after serve started")
            for scene in ids:
                wanted = f"flexmodes-{scene}"
                show_recording(cdp, wanted)
                time.sleep(0.5)  # a few of the viewer's frames on the recording
                if cdp.evaluate("window._handle.has_panicked()"):
                    fail(f"the viewer panicked on {wanted}: "
                         f"{cdp.evaluate('window._handle.panic_message()')}")
                shot = base64.b64decode(cdp.call("Page.captureScreenshot", format="png")["data"])
                stem = os.path.splitext(args.out)[0]
                os.makedirs(os.path.dirname(os.path.abspath(stem)), exist_ok=True)
                open(f"{stem}-{scene}.png", "wb").write(shot)
            print(f"every scene shown without a panic: {', '.join(ids)}")
            recording = f"flexmodes-{args.scene}"
            show_recording(cdp, recording)
        # Stop the mode animation at a phase (the timeline runs over the phase steps).
        span = None
        for _ in range(60):  # the data arrives after the recording is active
            span = cdp.evaluate(
                f"JSON.stringify(window._handle.get_timeline_time_range({json.dumps(recording)}, 'phase'))")
            span = json.loads(span) if span else None
            if span:
                break
            time.sleep(0.5)
        cdp.evaluate(f"window._handle.set_playing({json.dumps(recording)}, false)")
        cdp.evaluate(f"window._handle.set_active_timeline({json.dumps(recording)}, 'phase')")
        print(f"phase timeline: {span}")
        if span and "min" in span and "max" in span:
            t = round(span["min"] + args.phase * (span["max"] - span["min"]))
            cdp.evaluate(f"window._handle.set_time_for_timeline({json.dumps(recording)}, 'phase', {t})")
            for _ in range(40):  # applied on the viewer's next frame
                now = cdp.evaluate(
                    f"window._handle.get_time_for_timeline({json.dumps(recording)}, 'phase')")
                if now is not None and abs(now - t) <= 0.5:
                    break
                time.sleep(0.25)
            if now is None or abs(now - t) > 0.5:
                fail(f"the phase did not stop at {t} (the viewer says {now})")
        else:
            fail(f"the recording has no phase timeline ({span})")
        # Frames render slowly in software: wait until two screenshots in a row agree.
        previous, image = None, None
        for _ in range(30):
            time.sleep(2.0)
            shot = base64.b64decode(cdp.call("Page.captureScreenshot", format="png")["data"])
            if shot == previous:
                break
            previous = shot
        image = Image.open(io.BytesIO(previous)).convert("RGB")
        if cdp.evaluate("window._handle.has_panicked()"):
            fail("the viewer panicked while rendering")
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        image.save(args.out)
        total = image.width * image.height
        counts = {m: 0 for m in ["nr"] + args.methods.split(",")}
        targets = {m: colorsys.rgb_to_hsv(*(v / 255 for v in PALETTE[m])) for m in counts}
        for n, (r, g, b) in image.getcolors(total):
            h, s, v = colorsys.rgb_to_hsv(r / 255, g / 255, b / 255)
            for m, (th, ts, tv) in targets.items():
                # The colour, or its tint on either theme's background (bars are drawn
                # translucent): the same hue, at least half the saturation.
                dh = min(abs(h - th), 1 - abs(h - th))
                if dh <= 12 / 360 and ts * 0.5 <= s <= ts * 1.3 + 0.05 and v >= 0.25:
                    counts[m] += n
        shares = {m: n / total for m, n in counts.items()}
        print(f"screenshot {args.out} ({image.width}x{image.height}, {args.theme}): "
              + ", ".join(f"{m} {s:.2%}" for m, s in shares.items()))
        thin = [m for m, s in shares.items() if s < args.share]
        if thin:
            fail(f"{', '.join(thin)} cover(s) less than {args.share:.2%} of the page")
        # The teacher shows the scene again with other options: the viewer follows.
        server.stdin.write(f"show {args.scene} --method cb --modes 4\n")
        server.stdin.flush()
        switched = time.time()
        while time.time() - switched < 60:
            now = cdp.evaluate("window._handle.get_active_recording_id() ?? null")
            if now and now != recording:
                print(f"teacher's `show`: the viewer followed to {now} in "
                      f"{time.time() - switched:.1f} s")
                break
            time.sleep(0.5)
        else:
            fail("the viewer did not follow the teacher's `show` within 60 s")
        if args.control:
            check_control(args, control_url, debug_port, cdp)
    finally:
        chromium.kill()
        chromium.wait()
        shutil.rmtree(profile, ignore_errors=True)
        if server.poll() is None:
            server.stdin.write("quit\n")
            server.stdin.flush()
            try:
                code = server.wait(timeout=20)
            except subprocess.TimeoutExpired:
                server.kill()
                fail("the server did not stop on `quit`")
            if code != 0:
                fail(f"the server stopped with exit code {code}")
    print(f"ok: {time.time() - started:.1f} s in all")


if __name__ == "__main__":
    main()
