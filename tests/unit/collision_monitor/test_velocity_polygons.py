"""Nav2's velocity_polygon: the stop zone chosen by the command (testVelocityPolygonStop,
in spirit), and its refusals."""

from __future__ import annotations

import math
from typing import Any

import pytest

from aiobt_services.collision_monitor import MonitorConfigError

from .nav2_setup import give_scan, monitor, square

CMD_FORWARD = (0.5, 0.0, 0.0)
CMD_TURN = (0.0, 0.0, 1.0)


def velocity_polygon(**change: Any) -> dict[str, Any]:
    section: dict[str, Any] = {
        "type": "velocity_polygon",
        "action_type": "stop",
        "min_points": 2,
        "velocity_polygons": ["rotation", "forward", "stopped"],
        "rotation": {"points": square(0.3), "linear_min": -0.05, "linear_max": 0.05,
                     "theta_min": -2.0, "theta_max": 2.0},
        "forward": {"points": square(1.0), "linear_min": 0.0, "linear_max": 1.0,
                    "theta_min": -2.0, "theta_max": 2.0},
        "stopped": {"points": square(0.4), "linear_min": -1.0, "linear_max": 1.0,
                    "theta_min": -2.0, "theta_max": 2.0},
    }  # fmt: skip
    return section | change


def test_the_command_picks_the_zone() -> None:
    cm = monitor({"VelocityPolygon": velocity_polygon()})
    give_scan(cm, 0.6, 0.0)  # a ring 0.6 m round: inside forward, outside rotation
    assert cm.process(CMD_FORWARD, 0.0).action_type == "stop"
    assert cm.process(CMD_TURN, 0.0).action_type == "none"  # it may turn away
    assert cm.process((-0.5, 0.0, 0.0), 0.0).action_type == "none"  # stopped: the 0.4 square
    give_scan(cm, 0.2, 0.1)
    assert cm.process(CMD_TURN, 0.1).action_type == "stop"


def test_a_command_no_sub_polygon_covers_keeps_the_last_shape() -> None:
    cm = monitor({"VelocityPolygon": velocity_polygon()})
    give_scan(cm, 0.6, 0.0)
    assert cm.process(CMD_FORWARD, 0.0).action_type == "stop"
    assert cm.process((0.5, 0.0, 5.0), 0.0).action_type == "stop"  # turn rate beyond all
    assert cm.process(CMD_TURN, 0.0).action_type == "none"
    assert cm.process((0.5, 0.0, 5.0), 0.0).action_type == "none"


def test_holonomic_ranges_by_speed_and_direction() -> None:
    sideways = {
        "points": square(1.0),
        "linear_min": 0.0,
        "linear_max": 1.0,
        "theta_min": -2.0,
        "theta_max": 2.0,
        "direction_start_angle": math.pi / 4,
        "direction_end_angle": 3 * math.pi / 4,
    }
    rest = {"points": square(0.3), "linear_min": 0.0, "linear_max": 1.0,
            "theta_min": -2.0, "theta_max": 2.0}  # fmt: skip
    zone = velocity_polygon(holonomic=True, velocity_polygons=["left", "rest"],
                            left=sideways, rest=rest)  # fmt: skip
    for key in ("rotation", "forward", "stopped"):
        del zone[key]
    cm = monitor({"VelocityPolygon": zone})
    give_scan(cm, 0.6, 0.0)
    assert cm.process((0.0, 0.5, 0.0), 0.0).action_type == "stop"  # leftwards: the big one
    assert cm.process((0.5, 0.0, 0.0), 0.0).action_type == "none"


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"velocity_polygons": []}, "velocity_polygons must be a non-empty list"),
        ({"velocity_polygons": ["rotation", "spin"]}, "velocity polygon 'spin': no section"),
        ({"rotation": {"points": "[[0, 0], [1, 0]]", "linear_min": 0, "linear_max": 1,
                       "theta_min": 0, "theta_max": 1}}, "has 2 points"),
        ({"rotation": {"points": square(1.0), "linear_min": 1, "linear_max": 0,
                       "theta_min": 0, "theta_max": 1}}, "a minimum is above its maximum"),
        ({"rotation": {"points": square(1.0), "linear_min": 0, "linear_max": 1,
                       "theta_min": 0}}, "theta_max must be a finite number"),
    ],
)  # fmt: skip
def test_a_bad_sub_polygon_is_refused_by_name(change: dict[str, Any], message: str) -> None:
    with pytest.raises(MonitorConfigError, match=message):
        monitor({"VelocityPolygon": velocity_polygon(**change)})
