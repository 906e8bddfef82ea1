"""Compare screenshots of the explorer taken during a switch with the pictures before and
after it: a frame that matches neither is a half-drawn state (views empty, meshes stacked,
plots without their lines).

A picture is summarised by where each method's colour is: the viewer's part of the window
is cut into tiles, and each tile counts the pixels near each method's colour. Two pictures
of the same complete result differ only by the animation (bodies move within their lanes,
the time cursor moves), so their tile counts stay close; a half-drawn picture loses whole
tiles of a colour or moves them.
"""

import colorsys

from PIL import Image

# One colour per method, as src/scenes/mode_visuals.rs::method_color gives them (a test
# there checks the serve check's copy; this one is checked against that copy in CI).
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

TILES = (8, 5)


def viewer_box(image, panel):
    """The viewer's part of a screenshot: right of the explorer's panel, below the top bar
    and tab titles, above the time panel; without the badge at the top right."""
    w, h = image.size
    return (panel, 70, w, h - 40)


def summary(path, panel=340):
    """Tile counts: {(tile_x, tile_y, method): pixels}."""
    image = Image.open(path).convert("RGB")
    box = viewer_box(image, panel)
    image = image.crop(box).reduce(2)
    w, h = image.size
    targets = {m: colorsys.rgb_to_hsv(*(v / 255 for v in c)) for m, c in PALETTE.items()}
    counts = {}
    pixels = image.load()
    cache = {}
    for y in range(h):
        for x in range(w):
            rgb = pixels[x, y]
            if rgb not in cache:
                cache[rgb] = classify(rgb, targets)
            m = cache[rgb]
            if m is None:
                continue
            key = (x * TILES[0] // w, y * TILES[1] // h, m)
            counts[key] = counts.get(key, 0) + 1
    return counts


def classify(rgb, targets):
    """The method whose colour `rgb` is (or a tint of it), if any."""
    h, s, v = colorsys.rgb_to_hsv(*(c / 255 for c in rgb))
    if v < 0.25:
        return None
    best = None
    for m, (th, ts, tv) in targets.items():
        if ts < 0.3:
            # The grey-blue of NR: close in colour, not in hue alone.
            if max(abs(a - b) for a, b in zip(rgb, PALETTE[m])) <= 18:
                return m
            continue
        dh = min(abs(h - th), 1 - abs(h - th))
        if dh <= 10 / 360 and ts * 0.6 <= s <= min(1.0, ts * 1.3 + 0.05):
            if best is None or dh < best[1]:
                best = (m, dh)
    return best[0] if best else None


def distance(a, b):
    """How far picture summary `a` is from `b`: the pixels of the tile-and-method cells that
    one picture has and the other lacks (under 30 % of its count), over the pixels of `b` (at
    least 400). Animation moves lines and bodies within their tiles and changes counts
    smoothly; a half-drawn picture empties whole cells (a plot without its lines, a view
    reading "(empty)") or fills others (meshes stacked at the origin)."""
    def lacking(x, y):
        return sum(n for k, n in x.items() if n >= MIN_CELL and y.get(k, 0) < 0.3 * n)
    return (lacking(b, a) + lacking(a, b)) / max(sum(b.values()), 400)


# A tile-and-method cell counts from this many pixels (of the half-size picture).
MIN_CELL = 20


def methods(summary_):
    """The methods present with at least 0.5 % of the picture's method pixels."""
    total = max(sum(summary_.values()), 1)
    per = {}
    for (_, _, m), n in summary_.items():
        per[m] = per.get(m, 0) + n
    return sorted(m for m, n in per.items() if n >= 0.005 * total)
