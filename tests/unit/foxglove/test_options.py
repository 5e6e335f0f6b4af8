"""The bridge's options, recording names, up's command line for it and the shipped layout."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import foxglove
import pytest

from aiobt.cli import foxglove as cli
from aiobt.cli import up
from aiobt.foxglove import LAYOUT
from aiobt.foxglove.channels import GOAL_TOPIC, INITIALPOSE_TOPIC, Channels
from aiobt.foxglove.server import recording_path
from aiobt.system.config import ConfigError, SystemConfig
from aiobt.system.foxglove import FoxgloveOptions, foxglove_command


def parse(parser_of: object, *argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    parser_of.add_arguments(parser)  # type: ignore[attr-defined]
    return parser.parse_args(argv)


def test_defaults_bind_loopback_8765() -> None:
    options = cli.options_from_args(parse(cli))
    assert (options.host, options.port, options.mcap) == ("127.0.0.1", 8765, None)


def test_record_only_and_bad_flags_are_named() -> None:
    options = cli.options_from_args(parse(cli, "--no-server", "--mcap", "a.mcap"))
    assert options.port is None
    assert options.mcap == Path("a.mcap")
    with pytest.raises(ValueError, match="--no-server without --mcap"):
        cli.options_from_args(parse(cli, "--no-server"))
    with pytest.raises(ValueError, match="--footprint-radius must be > 0"):
        cli.options_from_args(parse(cli, "--footprint-radius", "0"))
    with pytest.raises(SystemExit):
        parse(cli, "--port", "70000")


def test_an_existing_recording_is_kept(tmp_path: Path) -> None:
    path = tmp_path / "run.mcap"
    assert recording_path(path, overwrite=False) == path
    path.write_bytes(b"old")
    (tmp_path / "run-1.mcap").write_bytes(b"old")
    assert recording_path(path, overwrite=False) == tmp_path / "run-2.mcap"
    assert recording_path(path, overwrite=True) == path


def test_up_runs_the_bridge_with_the_system_settings(tmp_path: Path) -> None:
    args = parse(up, "--foxglove", "--mcap", str(tmp_path / "r.mcap"))
    options = up.foxglove_from_args(args)
    assert options == FoxgloveOptions(port=8765, mcap=tmp_path / "r.mcap")
    command = foxglove_command(SystemConfig(namespace="bot"), options)
    assert command == [
        "foxglove", "--connect", "tcp/127.0.0.1:7447", "--namespace", "bot",
        "--host", "127.0.0.1", "--port", "8765", "--mcap", str(tmp_path / "r.mcap"),
    ]  # fmt: skip
    record_only = foxglove_command(SystemConfig(), FoxgloveOptions(port=None, mcap=Path("x")))
    assert "--no-server" in record_only
    assert not up.foxglove_from_args(parse(up)).wanted
    with pytest.raises(ConfigError, match="port 99999"):
        up.foxglove_from_args(parse(up, "--foxglove", "99999"))


def test_the_layout_uses_only_bridged_topics() -> None:
    layout = json.loads(LAYOUT.read_text())
    topics = Channels.create(foxglove.Context()).topics()
    panels = layout["configById"]
    assert set(panels["3D!aiobt"]["topics"]) <= topics
    assert {
        "/plan", "/local_plan", "/global_costmap", "/local_costmap", "/particle_cloud", "/sim/pose"
    } <= set(panels["3D!aiobt"]["topics"])  # fmt: skip
    plotted = {p["value"].split(".")[0] for p in panels["Plot!aiobtspeed"]["paths"]}
    assert plotted <= topics
    assert panels["RawMessages!aiobtfeedback"]["topicPath"] in topics
    assert panels["RosOut!aiobtlog"]["topicToRender"] in topics
    assert panels["Publish!aiobtgoal"]["topicName"] == GOAL_TOPIC
    assert panels["3D!aiobt"]["publish"]["poseTopic"] == GOAL_TOPIC
    assert panels["3D!aiobt"]["publish"]["poseEstimateTopic"] == INITIALPOSE_TOPIC
