"""The user's commands against a running system (``aiobt up`` on the small world)."""

from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from typing import IO

import pytest

from aiobt.testing.bus import free_endpoint

from .helpers import SystemProcess, kill_mentioning

pytestmark = [pytest.mark.integration, pytest.mark.timeout(240)]
NS = "clitest"


@pytest.fixture(scope="module")
def system(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """``aiobt up`` at 3x on the small world (its web view on a free port); yields the
    router endpoint."""
    endpoint = free_endpoint()
    config = tmp_path_factory.mktemp("up") / "system.yaml"
    config.write_text(
        f"namespace: {NS}\nworld: small\nspeed: 3\nrouter: {{listen: '{endpoint}'}}\n"
    )
    with SystemProcess(["up", "--config", str(config), "--web-port", "0"]) as up:
        try:
            up.wait_line("        up * ")
            yield endpoint
            code, _ = up.stop()
            assert code == 0
        finally:
            kill_mentioning(endpoint)


def aiobt(endpoint: str, *args: str, timeout: float = 120.0) -> subprocess.CompletedProcess[str]:
    command = [sys.executable, "-m", "aiobt.cli.main", *args, "-e", endpoint, "-n", NS]
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout, check=False)


def test_status_lists_every_service_with_version_and_clock(system: str) -> None:
    expected = {"robot", "localization", "planner", "controller", "behaviors",
                "velocity_smoother", "collision_monitor", "navigator"}  # fmt: skip
    for _ in range(10):  # a starved process can miss its lease for a moment: ask again
        done = aiobt(system, "status")
        assert done.returncode == 0, done.stderr
        assert done.stdout.startswith(f"router {system} (Zenoh id "), done.stdout
        rows = [line.split() for line in done.stdout.splitlines()[2:]]
        services = {row[1]: row for row in rows if row[0] == NS and row[1] != "web"}
        if set(services) == expected and all(len(row) == 6 for row in services.values()):
            break
    assert set(services) == expected, done.stdout
    web = [row for row in rows if row[:2] == [NS, "web"]]
    assert web, done.stdout  # the web view aiobt up serves, with its address
    assert web[0][-1].startswith("http://127.0.0.1:"), done.stdout
    assert all(row[2] == "0.1.0" and row[3] == "sim" for row in services.values()), done.stdout


def test_navigate_reaches_a_goal_with_live_feedback(system: str) -> None:
    done = aiobt(system, "navigate", "1.0", "1.0", "1.57")
    assert done.returncode == 0, done.stdout + done.stderr
    lines = done.stdout.splitlines()
    assert lines[-1].startswith("goal reached, "), lines[-1]
    off = float(lines[-1].split(", ")[1].split()[0])  # "goal reached, 0.12 m from the goal pose"
    assert off <= 0.3  # the goal checker's 0.25 m, and the newest feedback's lag
    progress = [line for line in lines if line.startswith("distance remaining")]
    assert float(progress[-1].split()[2]) <= 0.5, progress[-1]  # the last line is the newest


def test_navigate_through_counts_the_poses_down_as_the_robot_passes_them(system: str) -> None:
    # not ending where the robot stands: a path back to its start is done at once (as in Nav2,
    # the controller's goal checker looks at the path's end only)
    done = aiobt(system, "navigate", "--through", "1,1", "1.5,-1", "0.5,1.5")
    assert done.returncode == 0, done.stdout + done.stderr
    counts = [
        int(line.split("  ")[-1].split()[0])
        for line in done.stdout.splitlines()
        if line.endswith(("poses left", "pose left"))
    ]
    assert 2 in counts, done.stdout  # one line a second: each pose takes longer to pass
    assert counts[-1] == 1, done.stdout  # (the first may be passed at once: where is the robot?)
    assert counts == sorted(counts, reverse=True), done.stdout


def test_goal_refused_by_the_navigator_exits_1_with_its_reason(system: str) -> None:
    done = aiobt(system, "goal", "40", "40")
    assert done.returncode == 1, done.stdout + done.stderr
    assert done.stderr.startswith("aiobt goal: the navigator refused goal (40, 40, yaw 0): ")
    assert "outside the map" in done.stderr


def test_navigate_to_a_goal_off_the_map_fails_with_nav2s_error(system: str) -> None:
    done = aiobt(system, "navigate", "40", "40")
    assert done.returncode == 1
    assert done.stdout.splitlines()[-1].startswith("navigation ABORTED: error ")


def test_goal_then_monitor_sees_the_tree_run(system: str) -> None:
    aiobt(system, "navigate", "0.5", "0.0")  # so a tree is latched for the monitor to show first
    command = [sys.executable, "-m", "aiobt.cli.main", "monitor", "--plain", "-e", system, "-n", NS]
    with subprocess.Popen(command, stdout=subprocess.PIPE, text=True) as watcher:
        try:
            assert watcher.stdout is not None
            first = _line(watcher.stdout, 60.0)  # the monitor is subscribed once it shows this
            assert first.startswith("tree NavigateToPose"), first
            sent = aiobt(system, "goal", "-1.0", "-1.0")
            assert sent.returncode == 0, sent.stderr
            assert sent.stdout.strip() == (
                "goal (-1, -1, yaw 0) sent: the navigator is driving to it "
                "(follow it: aiobt monitor)"
            )
            deadline = time.monotonic() + 90.0
            line = ""
            while not _follows_path(line):
                line = _line(watcher.stdout, deadline - time.monotonic())
        finally:
            watcher.terminate()
    assert watcher.returncode in (0, -15)


def _line(stream: IO[str], timeout: float) -> str:
    """The next line of ``stream``; AssertionError after ``timeout`` s without one."""
    ready, _, _ = select.select([stream], [], [], max(0.0, timeout))
    assert ready, f"no monitor output within {timeout:.0f} s"
    return stream.readline()


def _follows_path(line: str) -> bool:
    return line.split()[2:] == ["RUNNING", "FollowPath"]  # "    1.2 s  RUNNING  FollowPath"


def test_monitor_once_prints_the_whole_tree(system: str) -> None:
    done = aiobt(system, "monitor", "--once")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("NavigateToPoseWReplanningAndRecovery (run ")
    assert any(line.split()[1:] == ["ComputePathToPose"] for line in lines)


def test_navigate_tells_of_a_planner_that_crashes_and_comes_back(system: str) -> None:
    status = aiobt(system, "status")
    [planner] = [row.split() for row in status.stdout.splitlines() if " planner " in row]
    far = ["1.5,1.5", "-1.5,1.9", "-1.5,-1.6", "1.5,-1.6"]  # long enough for a restart
    command = [sys.executable, "-m", "aiobt.cli.main", "navigate", "--through", *far,
               "-e", system, "-n", NS]  # fmt: skip
    with subprocess.Popen(command, stdout=subprocess.PIPE, text=True) as navigate:
        try:
            assert navigate.stdout is not None
            line = _line(navigate.stdout, 60.0)
            assert line.startswith("distance remaining"), line  # driving
            os.kill(int(planner[4]), signal.SIGKILL)  # aiobt up, this test's, restarts it
            told = [_line(navigate.stdout, 60.0)]
            while told[-1] and not told[-1].startswith("planner is back"):  # "": its end
                told.append(_line(navigate.stdout, 60.0))
            assert "planner went away (aiobt up restarts a crashed service)\n" in told, told
            assert told[-1] == "planner is back\n", told
            code = navigate.wait(120.0)
        finally:
            navigate.kill()
    assert code == 0  # the navigation still arrived
