"""``aiobt up`` tells localization where the simulation puts the robot: the world's
start (its map YAML's ``aiobt: start:``), or the robot's ``--start``."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import pytest

from aiobt.system.commands import service_command
from aiobt.system.config import config_from_dict
from aiobt.system.world_start import WorldError, start_from_args, world_file, world_start


def _localization(data: Mapping[str, object]) -> list[str]:
    return service_command("localization", config_from_dict(data, "test"))


def test_the_shipped_worlds_give_their_starts() -> None:
    assert world_start("office") == (2.0, 9.75, 0.0)
    assert world_start("small") == (0.0, 0.0, 0.0)
    assert world_file("office").name == "office.yaml"


def test_localization_starts_at_the_world_start_with_the_simulated_robots_params() -> None:
    command = _localization({"world": "office"})
    assert command == [
        "localization", "--connect", "tcp/127.0.0.1:7447", "--namespace", "robot",
        "--params-file", "sim_robot",
        "--set", "set_initial_pose=true", "--set", "initial_pose={x: 2, y: 9.75, yaw: 0}",
    ]  # fmt: skip


def test_a_map_yaml_path_gives_its_own_start_and_the_robots_start_wins(tmp_path: Path) -> None:
    world = tmp_path / "lab.yaml"
    world.write_text("image: lab.pgm\nresolution: 0.05\naiobt: {start: [1.5, -2, 1.25]}\n")
    assert "initial_pose={x: 1.5, y: -2, yaw: 1.25}" in _localization({"world": str(world)})
    moved = {"world": str(world), "services": {"robot": {"args": ["--start", "3", "4", "0.5"]}}}
    assert "initial_pose={x: 3, y: 4, yaw: 0.5}" in _localization(moved)
    world.write_text("image: lab.pgm\nresolution: 0.05\n")  # no aiobt: key: the robot's (0, 0, 0)
    assert world_start(str(world)) == (0.0, 0.0, 0.0)


def test_without_the_simulation_here_no_start_is_assumed() -> None:
    command = _localization({"services": {"robot": {"enabled": False}}})
    assert "--params-file" not in command
    assert not any(arg.startswith("initial_pose") for arg in command)


def test_a_bad_world_or_start_is_an_error_naming_it(tmp_path: Path) -> None:
    with pytest.raises(WorldError, match=r"world '/nowhere/x.yaml': cannot read"):
        world_start("/nowhere/x.yaml")
    # aiobt up: the robot stops naming the world; localization waits for an initialpose
    command = _localization({"world": "/nowhere/x.yaml"})
    assert not any(arg.startswith("initial_pose") for arg in command)
    bad = tmp_path / "bad.yaml"
    bad.write_text("aiobt: {start: [1, two]}\n")
    with pytest.raises(WorldError, match=r"bad.yaml: aiobt.start must be \[x, y, yaw\]"):
        world_start(str(bad))
    with pytest.raises(WorldError, match=r"robot --start 1 y: expected three numbers"):
        start_from_args(["--start", "1", "y"])
    assert start_from_args(["--seed", "3"]) is None
