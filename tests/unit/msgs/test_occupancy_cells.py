"""OccupancyGrid ``data`` given as a plain list: every bad cell is a MessageError naming
``data`` (so a subscriber logs one warning with key and field), never a raw exception."""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest

import aiobt.msgs as msgs
from aiobt.msgs import MessageError, OccupancyGrid

INFO = {"resolution": 0.05, "width": 2, "height": 1}


def _payload(data: Any) -> str:
    return json.dumps({"info": INFO, "data": data})


@pytest.mark.parametrize(
    ("data", "reason"),
    [
        (["a", "b"], "cell 0 = 'a' is not an integer"),
        ([0, "7"], "cell 1 = '7' is not an integer"),
        ([0, None], "cell 1 = None is not an integer"),
        ([0, {}], "cell 1 = {} is not an integer"),
        ([0.5, 1], "cell 0 = 0.5 is not a whole number"),
        ([1, 1.7], "cell 1 = 1.7 is not a whole number"),
        ([[0], [1]], r"cell 0 = \[0\] is not an integer"),
        ([[0, 1]], r"cell 0 = \[0, 1\] is not an integer"),
        ([True, False], "cell 0 = True is not an integer"),
        ([0, True], "cell 1 = True is not an integer"),
        ([0, 101], r"cell 1 = 101 not in \[-1, 100\]"),
        ([-2, 0], r"cell 0 = -2 not in \[-1, 100\]"),
        ([0, 255], r"cell 1 = 255 not in \[-1, 100\]"),  # would wrap to -1 as int8
        ([1e300, 0], r"cell 0 = 1e\+300 not in \[-1, 100\]"),
        ([0, 10**30], r"cell 1 = 10{30} not in \[-1, 100\]"),
        ([0, -(2**64)], r"cell 1 = -18446744073709551616 not in \[-1, 100\]"),
    ],
)
def test_a_bad_cell_is_a_message_error_naming_data(data: list[Any], reason: str) -> None:
    with pytest.raises(MessageError, match=reason) as caught:
        msgs.decode(OccupancyGrid, _payload(data), key="robot/map")
    assert (caught.value.key, caught.value.field) == ("robot/map", "data")
    assert "robot/map" in str(caught.value)
    with pytest.raises(MessageError, match=reason) as caught:  # from Python data too
        msgs.validate(OccupancyGrid, {"info": INFO, "data": data}, key="robot/map")
    assert caught.value.field == "data"


def test_non_finite_cells_are_refused_naming_data() -> None:
    for token in ("NaN", "Infinity", "-Infinity"):
        payload = f'{{"info": {json.dumps(INFO)}, "data": [0, {token}]}}'
        with pytest.raises(MessageError) as caught:
            msgs.decode(OccupancyGrid, payload, key="robot/map")
        assert caught.value.field == "data"


@pytest.mark.parametrize(
    ("data", "cells"),
    [
        ([0, 100], [[0, 100]]),
        ([-1, 50], [[-1, 50]]),
        ([100.0, -1.0], [[100, -1]]),  # whole floats (some encoders write 100.0) are cells
        ([0, 7.0], [[0, 7]]),
    ],
)
def test_good_lists_decode_to_their_cells(data: list[Any], cells: list[list[int]]) -> None:
    grid = msgs.decode(OccupancyGrid, _payload(data), key="robot/map")
    assert grid.array.tolist() == cells
    assert grid.array.dtype == np.int8


def test_the_compact_wire_form_is_unchanged() -> None:
    cells = np.arange(-1, 101, dtype=np.int8).reshape(6, 17)
    grid = OccupancyGrid.from_array(cells, 0.05)
    payload = grid.to_json()
    assert json.loads(payload)["data"][:2] == "eJ"  # base64 of zlib's header
    again = msgs.decode(OccupancyGrid, payload, key="robot/map")
    assert np.array_equal(again.array, cells)
    listed = msgs.decode(
        OccupancyGrid, json.dumps({**json.loads(payload), "data": cells.ravel().tolist()})
    )
    assert listed == grid
