"""The demo's picture: title, summary, start, goals with their tolerance, the estimate's
and the truth's tracks, scale and legend."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from aiobt.demo.annotate import GOAL, HEADER, START, TRAIL, TRUTH, nice_length
from aiobt.demo.picture import GOAL_TOLERANCE, SCALE, render, summary
from aiobt.demo.record import Leg, Record
from aiobt.msgs import OccupancyGrid

RESOLUTION = 0.05


def record() -> Record:
    cells = np.zeros((100, 100), np.int8)
    cells[60, 10:40] = 100  # a wall
    done = Record(map=OccupancyGrid.from_array(cells, RESOLUTION))
    done.trajectory = [(0.5, 0.5), (1.0, 0.5), (2.0, 2.0)]
    done.legs = [
        Leg("one", (2.0, 2.0, 0.0), reached=True, recoveries=1, seconds=20.0),
        Leg("two", (4.0, 1.0, 0.0), reached=False, seconds=5.5),
    ]
    return done


def test_the_summary_counts_goals_time_and_recoveries_in_plain_words() -> None:
    assert summary(record()) == "1 of 2 goals reached in 25.5 s of sim time, 1 recovery"
    with_truth = record()
    with_truth.tracking.on_truth(1.0, (2.0, 2.0))
    with_truth.tracking.on_estimate(1.0, (2.0, 2.02))
    assert summary(with_truth) == (
        "1 of 2 goals reached in 25.5 s of sim time, 1 recovery\n"
        "pose estimate off the truth by 2.0 cm RMS, 2.0 cm at worst"
    )


def test_the_picture_frames_the_map_and_marks_start_and_goal_tolerance() -> None:
    image = Image.open(io.BytesIO(render(record(), title="a title")))
    side = 100 * SCALE
    assert image.width == side
    assert image.height > side + 100  # a title and summary above, a legend below
    header = HEADER
    pixels = np.asarray(image.convert("RGB"))
    title_band = pixels[:header]
    assert (title_band < 100).all(axis=2).any()  # dark text in the title band

    def at(x: float, y: float) -> tuple[int, int]:  # map metres -> picture pixel (col, row)
        return round(x / RESOLUTION * SCALE), header + side - round(y / RESOLUTION * SCALE)

    col, row = at(0.5, 0.5)
    assert tuple(pixels[row, col]) == START  # the start marker
    col, row = at(2.0 + GOAL_TOLERANCE, 2.0)
    ring = pixels[row - 2 : row + 3, col - 2 : col + 3].reshape(-1, 3)
    assert any(tuple(p) == GOAL for p in ring)  # the tolerance ring, 0.25 m out


def _pixel(x: float, y: float) -> tuple[int, int]:
    """Map metres -> picture pixel (col, row) of a 100 x 100 cell map."""
    side = 100 * SCALE
    return round(x / RESOLUTION * SCALE), HEADER + side - round(y / RESOLUTION * SCALE)


def _colours_near(pixels: np.ndarray, x: float, y: float, reach: int = 1) -> set[tuple[int, ...]]:
    col, row = _pixel(x, y)
    patch = pixels[row - reach : row + reach + 1, col - reach : col + reach + 1]
    return {tuple(int(v) for v in p) for p in patch.reshape(-1, 3)}


def test_the_estimate_and_the_truth_are_both_drawn_where_they_part_and_where_they_agree() -> None:
    drawn = record()
    drawn.trajectory = [(1.0, 3.0), (3.0, 3.0), (4.0, 4.0)]  # the estimate: y = 3 first
    drawn.truth = [(1.0, 3.0), (3.0, 3.0), (4.0, 2.0)]  # the truth parts from it at x = 3
    pixels = np.asarray(Image.open(io.BytesIO(render(drawn))).convert("RGB"))
    assert TRAIL in _colours_near(pixels, 3.8, 3.8)  # the estimate alone
    assert TRUTH not in _colours_near(pixels, 3.8, 3.8, reach=3)
    assert TRUTH in _colours_near(pixels, 3.8, 2.2)  # the truth alone
    assert TRAIL not in _colours_near(pixels, 3.8, 2.2, reach=3)
    together = _colours_near(pixels, 2.0, 3.0, reach=4)  # the estimate on the wide truth
    assert {TRAIL, TRUTH} <= together
    legend = pixels[HEADER + 100 * SCALE :]
    assert (legend == TRUTH).all(axis=2).sum() > 50  # its swatch in the legend
    assert (legend == TRAIL).all(axis=2).sum() > 20


def test_without_a_truth_only_the_estimate_is_drawn_on_the_map() -> None:
    pixels = np.asarray(Image.open(io.BytesIO(render(record()))).convert("RGB"))
    on_map = pixels[HEADER : HEADER + 100 * SCALE]
    assert not (on_map == TRUTH).all(axis=2).any()
    assert (on_map == TRAIL).all(axis=2).sum() > 100


def test_the_scale_bar_is_1_2_or_5_times_a_power_of_ten() -> None:
    assert nice_length(1.0) == 1.0
    assert nice_length(4.3) == 2.0
    assert nice_length(0.9) == pytest.approx(0.5)
    assert nice_length(73.0) == 50.0
