"""The demo's picture: title, summary, start, goals with their tolerance, scale and legend."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from aiobt.demo.annotate import GOAL, HEADER, START, nice_length
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


def test_the_scale_bar_is_1_2_or_5_times_a_power_of_ten() -> None:
    assert nice_length(1.0) == 1.0
    assert nice_length(4.3) == 2.0
    assert nice_length(0.9) == pytest.approx(0.5)
    assert nice_length(73.0) == 50.0
