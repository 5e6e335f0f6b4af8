"""Every shell command in the README's code blocks, run as a new user would type it.

Each line runs through bash in a scratch directory holding ``.venv`` (this test's
interpreter's) and ``trees`` (the repository's), with this test's own router
endpoint and ports in place of the README's fixed ones (loopback only): each
must exit 0 (a long-running one: come up, then stop cleanly on Ctrl-C) and
print what the README says it does. The two opening commands are run elsewhere
(:data:`ELSEWHERE`); a README command run nowhere fails
:func:`test_every_command_of_the_readme_is_run_by_a_test`.
"""

from __future__ import annotations

import json
import re
import sys
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

from aiobt.testing.bus import free_endpoint, free_port
from tests.unit.cli.test_readme import _blocks

from .helpers import kill_mentioning, processes_mentioning
from .readme_shell import Shell, Terminal, command_lines

pytestmark = [pytest.mark.integration, pytest.mark.timeout(300)]
REPO = Path(__file__).resolve().parents[3]
README_ROUTER = "tcp/127.0.0.1:7447"
ELSEWHERE = {  # the opening blocks: what runs them
    "python3 -m venv .venv && .venv/bin/pip install -q -e \".[dev]\" && .venv/bin/aiobt demo":
        "tests/e2e/test_demo.py (aiobt demo); CI (.ci/run) sets the repository up that way",
    "python3 -m venv .venv && .venv/bin/pip install -q -e \".[dev]\" && .venv/bin/python -m pytest":
        "CI: the last line of .ci/run (tests/unit/cli/test_readme.py holds them equal)",
}  # fmt: skip
RUN_HERE = (  # how the tests below find the README lines they run
    ".venv/bin/aiobt up --world small",
    ".venv/bin/aiobt up --config system.yaml",
    ".venv/bin/aiobt status",
    ".venv/bin/aiobt navigate 1.5 1.5 1.57",
    ".venv/bin/aiobt navigate --through",
    ".venv/bin/aiobt goal -1.5 -1.6",
    ".venv/bin/aiobt monitor",
    ".venv/bin/aiobt foxglove --mcap run.mcap",
    ".venv/bin/aiobt web --port 8081",
    ".venv/bin/zenoh --mode client --connect tcp/127.0.0.1:7447 put",
    ".venv/bin/zenoh --mode client --connect tcp/127.0.0.1:7447 get",
    ".venv/bin/aiobt validate trees/nav2/*.xml",
    ".venv/bin/aiobt router --listen",
    ".venv/bin/aiobt robot --connect",
    ".venv/bin/aiobt localization --connect",
    "for s in planner controller behaviors navigator",
    ".venv/bin/aiobt run mission.xml --plugin mypkg.nodes",
    ".venv/bin/aiobt run trees/nav2/navigate_to_pose_w_replanning_and_recovery",
    ".venv/bin/aiobt nodes --plugin mypkg.nodes > models.xml",
    ".venv/bin/aiobt run mission.xml --plugin mypkg.nodes --groot2",
)


def readme_line(start: str) -> str:
    """The one README command line that starts with ``start`` (one of :data:`RUN_HERE`)."""
    assert start in RUN_HERE, start
    lines = command_lines()
    found = [start] if start in lines else [line for line in lines if line.startswith(start)]
    assert len(found) == 1, f"{start!r}: {found}"
    return found[0]


@pytest.fixture(scope="module")
def shell(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Shell]:
    here = tmp_path_factory.mktemp("readme")
    (here / ".venv").symlink_to(Path(sys.executable).parent.parent)
    (here / "trees").symlink_to(REPO / "trees")
    endpoint = free_endpoint()
    try:
        yield Shell(here, endpoint)
    finally:
        kill_mentioning(endpoint)


@pytest.fixture(scope="module")
def system(shell: Shell) -> Iterator[Terminal]:
    """``aiobt up --config system.yaml``, the README's file with this test's router."""
    config = yaml.safe_load(_blocks("yaml")[0])
    config["router"]["listen"] = shell.endpoint
    (shell.cwd / "system.yaml").write_text(yaml.safe_dump(config))
    line = readme_line(".venv/bin/aiobt up --config system.yaml")
    with shell.start(line, "--web-port", "0") as up:
        up.wait_for(
            "        up * robot, localization, planner, controller, behaviors, "
            "velocity_smoother, collision_monitor, navigator up"
        )
        yield up
        assert up.interrupt(within=20.0) == 0, up.text()


