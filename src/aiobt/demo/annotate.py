"""What makes the demo's picture readable on its own: a title and a summary above the
map, a scale bar on it, and a legend of every mark and shade below it."""

from __future__ import annotations

import math

from PIL import Image, ImageDraw, ImageFont

Colour = tuple[int, int, int]
PLAN, TRAIL, GOAL, RECOVERY, OBSTACLE, START = (
    (40, 90, 220), (220, 40, 40), (20, 150, 60), (245, 140, 0), (140, 60, 170), (0, 0, 0)
)  # fmt: skip
TRUTH = (0, 190, 200)  # the simulation's track, drawn wide under the estimate's
WALL, UNKNOWN, COST = (0, 0, 0), (180, 180, 180), (120, 170, 255)
_TITLE, _TEXT = ImageFont.load_default(size=20), ImageFont.load_default(size=14)
HEADER = 80  # px above the map: title and summary (two lines)
_ROW = 22  # px per legend row
LEGEND: tuple[tuple[str, Colour, str], ...] = (
    ("line", PLAN, "planned path"),
    ("line", TRAIL, "driven, as estimated (pose)"),
    ("wide", TRUTH, "driven, in truth (the simulation's sim/pose)"),
    ("start", START, "start"),
    ("ring", GOAL, "goal k, ring: 0.25 m tolerance"),
    ("dot", OBSTACLE, "filled: goal not reached"),
    ("cross", RECOVERY, "recovery"),
    ("box", OBSTACLE, "box put in the way"),
    ("fill", WALL, "wall"),
    ("fill", UNKNOWN, "unknown"),
    ("fill", COST, "inflated cost (darker: costlier)"),
)
_PER_ROW = 2


def framed(image: Image.Image, title: str, summary: str) -> Image.Image:
    """``image`` under a title and a summary, above the legend."""
    rows = math.ceil(len(LEGEND) / _PER_ROW)
    out = Image.new("RGB", (image.width, HEADER + image.height + rows * _ROW + 12), "white")
    out.paste(image, (0, HEADER))
    draw = ImageDraw.Draw(out)
    draw.text((10, 8), title, fill=(0, 0, 0), font=_TITLE)
    draw.multiline_text((10, 36), summary, fill=(40, 40, 40), font=_TEXT, spacing=4)
    top = HEADER + image.height + 8
    width = image.width // _PER_ROW
    for index, (kind, colour, text) in enumerate(LEGEND):
        x, y = 10 + (index % _PER_ROW) * width, top + (index // _PER_ROW) * _ROW
        _swatch(draw, kind, colour, (x, y + 2))
        draw.text((x + 26, y), text, fill=(0, 0, 0), font=_TEXT)
    return out


def _swatch(draw: ImageDraw.ImageDraw, kind: str, colour: Colour, at: tuple[int, int]) -> None:
    x, y = at
    if kind in ("line", "wide"):
        draw.line((x, y + 7, x + 18, y + 7), fill=colour, width=3 if kind == "line" else 7)
    elif kind in ("ring", "dot"):
        fill = colour if kind == "dot" else None
        draw.ellipse((x + 2, y, x + 16, y + 14), outline=GOAL, width=3, fill=fill)
    elif kind == "cross":
        cross(draw, (x + 9, y + 7), 6)
    elif kind == "start":
        start_mark(draw, (x + 9, y + 7), 7)
    elif kind == "box":
        draw.rectangle((x + 1, y, x + 17, y + 14), outline=colour, width=3)
    else:
        draw.rectangle((x + 1, y, x + 17, y + 14), fill=colour, outline=(120, 120, 120))


def cross(draw: ImageDraw.ImageDraw, at: tuple[float, float], size: float = 8) -> None:
    x, y = at
    draw.line((x - size, y - size, x + size, y + size), fill=RECOVERY, width=4)
    draw.line((x - size, y + size, x + size, y - size), fill=RECOVERY, width=4)


def start_mark(draw: ImageDraw.ImageDraw, at: tuple[float, float], size: float = 10) -> None:
    """A black triangle, pointing up."""
    x, y = at
    draw.polygon([(x, y - size), (x + size, y + size), (x - size, y + size)], fill=START)


def nice_length(metres: float) -> float:
    """The largest 1, 2 or 5 x 10^k metres not above ``metres``."""
    power = 10.0 ** math.floor(math.log10(metres))
    return next(f * power for f in (5.0, 2.0, 1.0) if f * power <= metres)


def scale_bar(draw: ImageDraw.ImageDraw, pixels_per_metre: float, height: int) -> float:
    """A bar of about a fifth of the map's width, bottom left; its length in metres."""
    width = draw.im.size[0]
    metres = nice_length(width / pixels_per_metre / 5.0)
    length = metres * pixels_per_metre
    x, y = 16, height - 18
    draw.rectangle((x - 8, y - 26, x + length + 8, y + 8), fill=(255, 255, 255))
    draw.line((x, y - 6, x, y, x + length, y, x + length, y - 6), fill=(0, 0, 0), width=3)
    draw.text((x + 4, y - 24), f"{metres:g} m", fill=(0, 0, 0), font=_TEXT)
    return metres
