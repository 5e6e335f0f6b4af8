"""``aiobt demo`` as the README runs it: the real system, every goal reached, a recovery
on the walled-in goal, a picture."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from aiobt.testing.bus import free_endpoint
from tests.integration.system.helpers import kill_mentioning, processes_mentioning

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(300)]


def test_the_demo_patrols_through_the_navigator_recovers_and_draws(tmp_path: Path) -> None:
    endpoint = free_endpoint()
    command = [sys.executable, "-m", "aiobt.cli.main", "demo", "--out", str(tmp_path)]
    try:
        done = subprocess.run(
            [*command, "--listen", endpoint], capture_output=True, text=True, timeout=280
        )
    finally:
        kill_mentioning(endpoint)
    assert done.returncode == 0, done.stdout + done.stderr
    lines = done.stdout.splitlines()
    goals = [line.strip() for line in lines if line.strip().startswith("goal ")]
    assert [g.split()[1] for g in goals] == ["1/4", "2/4", "3/4", "4/4"]
    assert all(": reached in " in g for g in goals), goals
    walled_in = next(g for g in goals if g.startswith("goal 3/4"))
    recoveries = int(walled_in.rsplit(", ", 1)[1].split()[0])
    assert recoveries >= 1, walled_in  # no path out until the first recovery
    assert "  the robot is walled in by 2 boxes (in the planner's costmap)" in lines
    assert "  the boxes are gone" in lines
    assert done.stderr == ""  # no log line mixed into the demo's output
    assert lines[-2].startswith("pose estimate off the truth by "), lines[-2]  # both tracks
    summary = lines[-1]
    assert summary.startswith("4 of 4 goals reached, ")
    picture = Path(summary.rsplit("picture: ", 1)[1])
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert processes_mentioning(endpoint) == []