def test_up_on_the_small_world_comes_up_and_stops_on_ctrl_c(shell: Shell) -> None:
    line = readme_line(".venv/bin/aiobt up --world small")
    other = free_endpoint()
    with shell.start(line, "--listen", other, "--web-port", "0") as up:
        up.wait_for("(wall time)")
        # "in under 3 s" on a quiet machine (test_up.py); here only bounded: the tests
        # share two cores with other work
        assert up.interrupt(within=20.0) == 0, up.text()
    assert processes_mentioning(other) == []  # everything stopped
    kill_mentioning(other)


def test_the_tour_with_the_system_up(shell: Shell, system: Terminal) -> None:
    assert "(sim time x4)" in system.wait_for("        up * ")  # speed: 4 in system.yaml
    status = shell.run(readme_line(".venv/bin/aiobt status"))
    assert status.splitlines()[0].startswith(f"router {shell.endpoint} (Zenoh id ")
    services = {row.split()[1] for row in status.splitlines()[2:] if row.startswith("robot ")}
    assert services == {
        "robot", "localization", "planner", "controller", "behaviors", "velocity_smoother",
        "collision_monitor", "navigator", "web",
    }  # fmt: skip
    lines = shell.run(readme_line(".venv/bin/aiobt navigate 1.5 1.5 1.57")).splitlines()
    assert any(line.startswith("distance remaining") for line in lines)  # live feedback
    assert lines[-1].startswith("goal reached, "), lines
    lines = shell.run(readme_line(".venv/bin/aiobt navigate --through")).splitlines()
    left = [int(m.group(1)) for m in map(re.compile(r"(\d) poses? left$").search, lines) if m]
    assert left == sorted(left, reverse=True), lines  # counted down as they are passed
    assert left[0] >= 2, lines  # (1, 1) is within 0.7 m of the last goal: passed at once
    assert left[-1] == 1, lines
    assert lines[-1].startswith("goal reached, "), lines
    said = shell.run(readme_line(".venv/bin/aiobt goal -1.5 -1.6"))
    assert "the navigator is driving to it" in said


def test_the_viewers_with_the_system_up(shell: Shell, system: Terminal) -> None:
    with shell.start(readme_line(".venv/bin/aiobt monitor")) as monitor:
        assert monitor.wait_for("tree ").startswith("tree NavigateToPose")  # piped: --plain
        assert monitor.interrupt() == 0, monitor.text()
    port = free_port()
    with shell.start(
        readme_line(".venv/bin/aiobt foxglove --mcap run.mcap"), "--port", str(port)
    ) as foxglove:
        foxglove.wait_for(f"Foxglove server on ws://127.0.0.1:{port}")
        assert foxglove.interrupt() == 0, foxglove.text()
    assert (shell.cwd / "run.mcap").read_bytes()[:8] == b"\x89MCAP0\r\n"  # recorded
    web_port = str(free_port())
    with shell.start(readme_line(".venv/bin/aiobt web --port 8081"), port=web_port) as web:
        web.wait_for(f"web view on http://127.0.0.1:{web_port}/")
        with urllib.request.urlopen(f"http://127.0.0.1:{web_port}/", timeout=10) as page:
            assert '<canvas id="map"' in page.read().decode()
        assert web.interrupt() == 0, web.text()


def test_the_zenoh_command_line_with_the_system_up(shell: Shell, system: Terminal) -> None:
    shell.run(readme_line(".venv/bin/zenoh --mode client --connect tcp/127.0.0.1:7447 put"))
    system.wait_for("goal_pose (1.5, -0.5) received")  # the navigator took the goal
    info = shell.run(readme_line(".venv/bin/zenoh --mode client --connect tcp/127.0.0.1:7447 get"))
    assert json.loads(info.splitlines()[-1])["service"] == "navigator"  # JSON, not base64


