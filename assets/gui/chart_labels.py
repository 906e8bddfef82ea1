#!/usr/bin/env python3
"""A look at a screenshot of the explorer (or of `flexmodes view FILE --screenshot`): every
text label the viewer draws in a 2-D chart view, and every plot legend, sits clear of the data
and of every other label.

    python3 assets/gui/chart_labels.py target/gui-check/l-bracket/final.png ...
    python3 assets/gui/chart_labels.py --self-test target/gui-check/l-bracket/final.png
    python3 assets/gui/chart_labels.py --recordings target/ci-recordings \
        --binary target/debug/flexmodes --out target/gui-check/recordings

With --recordings every `.rrd` in the folder is opened by `flexmodes view FILE --screenshot`
(the gui build) under a private Xvfb, in both themes, and each screenshot is checked (the
viewer alone: no explorer panel).

The viewer (Rerun 0.36) draws a label as its text on a rounded box of one translucent colour,
6 px wider and 4 px taller than the text on each side; on a 2-D view's plain background that
box is one exact colour per theme (BOX below). So a label is a connected patch of that colour,
and what it covers shows in it:

- its margin (the box less the text's rectangle) holds nothing but the box colour: a curve, a
  bar, a grid line or another label's box under or over it changes those pixels (two
  translucent boxes overlapping are darker where they overlap);
- inside the margin every pixel lies between the box colour and the one text colour (glyph
  edges blend the two): a data point of another colour under the text does not.

A plot view's legend (the bar chart's and the histories', drawn by egui's plots) is a frame of
its own colour on the dark theme (on the light one it is the plot's white and cannot be told
from it): its margin is checked the same way, so bars or curves behind it are found.

Each problem is printed with the screenshot, the label's box in pixels and what was found; the
exit status is 1 if any. --self-test draws a curve across a label, a second label overlapping
one, and a bar behind a plot legend into copies of the given screenshots, and fails unless
each copy is caught: a check that cannot fail proves nothing.
"""

import argparse
import glob
import os
import subprocess
import sys

import numpy as np
from PIL import Image, ImageDraw
from scipy import ndimage

# The plain background of a 2-D view and the colour of a label's box on it, per theme
# (Rerun 0.36.3, measured in the explorer's and the viewer's screenshots).
BACKGROUND = {"dark": (0, 0, 0), "light": (255, 255, 255)}
BOX = {"dark": (22, 22, 22), "light": (239, 239, 239)}
# The colour the box is drawn in at half opacity (BOX = half FILL over the background; where
# two boxes overlap the viewer shows half FILL over BOX: 33 and 231).
FILL = {"dark": (44, 44, 44), "light": (223, 223, 223)}
# A plot legend's frame (dark theme only: on the light one it is the plot's white).
PLOT_LEGEND = {"dark": (33, 33, 33)}
# A box is at least this tall and wide, px (one line of text at the viewer's 18 px font,
# with its margins: 26 px; a one-character label 20 px wide).
MIN_BOX = 16
# The margin checked on each side of a box, px (the viewer's is 4 above and below, 6 left and
# right), and the corner left out of it (the box's corners are rounded with radius 4).
MARGIN = (2, 3)
CORNER = 6
# A pixel inside a box is foreign when it lies farther than this from every blend of the box
# colour and the text colour (0–255 per channel; glyph edges are blended in linear light, so
# they bow away from the straight line in sRGB by up to ~25).
FOREIGN = 45
# A plot legend's margin counts only pixels at least this far from grey (max − min channel):
# bars and curves are in the methods' colours, the grid behind the legend is grey.
CHROMA = 24
# A plot legend is at least this tall, px (one entry and its margins; a view's tab bar, of the
# same colour, is 25).
MIN_PLOT_LEGEND = 30
# Foreign pixels tolerated per box (anti-aliasing at a rounded corner).
TOLERATED = 2


def theme_of(pixels):
    """dark or light: whichever plain 2-D background is more common."""
    dark = np.all(pixels == BACKGROUND["dark"], axis=2).sum()
    light = np.all(pixels == BACKGROUND["light"], axis=2).sum()
    return "dark" if dark >= light else "light"


def patches(pixels, colour, min_size=MIN_BOX, solid=False):
    """Connected patches of exactly `colour` (±1) at least `min_size` px each way and mostly
    that colour: (top, bottom, left, right) inclusive. `solid`: only the parts at least 5 px
    thick count (a plot's grid lines share its legend's colour and would join it)."""
    mask = np.all(np.abs(pixels.astype(int) - colour) <= 1, axis=2)
    if solid:
        mask = ndimage.binary_opening(mask, structure=np.ones((5, 5), dtype=bool))
    labelled, _ = ndimage.label(mask)
    found = []
    for index, window in enumerate(ndimage.find_objects(labelled), start=1):
        if window is None:
            continue
        rows, cols = window
        h, w = rows.stop - rows.start, cols.stop - cols.start
        if h < min_size or w < min_size:
            continue
        if (labelled[window] == index).sum() < 0.4 * h * w:
            continue
        found.append((rows.start, rows.stop - 1, cols.start, cols.stop - 1))
    return found


