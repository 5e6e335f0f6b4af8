"""``aiobt navigator``'s options and its refusal of default trees that are not there."""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from aiobt.core.clock import ManualClock
from aiobt.transport import Bus
from aiobt_services.navigator.main import add_arguments, build_navigator
from aiobt_services.navigator.trees import TreeLoadFailure


def parse(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    return parser.parse_args(list(argv))


def test_options_reach_the_navigator(local_bus: Bus, tmp_path: Path) -> None:
    args = parse(
        "--default-tree",
        "NavigateToPoseWReplanningGoalPatienceAndRecovery",
        "--bt-loop-duration",
        "0.05",
        "--btlog-dir",
        str(tmp_path),
        "--sim-time",
        "--clock-timeout",
        "3",
    )
    navigator = build_navigator(args, local_bus, ManualClock())
    options = navigator.options
    assert options.default_to_pose_tree == "NavigateToPoseWReplanningGoalPatienceAndRecovery"
    assert options.default_through_poses_tree.endswith(
        "navigate_through_poses_w_replanning_and_recovery.xml"
    )
    assert options.bt_loop_duration == 0.05
    assert options.btlog_dir == tmp_path
    assert options.clock_timeout == 3.0
    assert build_navigator(parse(), local_bus, ManualClock()).options.clock_timeout is None
    assert navigator.recorder is None  # no --mcap-dir: nothing records


def test_mcap_dir_makes_the_navigator_record(local_bus: Bus, tmp_path: Path) -> None:
    navigator = build_navigator(parse("--mcap-dir", str(tmp_path)), local_bus, ManualClock())
    assert navigator.options.mcap_dir == tmp_path
    assert navigator.recorder is not None


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--default-tree", "NoSuchTree"], "'NoSuchTree' is not registered"),
        (["--default-through-tree", "/nowhere/t.xml"], "/nowhere/t.xml does not exist"),
        (["--tree-dir", "/nowhere"], "/nowhere is not a directory"),
    ],
)
def test_missing_default_trees_stop_the_navigator(
    local_bus: Bus, argv: list[str], message: str
) -> None:
    with pytest.raises(TreeLoadFailure, match=message):
        build_navigator(parse(*argv), local_bus, ManualClock())


def test_bad_numbers_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        parse("--bt-loop-duration", "0")
    assert "must be a finite number > 0" in capsys.readouterr().err