def test_validate_the_shipped_trees(shell: Shell) -> None:
    out = shell.run(readme_line(".venv/bin/aiobt validate trees/nav2/*.xml"))
    shipped = len(list((REPO / "trees" / "nav2").glob("*.xml")))
    assert out.splitlines()[-1] == f"{shipped} of {shipped} files valid"
    assert "nav2_tree_nodes.xml (81 node models, no tree)" in out


def test_two_machines_one_router_here_on_one(shell: Shell) -> None:
    """The two-machine example on loopback: its router, its robot, then the loop."""
    machines = Shell(shell.cwd, free_endpoint())  # not the tour's router
    try:
        with (
            machines.start(readme_line(".venv/bin/aiobt router --listen")) as router,
            machines.start(readme_line(".venv/bin/aiobt robot --connect")) as robot,
            machines.start(readme_line(".venv/bin/aiobt localization --connect")) as loc,
        ):
            router.wait_for(f"listening on {machines.endpoint}")
            robot.wait_for("robot up on namespace 'robot'")
            loc.wait_for("localization up on namespace 'robot'")
            loop = readme_line("for s in planner controller behaviors navigator")
            with machines.start(loop + "; wait") as rest:  # wait: the loop's shell stays
                for name in ("planner", "controller", "behaviors", "navigator"):
                    rest.wait_for(f"{name} up on namespace 'robot'")
                status = machines.run(".venv/bin/aiobt status")
                rows = [row.split() for row in status.splitlines()[2:]]
                assert {row[1] for row in rows} == {
                    "robot", "localization", "planner", "controller", "behaviors", "navigator"
                }, status  # fmt: skip
                assert all(row[3] == "sim" for row in rows if row[1] != "robot"), status
                rest.interrupt()  # its shell's code is the interrupted wait's
            assert robot.interrupt() == 0, robot.text()
            assert router.interrupt() == 0, router.text()
    finally:
        kill_mentioning(machines.endpoint)
    assert processes_mentioning(machines.endpoint) == []


MISSION = """<root BTCPP_format="4"><BehaviorTree ID="Mission">
  <Sequence><Say message="hello"/><Say message="world"/></Sequence>
</BehaviorTree></root>"""
PLUGIN = """from aiobt import AsyncActionNode, BehaviorTreeFactory, Status, input_port


class Say(AsyncActionNode):
    PORTS = (input_port("message", str),)

    async def run(self) -> Status:
        await self.clock.sleep(0.1)
        print(self.get_input("message"))
        return Status.SUCCESS


def register(factory: BehaviorTreeFactory) -> None:
    factory.register_node_type(Say)
"""


def test_running_your_own_tree(shell: Shell) -> None:
    """``mission.xml`` and ``mypkg.nodes`` stand for the reader's: a small pair here."""
    (shell.cwd / "mission.xml").write_text(MISSION)
    (shell.cwd / "mypkg").mkdir()
    (shell.cwd / "mypkg" / "__init__.py").write_text("")
    (shell.cwd / "mypkg" / "nodes.py").write_text(PLUGIN)
    out = shell.run(readme_line(".venv/bin/aiobt run mission.xml --plugin mypkg.nodes"))
    assert out.splitlines()[-1].startswith("tree Mission: SUCCESS after "), out
    nav2 = readme_line(".venv/bin/aiobt run trees/nav2/navigate_to_pose_w_replanning_and_recovery")
    out = shell.run(nav2)
    assert out.splitlines()[-1].startswith("tree NavigateToPoseWReplanningAndRecovery: SUCCESS")
    shell.run(readme_line(".venv/bin/aiobt nodes --plugin mypkg.nodes > models.xml"))
    assert '<Action ID="Say">' in (shell.cwd / "models.xml").read_text()
    port = str(free_port())  # not Groot2's 1667: another test may hold it
    out = shell.run(
        readme_line(".venv/bin/aiobt run mission.xml --plugin mypkg.nodes --groot2"), port
    )
    assert out.splitlines()[-1].startswith("tree Mission: SUCCESS after "), out


def test_every_command_of_the_readme_is_run_by_a_test() -> None:
    lines = command_lines()
    missing = [line for line in lines if line not in ELSEWHERE and not line.startswith(RUN_HERE)]
    assert not missing, "README commands no test runs:\n" + "\n".join(missing)
    assert set(ELSEWHERE) <= set(lines)  # what is run elsewhere is still in the README