def rounded(pixels, box, colour):
    """Whether a patch has a rounded corner, as the viewer's label boxes and plot legends do
    (a text view's table rows, of the same colour, are square)."""
    top, bottom, left, right = box
    same = lambda y, x: np.abs(pixels[y, x].astype(int) - colour).max() <= 1
    corners = [(top, left, top, left + CORNER), (top, right, top, right - CORNER),
               (bottom, left, bottom, left + CORNER), (bottom, right, bottom, right - CORNER)]
    return any(not same(y, x) and same(y2, x2) for y, x, y2, x2 in corners)


def on_view_background(pixels, box, theme):
    """Whether most of the band of 2 px around a patch is a 2-D view's background (a label
    on a chart; a striped table row of a text view has that view's own grey around it)."""
    top, bottom, left, right = box
    h, w, _ = pixels.shape
    t, b, l, r = max(top - 2, 0), min(bottom + 2, h - 1), max(left - 2, 0), min(right + 2, w - 1)
    band = np.concatenate([pixels[t:top, l:r + 1].reshape(-1, 3),
                           pixels[bottom + 1:b + 1, l:r + 1].reshape(-1, 3),
                           pixels[top:bottom + 1, l:left].reshape(-1, 3),
                           pixels[top:bottom + 1, right + 1:r + 1].reshape(-1, 3)])
    if len(band) == 0:
        return False
    return np.all(band == BACKGROUND[theme], axis=1).mean() > 0.5


def label_boxes(pixels, theme):
    """The label boxes: rounded patches of the box colour on a 2-D view's background."""
    return [b for b in patches(pixels, BOX[theme])
            if rounded(pixels, b, BOX[theme]) and on_view_background(pixels, b, theme)]


def margin_problems(pixels, box, colour, coloured_only=False):
    """Pixels of the box's margin (less its rounded corners) that are not the box colour
    (`coloured_only`: and not grey either, as a plot's grid lines behind its legend are)."""
    top, bottom, left, right = box
    inside = pixels[top:bottom + 1, left:right + 1].astype(int)
    region = np.abs(inside - colour).max(axis=2) > 1
    if coloured_only:
        region &= (inside.max(axis=2) - inside.min(axis=2)) > CHROMA
    my, mx = MARGIN
    ring = np.zeros_like(region)
    ring[:my, CORNER:-CORNER] = True
    ring[-my:, CORNER:-CORNER] = True
    ring[CORNER:-CORNER, :mx] = True
    ring[CORNER:-CORNER, -mx:] = True
    hits = np.argwhere(region & ring)
    return [(int(top + y), int(left + x)) for y, x in hits]


def foreign_inside(pixels, box, colour):
    """Pixels inside the box that are no blend of the box colour and its text colour."""
    top, bottom, left, right = box
    inside = pixels[top:bottom + 1, left:right + 1].astype(float)
    x = np.array(colour, dtype=float)
    distance = np.linalg.norm(inside - x, axis=2)
    if distance.max() < 8:
        return []
    # The text colour: the pixel farthest from the box colour.
    ty, tx = np.unravel_index(np.argmax(distance), distance.shape)
    t = inside[ty, tx]
    d = t - x
    s = np.clip(((inside - x) @ d) / max(d @ d, 1e-9), 0.0, 1.0)
    off = np.linalg.norm(inside - (x + s[..., None] * d), axis=2)
    hits = np.argwhere(off > FOREIGN)
    return [(int(top + y), int(left + x_)) for y, x_ in hits]


def plot_legends(pixels, theme):
    """The plot legends' frames: solid patches of their colour, tall enough, with rounded
    corners (a view's tab bar, of the same colour, is square)."""
    colour = PLOT_LEGEND[theme]
    # A bar through the whole legend cuts it in two: parts with the same top and bottom a few
    # pixels apart are one legend (the bar then lies in its margin).
    parts = sorted(patches(pixels, colour, min_size=4, solid=True), key=lambda b: (b[0], b[2]))
    joined = []
    for box in parts:
        last = joined[-1] if joined else None
        if (last and abs(last[0] - box[0]) <= 2 and abs(last[1] - box[1]) <= 2
                and 0 <= box[2] - last[3] <= 40):
            joined[-1] = (min(last[0], box[0]), max(last[1], box[1]), last[2], box[3])
        else:
            joined.append(box)
    return [b for b in joined
            if b[1] - b[0] + 1 >= MIN_PLOT_LEGEND and b[3] - b[2] + 1 >= MIN_BOX
            and rounded(pixels, b, colour)]


