"""Nav2 map_server maps: a YAML file plus a PGM/PNG image.

Conventions follow Nav2's ``map_io``: image row 0 is the *top* of the map,
``origin`` is the pose of the lower-left pixel, occupancy of a pixel value
``v`` (0..255, colour averaged) is ``p = (255 - v) / 255`` (``v / 255`` with
``negate``); in ``trinary`` mode ``p > occupied_thresh`` is 100,
``p < free_thresh`` is 0 and anything between is -1 (unknown). ``scale`` maps
the band between the thresholds linearly onto 0..100; ``raw`` uses the pixel
value itself (0..100, anything else unknown).

The loaded grid is stored like a ROS OccupancyGrid: ``grid[row, col]`` with row
0 at the *bottom* (the origin), so ``grid.ravel()`` is the message's ``data``.

Optional aiobt extras live under an ``aiobt:`` key that Nav2 ignores:
``start: [x, y, yaw]`` and ``dock: [x, y, yaw]`` (where the robot stands docked,
facing the dock: see ``dock.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import yaml
from PIL import Image, UnidentifiedImageError

MODES = ("trinary", "scale", "raw")
OCCUPIED = 100
FREE = 0
UNKNOWN = -1


class MapError(ValueError):
    """A map file or one of its fields is missing or malformed."""

    def __init__(self, path: Path | str, field_name: str, problem: str) -> None:
        super().__init__(f"{path}: field '{field_name}': {problem}")
        self.path = str(path)
        self.field_name = field_name
        self.problem = problem


@dataclass(slots=True, frozen=True)
class Dock:
    """A charging dock: the robot's pose in ``map`` when docked (facing the dock)."""

    x: float
    y: float
    yaw: float


