"""The dock database: Nav2's YAML, and every problem named by file, line and dock."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from aiobt_services.docking.database import (
    DATABASES_DIR,
    docks_from_params,
    load_database,
    parse_database,
)
from aiobt_services.docking.errors import DockDatabaseError
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.worlds import WORLDS_DIR

GOOD = """\
docks:
  home_dock:
    type: simple_charging_dock
    pose: [0.49, 9.75, 3.14]
    id: tag_0
  kitchen:
    type: ''
    frame: odom
    pose: [1, 2, 0]
"""


def test_nav2s_format_with_its_defaults() -> None:
    docks = parse_database(GOOD)
    assert list(docks) == ["home_dock", "kitchen"]
    home, kitchen = docks["home_dock"], docks["kitchen"]
    assert (home.type, home.frame, home.id) == ("simple_charging_dock", "map", "tag_0")
    assert (home.pose.x, home.pose.y, home.pose.yaw) == (0.49, 9.75, 3.14)
    assert (kitchen.type, kitchen.frame, kitchen.id) == ("", "odom", "")


@pytest.mark.parametrize(
    ("text", "where"),
    [
        (
            "docks:\n  a:\n    type: t\n    pose: [1, 2]\n",
            ":4: dock 'a' 'pose' must be [x, y, theta]",
        ),
        ("docks:\n  a:\n    type: t\n    pose: [1, x, 2]\n", ":4: dock 'a' 'pose' must hold three"),
        ("docks:\n  a:\n    pose: [1, 2, 3]\n", ":2: dock 'a' has no 'type'"),
        ("docks:\n  a:\n    type: t\n", ":2: dock 'a' has no 'pose'"),
        ("docks:\n  a:\n    type: t\n    pos: [1, 2, 3]\n", ":4: dock 'a' unknown field 'pos'"),
        (
            "docks:\n  a: {type: t, pose: [0, 0, 0]}\n  a: {type: t, pose: [1, 0, 0]}\n",
            ":3: dock 'a' appears twice",
        ),
        ("dock:\n  a: {}\n", " does not contain 'docks'"),
        ("docks:\n  a: [type: t\n", ":3: not YAML"),
        ("docks:\n  a:\n    type: [t]\n    pose: [1, 2, 3]\n", ":3: dock 'a' 'type' must be"),
    ],
)
def test_a_bad_database_is_named_by_line_and_dock(text: str, where: str) -> None:
    with pytest.raises(DockDatabaseError) as caught:
        parse_database(text, "docks.yaml")
    assert f"dock database docks.yaml{where}" in str(caught.value)


def test_a_missing_file_is_named(tmp_path: Path) -> None:
    with pytest.raises(DockDatabaseError, match=r"nope\.yaml: cannot read"):
        load_database(tmp_path / "nope.yaml")


@pytest.mark.parametrize("world", ["office", "small"])
def test_each_shipped_world_has_its_dock_in_its_database(world: str) -> None:
    dock = load_map(WORLDS_DIR / f"{world}.yaml").dock
    assert dock is not None
    home = load_database(DATABASES_DIR / f"{world}.yaml")["home_dock"]
    assert (home.pose.x, home.pose.y) == pytest.approx((dock.x, dock.y))
    assert math.cos(home.pose.yaw - dock.yaw) == pytest.approx(1.0)


# -- Nav2's ``docks`` parameter (its UtilsTests.parseDockParams1-3) -------------------


def test_docks_from_params_with_nav2s_defaults() -> None:
    docks = docks_from_params(
        ["dockC", "dockD"],
        {
            "dockC": {"frame": "mapA", "type": "typeA", "pose": "[0.3, 0.3, 0.3]"},
            "dockD": {"type": "typeB", "pose": "0.3,0.3,0.3", "id": "D"},
        },
    )
    c, d = docks["dockC"], docks["dockD"]
    assert (c.frame, d.frame) == ("mapA", "map")
    assert (c.type, c.pose.x, c.pose.y, c.pose.yaw) == ("typeA", 0.3, 0.3, 0.3)
    assert (c.id, d.id) == ("", "D")


@pytest.mark.parametrize(
    ("given", "problem"),
    [
        ({}, "Dock dockA has no dock 'type'"),  # parseDockParams1: no type set
        ({"dockA": {"type": "t"}}, "Dock dockA has no valid 'pose'"),
        ({"dockA": {"type": "t", "pose": "[0.3, 0.3]"}}, r"dockA.pose='\[0.3, 0.3\]' must be"),
        ({"dockA": {"type": "t", "pose": "[a, 0, 0]"}}, "must hold three numbers"),
        ({"dockA": {"type": "t", "pose": "[inf, 0, 0]"}}, "must be finite"),
        ({"dockA": {"type": "t", "pose": "[0, 0, 0]", "yaw": "1"}}, "dockA.yaw: unknown dock"),
    ],
)
def test_a_bad_dock_parameter_names_the_dock_and_field(
    given: dict[str, dict[str, str]], problem: str
) -> None:
    with pytest.raises(ValueError, match=problem):
        docks_from_params(["dockA"], given)


def test_a_dock_named_twice_is_refused() -> None:
    with pytest.raises(ValueError, match="dock 'a' appears twice"):
        docks_from_params(["a", "a"], {"a": {"type": "t", "pose": "[0, 0, 0]"}})
