"""``aiobt planner --help`` names the actions and the planner and smoother ids it serves."""

from __future__ import annotations

import pytest

from aiobt.cli import main as cli


def test_help_names_actions_and_planner_ids(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as done:
        cli.main(["planner", "--help"])
    assert done.value.code == 0
    text = " ".join(capsys.readouterr().out.split())  # argparse wraps lines
    for action in (
        "compute_path_to_pose",
        "compute_path_through_poses",
        "smooth_path",
        "compute_coverage_path",
    ):
        assert action in text
    assert "Planner ids (goal.planner_id): GridBased (default), ThetaStar." in text
    assert "'simple_smoother'" in text
    assert "srv/is_path_valid" in text
    assert "services/aiobt_services/planner/README.md" in text