def clean_boxes(pixels, theme):
    """The label boxes with nothing found in them (the ones a fault is drawn into)."""
    colour = BOX[theme]
    return [b for b in label_boxes(pixels, theme)
            if len(margin_problems(pixels, b, colour)) <= TOLERATED
            and len(foreign_inside(pixels, b, colour)) <= TOLERATED]


def viewer_area(pixels, panel):
    """The viewer's part of the explorer's window (right of its panel, below the top bar,
    above the time panel); a `view` screenshot has no panel (panel 0)."""
    h, w, _ = pixels.shape
    return pixels[70:h - 40, panel:w], (70, panel)


def check(path, panel=340, theme=None):
    """Problems found in one screenshot, and the number of labels and legends checked."""
    image = np.asarray(Image.open(path).convert("RGB"))
    pixels, (oy, ox) = viewer_area(image, panel)
    theme = theme or theme_of(pixels)
    problems = []
    checked = 0
    kinds = [("label", BOX[theme], label_boxes(pixels, theme))]
    if theme in PLOT_LEGEND:
        kinds.append(("plot legend", PLOT_LEGEND[theme], plot_legends(pixels, theme)))
    for kind, colour, boxes in kinds:
        inside = kind == "label"
        for box in boxes:
            checked += 1
            where = (f"{kind} box x {box[2] + ox}–{box[3] + ox}, y {box[0] + oy}–"
                     f"{box[1] + oy}")
            ring = margin_problems(pixels, box, colour, coloured_only=not inside)
            if len(ring) > TOLERATED:
                y, x = ring[0]
                problems.append(f"{path}: {where}: {len(ring)} pixels of its margin are not "
                                f"its box (something under or over it; first at x {x + ox}, "
                                f"y {y + oy}: {tuple(int(v) for v in pixels[y, x])})")
                continue
            if inside:
                odd = foreign_inside(pixels, box, colour)
                if len(odd) > TOLERATED:
                    y, x = odd[0]
                    problems.append(f"{path}: {where}: {len(odd)} pixels inside are neither "
                                    f"its box nor its text (first at x {x + ox}, y {y + oy}: "
                                    f"{tuple(int(v) for v in pixels[y, x])})")
    return problems, checked, theme


