"""Nav2 map_server conventions on tiny hand-made maps."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from aiobt_services.robot.mapfile import MapError, MapInfo, load_map, save_map
from aiobt_services.robot.worlds import OFFICE, SMALL


def write_map(tmp_path: Path, pixels: list[list[int]], **fields: object) -> Path:
    Image.fromarray(np.array(pixels, dtype=np.uint8)).save(tmp_path / "m.pgm")
    doc = {"image": "m.pgm", "resolution": 0.5, "origin": [1.0, -2.0, 0.0]}
    doc.update(fields)
    lines = [f"{k}: {v}" for k, v in doc.items()]
    (tmp_path / "m.yaml").write_text("\n".join(lines) + "\n")
    return tmp_path / "m.yaml"


# top row of the image is the TOP of the map: black (occupied) top-left
PIXELS = [[0, 254, 205], [254, 254, 254]]


def test_image_top_row_is_top_of_map(tmp_path: Path) -> None:
    info = load_map(write_map(tmp_path, PIXELS))
    assert info.grid.shape == (2, 3)
    # grid row 0 is the bottom (origin) row; the black pixel lands in the top row
    assert info.grid[1].tolist() == [100, 0, -1]
    assert info.grid[0].tolist() == [0, 0, 0]


def test_origin_is_lower_left_pixel(tmp_path: Path) -> None:
    info = load_map(write_map(tmp_path, PIXELS))
    assert info.occupancy_at(1.0 + 0.25, -2.0 + 0.5 + 0.25) == 100  # top-left cell
    assert info.occupancy_at(1.0 + 0.25, -2.0 + 0.25) == 0  # bottom-left cell
    assert info.occupancy_at(0.9, -1.9) == -1  # outside the map
    xs, ys = info.cell_to_world([0.5], [0.5])
    assert (xs[0], ys[0]) == pytest.approx((1.25, -1.75))


def test_origin_yaw_rotates_cells(tmp_path: Path) -> None:
    info = load_map(write_map(tmp_path, PIXELS, origin=[0.0, 0.0, 1.5707963267948966]))
    xs, ys = info.cell_to_world([0.5], [2.5])  # bottom-right cell centre
    assert (xs[0], ys[0]) == pytest.approx((-0.25, 1.25))
    assert info.world_to_cell(-0.25, 1.25) == pytest.approx((0.5, 2.5))


def test_negate_inverts_occupancy(tmp_path: Path) -> None:
    info = load_map(write_map(tmp_path, PIXELS, negate=1))
    assert info.grid[1].tolist() == [0, 100, 100]


def test_thresholds_are_strict(tmp_path: Path) -> None:
    # v=89 -> p=0.651 (> 0.65 occupied); v=90 -> p=0.647 (unknown); v=205 -> 0.196
    pixels = [[89, 90, 205, 204]]
    info = load_map(write_map(tmp_path, pixels, occupied_thresh=0.65, free_thresh=0.196))
    assert info.grid[0].tolist() == [100, -1, -1, -1]
    info = load_map(write_map(tmp_path, pixels, occupied_thresh=0.65, free_thresh=0.25))
    assert info.grid[0].tolist() == [100, -1, 0, 0]


def test_scale_and_raw_modes(tmp_path: Path) -> None:
    info = load_map(
        write_map(tmp_path, [[0, 128, 255]], mode="scale", free_thresh=0.0, occupied_thresh=1.0)
    )
    assert info.grid[0].tolist() == [100, 50, 0]
    info = load_map(write_map(tmp_path, [[0, 42, 100, 200]], mode="raw"))
    assert info.grid[0].tolist() == [0, 42, 100, -1]


def test_png_colour_image_is_averaged(tmp_path: Path) -> None:
    rgb = np.zeros((1, 2, 3), dtype=np.uint8)
    rgb[0, 1] = (255, 255, 252)
    Image.fromarray(rgb).save(tmp_path / "c.png")
    (tmp_path / "c.yaml").write_text("image: c.png\nresolution: 0.1\norigin: [0, 0, 0]\n")
    assert load_map(tmp_path / "c.yaml").grid.tolist() == [[100, 0]]


@pytest.mark.parametrize(
    ("fields", "field_name"),
    [
        ({"resolution": -1}, "resolution"),
        ({"resolution": "fine"}, "resolution"),
        ({"origin": [0, 0]}, "origin"),
        ({"origin": "[0, 0, .nan]"}, "origin[2]"),
        ({"negate": 2}, "negate"),
        ({"occupied_thresh": 1.5}, "occupied_thresh"),
        ({"free_thresh": 0.9}, "free_thresh"),
        ({"mode": "fancy"}, "mode"),
        ({"image": "missing.pgm"}, "image"),
    ],
)
def test_bad_fields_name_file_and_field(
    tmp_path: Path, fields: dict[str, object], field_name: str
) -> None:
    path = write_map(tmp_path, PIXELS, **fields)
    with pytest.raises(MapError) as err:
        load_map(path)
    assert err.value.field_name == field_name
    assert str(path) in str(err.value)
    assert f"'{field_name}'" in str(err.value)


def test_missing_yaml_and_garbage(tmp_path: Path) -> None:
    with pytest.raises(MapError, match="cannot read"):
        load_map(tmp_path / "nope.yaml")
    (tmp_path / "bad.yaml").write_text("image: [unclosed\n")
    with pytest.raises(MapError, match="not valid YAML"):
        load_map(tmp_path / "bad.yaml")
    (tmp_path / "img.pgm").write_text("not an image")
    (tmp_path / "g.yaml").write_text("image: img.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n")
    with pytest.raises(MapError, match="cannot decode"):
        load_map(tmp_path / "g.yaml")
    (tmp_path / "r.yaml").write_text("image: img.pgm\norigin: [0, 0, 0]\n")
    with pytest.raises(MapError, match="'resolution': missing"):
        load_map(tmp_path / "r.yaml")


def test_save_then_load_round_trips(tmp_path: Path) -> None:
    grid = np.array([[0, 100, -1], [100, 0, 0]], dtype=np.int8)
    info = MapInfo(grid=grid, resolution=0.1, origin=(-1.0, 2.0, 0.0), start=(0.1, 2.1, 0.5))
    save_map(info, tmp_path / "w.yaml")
    back = load_map(tmp_path / "w.yaml")
    assert back.grid.tolist() == grid.tolist()
    assert back.origin == (-1.0, 2.0, 0.0)
    assert back.start == (0.1, 2.1, 0.5)


def test_shipped_worlds_load() -> None:
    office, small = load_map(OFFICE), load_map(SMALL)
    assert office.width * office.resolution == pytest.approx(20.0)
    assert office.height * office.resolution == pytest.approx(20.0)
    assert office.dock is not None
    assert office.occupancy_at(*office.start[:2]) == 0
    assert office.occupancy_at(office.dock.x, office.dock.y) == 0
    assert small.occupancy_at(0.0, 0.0) == 0
    assert small.occupancy_at(2.45, 0.0) == 100  # east wall


def _grow(mask: np.ndarray) -> np.ndarray:
    grown = mask.copy()
    grown[1:] |= mask[:-1]
    grown[:-1] |= mask[1:]
    grown[:, 1:] |= mask[:, :-1]
    grown[:, :-1] |= mask[:, 1:]
    return grown


def test_every_office_room_is_reachable_for_the_robot() -> None:
    office = load_map(OFFICE)
    blocked = office.grid == 100
    for _ in range(round(0.25 / office.resolution)):  # robot radius + margin
        blocked = _grow(blocked)
    row, col = (int(v) for v in office.world_to_cell(*office.start[:2]))
    reached = np.zeros_like(blocked)
    reached[row, col] = True
    while True:
        grown = _grow(reached) & ~blocked
        if (grown == reached).all():
            break
        reached = grown
    rooms: dict[str, tuple[float, float]] = {"south-west": (2, 5), "south": (10, 7)}
    rooms |= {"south-east": (17, 5), "open plan": (6, 18)}
    rooms |= {"north-east": (16, 13), "north-east top": (16, 18), "dock": (0.6, 9.75)}
    for name, (x, y) in rooms.items():
        r, c = (int(v) for v in office.world_to_cell(x, y))
        assert reached[r, c], f"{name} unreachable"
