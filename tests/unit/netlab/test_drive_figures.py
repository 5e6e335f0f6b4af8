"""The stall test's measure: how long the base moved after its last command."""

from __future__ import annotations

import pytest

from tests.netlab.scenario import ORDER_GRACE, drive_figures


def test_driving_on_after_the_commands_stopped_counts() -> None:
    commands = [0.0, 0.05, 0.1]
    moving = [0.02, 0.12, 0.4, 0.9, 1.5]  # on for 1.4 s after the last command
    figures = drive_figures(commands, moving)
    assert figures["stale_drive"] == pytest.approx(1.4)
    assert figures["commands"] == 3


def test_the_first_motion_of_a_new_stream_before_its_command_does_not() -> None:
    commands = [0.0, 0.05, 10.0, 10.05]  # a 9.95 s pause between two navigations
    moving = [0.04, 9.99, 10.02, 10.06]  # 9.99: seen just before the command that made it
    figures = drive_figures(commands, moving)
    assert figures["stale_drive"] < 0.05  # only the last motion, 0.01 s after its command
    assert figures["cmd_gap"] == pytest.approx(9.95)


def test_a_motion_long_before_the_next_command_counts() -> None:
    commands = [0.0, 5.0]
    moving = [5.0 - ORDER_GRACE - 0.01]
    assert drive_figures(commands, moving)["stale_drive"] == pytest.approx(4.99 - ORDER_GRACE)