def spoiled(path, out, panel=340):
    """Copies of a screenshot with one fault drawn in each; (copy, fault) pairs."""
    image = Image.open(path).convert("RGB")
    pixels, (oy, ox) = viewer_area(np.asarray(image), panel)
    theme = theme_of(pixels)
    boxes = clean_boxes(pixels, theme)
    copies = []
    if boxes:
        # A curve of another colour drawn across the widest label.
        top, bottom, left, right = max(boxes, key=lambda b: b[3] - b[2])
        crossed = image.copy()
        ImageDraw.Draw(crossed).line(
            [(left + ox - 10, top + oy - 8), (right + ox + 10, bottom + oy + 8)],
            fill=(230, 120, 0), width=2)
        copies.append((crossed, "a curve across a label"))
        # A second label's translucent box overlapping it by half its width.
        overlapped = image.copy()
        h, w = bottom - top + 1, right - left + 1
        layer = Image.new("RGBA", image.size, (0, 0, 0, 0))
        ImageDraw.Draw(layer).rounded_rectangle(
            [left + ox + w // 2, top + oy + h // 3, left + ox + w // 2 + w, top + oy + h // 3 + h],
            radius=4, fill=FILL[theme] + (128,))
        overlapped = Image.alpha_composite(overlapped.convert("RGBA"), layer).convert("RGB")
        copies.append((overlapped, "a label overlapping a label"))
        # A data point of another colour under a label's text, clear of its margin.
        dotted = image.copy()
        cy, cx = (top + bottom) // 2 + oy, (left + right) // 2 + ox
        ImageDraw.Draw(dotted).ellipse([cx - 2, cy - 2, cx + 2, cy + 2], fill=(30, 150, 60))
        copies.append((dotted, "a point under a label's text"))
    if theme in PLOT_LEGEND:
        legends = plot_legends(pixels, theme)
        if legends:
            top, bottom, left, right = legends[0]
            barred = image.copy().convert("RGBA")
            layer = Image.new("RGBA", image.size, (0, 0, 0, 0))
            # A bar rising from below to a third of the legend's height, and one through it.
            third = (bottom - top) // 3
            draw = ImageDraw.Draw(layer)
            draw.rectangle([left + ox + 12, bottom + oy - third, left + ox + 20, bottom + oy + 30],
                           fill=(150, 90, 40, 120))
            draw.rectangle([right + ox - 30, top + oy - 30, right + ox - 22, bottom + oy + 30],
                           fill=(40, 110, 230, 120))
            barred = Image.alpha_composite(barred, layer).convert("RGB")
            copies.append((barred, "a bar behind a plot legend"))
    written = []
    for n, (copy, fault) in enumerate(copies):
        name = f"{out}-spoiled-{n}.png"
        copy.save(name)
        written.append((name, fault))
    return written


def screenshots_of_recordings(folder, binary, out, window):
    """`flexmodes view FILE --screenshot` of every recording in `folder`, dark and light,
    under a private Xvfb; the screenshots' paths (failing if one is not written)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import check_switches  # noqa: E402 (its Xvfb helpers)

    recordings = sorted(glob.glob(os.path.join(folder, "*.rrd")))
    if not recordings:
        print(f"chart_labels: FAILED: no recording in {folder}", file=sys.stderr)
        sys.exit(1)
    os.makedirs(out, exist_ok=True)
    display, xvfb = check_switches.start_xvfb("2600x1800")
    written = []
    try:
        for rrd in recordings:
            for theme in ("dark", "light"):
                name = os.path.basename(rrd)[:-4]
                shot = os.path.join(out, f"{name}-{theme}.png")
                env = dict(os.environ, DISPLAY=display, HOME=os.path.join(out, "home"))
                env.setdefault("XDG_RUNTIME_DIR", "/tmp")
                done = subprocess.run(
                    [binary, "view", rrd, "--screenshot", shot, "--window-size", window,
                     "--theme", theme],
                    env=env, capture_output=True, text=True, timeout=600)
                if done.returncode != 0 or not os.path.exists(shot):
                    print((done.stdout + done.stderr)[-2000:], file=sys.stderr)
                    print(f"chart_labels: FAILED: no screenshot of {rrd} ({theme})",
                          file=sys.stderr)
                    sys.exit(1)
                written.append(shot)
    finally:
        check_switches.stop_xvfb(xvfb)
    return written


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("screenshots", nargs="*")
    p.add_argument("--recordings", help="screenshot every .rrd in this folder and check them")
    p.add_argument("--binary", default="target/debug/flexmodes",
                   help="with --recordings: the gui build that opens them")
    p.add_argument("--out", default="target/gui-check/recordings",
                   help="with --recordings: where the screenshots go")
    p.add_argument("--window", default="1280x800")
    p.add_argument("--panel", type=int, default=340,
                   help="width of the explorer's panel left of the viewer, px (0 for `view`)")
    p.add_argument("--self-test", action="store_true",
                   help="check spoiled copies of the screenshots: each must be caught")
    args = p.parse_args()
    failed = False
    shots = [(path, args.panel) for path in args.screenshots]
    if args.recordings:
        shots += [(path, 0) for path in screenshots_of_recordings(
            args.recordings, args.binary, args.out, args.window)]
    if not shots:
        p.error("no screenshot given and no --recordings")
    total = 0
    for path, panel in shots:
        args.panel = panel
        problems, checked, theme = check(path, args.panel)
        total += checked
        if checked == 0 and panel != 0:
            print(f"chart_labels: FAILED: {path}: no label found ({theme} theme): the check "
                  "saw nothing to check", file=sys.stderr)
            failed = True
        elif checked == 0:
            print(f"{path}: no chart labels or plot legends ({theme} theme)")
        for problem in problems:
            print(f"chart_labels: {problem}", file=sys.stderr)
            failed = True
        if not problems and checked:
            print(f"{path}: {checked} labels and legends ({theme} theme), each clear of the "
                  "data and of the others")
        if args.self_test:
            stem = path[:-4] if path.endswith(".png") else path
            known = {p.split(": ", 1)[1] for p in problems}
            for copy, fault in spoiled(path, stem, args.panel):
                found, _, _ = check(copy, args.panel)
                caught = [p for p in found if p.split(": ", 1)[1] not in known]
                if caught:
                    print(f"{copy}: {fault}: caught ({caught[0].split(': ', 1)[1][:90]}…)")
                else:
                    print(f"chart_labels: FAILED: {copy}: {fault} drawn, not caught",
                          file=sys.stderr)
                    failed = True
    if total == 0:
        print("chart_labels: FAILED: no label in any screenshot", file=sys.stderr)
        failed = True
    if failed:
        sys.exit(1)
    print(f"ok: {total} labels and legends in {len(shots)} screenshots")


if __name__ == "__main__":
    main()