@dataclass(slots=True)
class MapInfo:
    """An occupancy grid (row 0 at the bottom) and where it lies in ``map``."""

    grid: npt.NDArray[np.int8]
    resolution: float
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    source: str = "<memory>"
    start: tuple[float, float, float] = (0.0, 0.0, 0.0)
    dock: Dock | None = None
    extras: dict[str, Any] = field(default_factory=dict)

    @property
    def height(self) -> int:
        return int(self.grid.shape[0])

    @property
    def width(self) -> int:
        return int(self.grid.shape[1])

    def cell_to_world(
        self, rows: npt.ArrayLike, cols: npt.ArrayLike
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """Map coordinates of (fractional) cell positions, origin yaw applied."""
        ox, oy, yaw = self.origin
        u = np.asarray(cols, dtype=np.float64) * self.resolution
        v = np.asarray(rows, dtype=np.float64) * self.resolution
        c, s = math.cos(yaw), math.sin(yaw)
        return ox + c * u - s * v, oy + s * u + c * v

    def world_to_cell(self, x: float, y: float) -> tuple[float, float]:
        """Fractional (row, col) of a map point; integer part is the cell index."""
        ox, oy, yaw = self.origin
        dx, dy = x - ox, y - oy
        c, s = math.cos(yaw), math.sin(yaw)
        u, v = c * dx + s * dy, -s * dx + c * dy
        return v / self.resolution, u / self.resolution

    def contains(self, x: float, y: float, margin: float = 0.0) -> bool:
        """Is the point inside the map rectangle, ``margin`` metres from its edge?"""
        row, col = self.world_to_cell(x, y)
        m = margin / self.resolution
        return m <= row <= self.height - m and m <= col <= self.width - m

    def disc_blocked(self, x: float, y: float, radius: float) -> bool:
        """Does any occupied cell touch the disc of ``radius`` around the point?"""
        row, col = self.world_to_cell(x, y)
        reach = radius / self.resolution + 1.0
        r0, r1 = max(0, math.floor(row - reach)), min(self.height, math.ceil(row + reach) + 1)
        c0, c1 = max(0, math.floor(col - reach)), min(self.width, math.ceil(col + reach) + 1)
        rows, cols = np.mgrid[r0:r1, c0:c1]
        near = np.hypot(rows + 0.5 - row, cols + 0.5 - col) <= radius / self.resolution + 0.5
        return bool(np.any(self.grid[r0:r1, c0:c1][near] == OCCUPIED))

    def occupancy_at(self, x: float, y: float) -> int:
        """Cell value under a map point; UNKNOWN outside the map."""
        row, col = self.world_to_cell(x, y)
        r, c = math.floor(row), math.floor(col)
        if 0 <= r < self.height and 0 <= c < self.width:
            return int(self.grid[r, c])
        return UNKNOWN


def occupancy_from_pixels(
    pixels: npt.NDArray[np.uint8],
    *,
    negate: bool = False,
    occupied_thresh: float = 0.65,
    free_thresh: float = 0.196,
    mode: str = "trinary",
    alpha: npt.NDArray[np.uint8] | None = None,
) -> npt.NDArray[np.int8]:
    """Nav2's pixel -> occupancy rule; ``pixels`` image-ordered (row 0 on top)."""
    values = pixels.astype(np.float64)
    if mode == "raw":
        raw = np.where(values <= OCCUPIED, values, UNKNOWN)
        return np.flipud(raw).astype(np.int8)
    shade = values / 255.0
    occ = shade if negate else 1.0 - shade
    out = np.full(occ.shape, UNKNOWN, dtype=np.int8)
    out[occ < free_thresh] = FREE
    if mode == "scale":
        band = (occ >= free_thresh) & (occ <= occupied_thresh)
        if alpha is not None:
            band &= alpha == 255
        ratio = (occ - free_thresh) / max(occupied_thresh - free_thresh, 1e-12)
        out[band] = np.rint(ratio[band] * OCCUPIED).astype(np.int8)
    out[occ > occupied_thresh] = OCCUPIED
    return np.flipud(out)


def load_map(yaml_path: str | Path) -> MapInfo:
    """Load a Nav2 map YAML and its image; errors name the file and field."""
    path = Path(yaml_path)
    doc = _read_yaml(path)
    image_path = _image_path(path, doc)
    resolution = _positive(path, doc, "resolution")
    origin = _floats(path, doc, "origin", 3)
    negate = _flag(path, doc.get("negate", 0))
    occ = _fraction(path, doc, "occupied_thresh", 0.65)
    free = _fraction(path, doc, "free_thresh", 0.196)
    if free > occ:
        raise MapError(path, "free_thresh", f"{free} is above occupied_thresh {occ}")
    mode = doc.get("mode", "trinary")
    if mode not in MODES:
        raise MapError(path, "mode", f"{mode!r} is not one of {', '.join(MODES)}")
    pixels, alpha = _read_image(image_path, path)
    grid = occupancy_from_pixels(
        pixels, negate=negate, occupied_thresh=occ, free_thresh=free, mode=mode, alpha=alpha
    )
    info = MapInfo(grid=grid, resolution=resolution, origin=(origin[0], origin[1], origin[2]))
    info.source = str(path)
    _read_extras(path, doc.get("aiobt"), info)
    return info


def _read_yaml(path: Path) -> dict[str, Any]:
    try:
        text = path.read_text()
    except OSError as exc:
        raise MapError(path, "<file>", f"cannot read map YAML: {exc.strerror or exc}") from exc
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise MapError(path, "<file>", f"not valid YAML: {exc}") from exc
    if not isinstance(doc, dict):
        raise MapError(path, "<file>", "expected a mapping of map fields")
    return doc


def _image_path(path: Path, doc: dict[str, Any]) -> Path:
    image = doc.get("image")
    if not isinstance(image, str) or not image:
        raise MapError(path, "image", "missing or not a file name")
    image_path = Path(image)
    return image_path if image_path.is_absolute() else path.parent / image_path


def _number(path: Path, name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise MapError(path, name, f"expected a number, got {value!r}")
    if not math.isfinite(value):
        raise MapError(path, name, f"must be finite, got {value!r}")
    return float(value)


def _positive(path: Path, doc: dict[str, Any], name: str) -> float:
    if name not in doc:
        raise MapError(path, name, "missing")
    value = _number(path, name, doc[name])
    if value <= 0.0:
        raise MapError(path, name, f"must be > 0, got {value}")
    return value


def _floats(path: Path, doc: dict[str, Any], name: str, count: int) -> list[float]:
    value = doc.get(name)
    if not isinstance(value, list) or len(value) != count:
        raise MapError(path, name, f"expected a list of {count} numbers, got {value!r}")
    return [_number(path, f"{name}[{i}]", v) for i, v in enumerate(value)]


def _fraction(path: Path, doc: dict[str, Any], name: str, default: float) -> float:
    value = _number(path, name, doc.get(name, default))
    if not 0.0 <= value <= 1.0:
        raise MapError(path, name, f"must be within [0, 1], got {value}")
    return value


def _flag(path: Path, value: Any) -> bool:
    if isinstance(value, bool) or value in (0, 1):
        return bool(value)
    raise MapError(path, "negate", f"expected 0, 1, true or false, got {value!r}")


def _read_image(image_path: Path, yaml_path: Path) -> tuple[Any, Any]:
    try:
        with Image.open(image_path) as img:
            img.load()
            alpha = np.asarray(img.getchannel("A")) if "A" in img.getbands() else None
            grey = np.asarray(img.convert("RGB"), dtype=np.float64).mean(axis=2)
    except FileNotFoundError as exc:
        raise MapError(yaml_path, "image", f"image file {image_path} does not exist") from exc
    except (UnidentifiedImageError, OSError) as exc:
        raise MapError(yaml_path, "image", f"cannot decode {image_path}: {exc}") from exc
    return np.rint(grey).astype(np.uint8), alpha


def _read_extras(path: Path, extras: Any, info: MapInfo) -> None:
    if extras is None:
        return
    if not isinstance(extras, dict):
        raise MapError(path, "aiobt", "expected a mapping")
    info.extras = dict(extras)
    if "start" in extras:
        x, y, yaw = _floats(path, extras, "start", 3)
        info.start = (x, y, yaw)
    if "dock" in extras:
        x, y, yaw = _floats(path, extras, "dock", 3)
        info.dock = Dock(x, y, yaw)


def save_map(info: MapInfo, yaml_path: str | Path, *, image_name: str | None = None) -> None:
    """Write ``info`` as a Nav2 map (trinary PGM: 0 occupied, 254 free, 205 unknown)."""
    path = Path(yaml_path)
    image_name = image_name or path.with_suffix(".pgm").name
    pixels = np.full(info.grid.shape, 205, dtype=np.uint8)
    pixels[info.grid == FREE] = 254
    pixels[info.grid == OCCUPIED] = 0
    Image.fromarray(np.ascontiguousarray(np.flipud(pixels))).save(path.parent / image_name)
    doc: dict[str, Any] = {
        "image": image_name,
        "mode": "trinary",
        "resolution": info.resolution,
        "origin": list(info.origin),
        "negate": 0,
        "occupied_thresh": 0.65,
        "free_thresh": 0.196,
        "aiobt": {"start": list(info.start)},
    }
    if info.dock is not None:
        doc["aiobt"]["dock"] = [info.dock.x, info.dock.y, info.dock.yaw]
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
