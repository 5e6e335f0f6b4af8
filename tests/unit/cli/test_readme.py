"""The README's examples run as written (so they never rot)."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from aiobt.cli.main import _full_parser, main
from aiobt.system.commands import router_command, service_command
from aiobt.system.config import config_from_dict

REPO = Path(__file__).resolve().parents[3]
README = (REPO / "README.md").read_text(encoding="utf-8")


def _blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", README, flags=re.S)


def test_readme_opens_with_the_setup_and_test_commands_ci_runs() -> None:
    first, second = _blocks("bash")[:2]
    assert first.strip().endswith(".venv/bin/aiobt demo")
    test_command = second.strip()
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8")
    assert ci.strip().splitlines()[-1] == test_command


def test_embedding_example_runs_and_succeeds(tmp_path: Path) -> None:
    [example] = _blocks("python")
    # the example sleeps a wall-clock second per leaf; a shorter sleep keeps the test quick
    script = tmp_path / "example.py"
    script.write_text(
        example.replace("await self.clock.sleep(1.0)", "await self.clock.sleep(0.01)")
    )
    done = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, timeout=60, check=False
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["hello", "world", "Status.SUCCESS"]


def _commands(marker: str = ".venv/bin/aiobt run ") -> list[list[str]]:
    """The commands of the first bash block holding ``marker``, comments dropped."""
    block = next(b for b in _blocks("bash")[2:] if marker in b).replace("\\\n", " ")
    lines = [line.split(" #")[0] for line in block.splitlines() if not line.startswith("#")]
    return [shlex.split(line) for line in lines if line.strip()]


def test_the_tour_commands_exist_and_their_flags_parse() -> None:
    tour = _commands(".venv/bin/aiobt up") + _commands(".venv/bin/aiobt navigate")
    aiobt = [c[1:] for c in tour if c[0] == ".venv/bin/aiobt"]
    assert {c[0] for c in aiobt} >= {"up", "status", "navigate", "goal", "monitor", "validate"}
    for argv in aiobt:
        _full_parser(argv).parse_args(argv)  # SystemExit on an unknown flag


def test_the_tour_config_is_a_valid_system_config() -> None:
    config, _ = _blocks("yaml")
    loaded = config_from_dict(yaml.safe_load(config), "README")
    assert loaded.uses_sim_time
    assert loaded.services["controller"].args == ("--max-speed", "0.4")


def test_the_realtime_config_gives_each_service_its_default_priority() -> None:
    _, config = _blocks("yaml")
    loaded = config_from_dict(yaml.safe_load(config), "README")
    levels = (("robot", 90), ("controller", 90), ("velocity_smoother", 90),
              ("collision_monitor", 90), ("planner", 70), ("navigator", 60))  # fmt: skip
    for name, level in levels:
        argv = service_command(name, loaded)
        args = _full_parser(argv).parse_args(argv)  # SystemExit on an unknown flag
        assert args.realtime_priority == level, name
    argv = router_command(loaded)
    assert _full_parser(argv).parse_args(argv).realtime_priority == 60


def test_the_embedding_snippet_is_the_example_a_test_runs() -> None:
    [snippet] = _blocks("py")
    example = (REPO / "examples" / "embedded.py").read_text()
    for line in snippet.strip().splitlines():
        assert line.strip() in example, line


def test_the_nav2_run_command_of_the_readme_succeeds(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    [command] = [c for c in _commands() if "trees/nav2/nav2_tree_nodes.xml" in c]
    monkeypatch.chdir(REPO)
    assert main(command[1:]) == 0
    assert "SUCCESS after" in capsys.readouterr().out


def test_the_nodes_command_of_the_readme_prints_a_model(
    capsys: pytest.CaptureFixture[str],
) -> None:
    [command] = [c for c in _commands() if "nodes" in c[:2]]
    args = [a if a != "mypkg.nodes" else "aiobt.examples.patrol" for a in command[1:]]
    assert args[-2:] == [">", "models.xml"]
    assert main(args[:-2]) == 0
    assert "<TreeNodesModel>" in capsys.readouterr().out
