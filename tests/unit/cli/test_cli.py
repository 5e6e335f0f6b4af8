"""The ``aiobt`` command line: run, nodes, the patrol example (in-process)."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import pytest

from aiobt.cli import run as run_cli
from aiobt.cli.main import main
from aiobt.core.errors import BlackboardError
from aiobt.examples import patrol

REPO = Path(__file__).resolve().parents[3]
NAV2 = REPO / "trees" / "nav2"


def test_the_patrol_example_charges_when_the_battery_runs_low_and_succeeds(
    capsys: pytest.CaptureFixture[str],
) -> None:
    parser = argparse.ArgumentParser()
    run_cli.add_tree_arguments(parser)
    args = parser.parse_args(["--speed", "200", "--plugin", "aiobt.examples.patrol"])
    factory = run_cli.build_factory(args)
    factory.register_behavior_tree_from_text(patrol.PATROL_XML, file=patrol.__file__)
    bb = run_cli.root_blackboard([], patrol.INITIAL_STATE)
    tree = factory.create_tree(blackboard=bb, clock=run_cli.speed_clock(args.speed))
    assert run_cli.finish(tree, args) == 0
    out = capsys.readouterr().out
    lines = [
        line.split(maxsplit=2)[1:]
        for line in out.splitlines()
        if line.strip().endswith(("move", "charge", "battery_ok"))
    ]
    events = [" ".join(parts) for parts in lines]
    # lap 1 visits the three waypoints without trouble
    assert events[:3] == [
        "SUCCESS visit_a/battery_ok",
        "RUNNING visit_a/move",
        "SUCCESS visit_a/move",
    ]
    # on lap 2 the battery check fails mid-move: the move is halted, the robot charges, and retries
    low = events.index("FAILURE visit_a/battery_ok")
    assert events[low + 1 : low + 4] == [
        "halted visit_a/move",
        "RUNNING visit_a/charge",
        "SUCCESS visit_a/charge",
    ]
    assert events[-1] == "SUCCESS visit_home/move"
    assert "tree Patrol: SUCCESS" in out
    assert bb["pose"][:2] == pytest.approx((0.0, 0.0), abs=0.01)


def test_run_reports_a_bad_port_with_file_and_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    tree = tmp_path / "bad.xml"
    tree.write_text(
        '<root BTCPP_format="4">\n  <BehaviorTree ID="T">\n'
        '    <Sleep msecs="10"/>\n  </BehaviorTree>\n</root>\n'
    )
    assert main(["run", str(tree)]) == 2
    err = capsys.readouterr().err
    assert f"{tree}:3" in err
    assert "[msecs]" in err
    assert "did you mean [msec]" in err


def test_run_halts_at_max_time_and_fails(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    tree = tmp_path / "long.xml"
    tree.write_text(
        '<root BTCPP_format="4"><BehaviorTree ID="T"><Sleep msec="100000"/></BehaviorTree></root>'
    )
    assert main(["run", str(tree), "--speed", "100", "--max-time", "1", "--trace", "all"]) == 1
    out = capsys.readouterr().out
    assert "halted" in out
    assert "tree T: halted at --max-time 1 s of clock time (it was RUNNING)" in out


def test_run_nav2_tree_with_stubbed_leaves_validates_ports_against_the_manifest(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = (NAV2 / "navigate_to_pose_w_replanning_and_recovery.xml").read_text()
    assert 'path="{path}"' in text
    broken = tmp_path / "nav.xml"
    broken.write_text(text.replace('path="{path}"', 'pathh="{path}"', 1))
    args = [
        "run",
        str(broken),
        "--nodes-model",
        str(NAV2 / "nav2_tree_nodes.xml"),
        "--stub",
        "*=SUCCESS",
    ]
    assert main(args) == 2
    assert "[pathh]" in capsys.readouterr().err


def test_stub_spec_errors_are_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    tree = tmp_path / "t.xml"
    tree.write_text(
        '<root BTCPP_format="4"><BehaviorTree ID="T"><AlwaysSuccess/></BehaviorTree></root>'
    )
    assert main(["run", str(tree), "--stub", "X=MAYBE"]) == 2
    assert "--stub 'X=MAYBE'" in capsys.readouterr().err


def test_nodes_lists_the_builtins(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["nodes", "--builtins", "--list"]) == 0
    ids = {line.split()[1] for line in capsys.readouterr().out.splitlines()}
    assert {"Sequence", "ReactiveFallback", "Switch6", "RetryUntilSuccessful", "Sleep"} <= ids


def test_nodes_model_of_a_plugin_is_xml_with_its_ports(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["nodes", "--plugin", "aiobt.examples.patrol"]) == 0
    out = capsys.readouterr().out
    assert "<TreeNodesModel>" in out
    assert '<Action ID="MoveTo"' in out
    assert 'name="goal"' in out


def test_run_writes_the_requested_logs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import json
    import sqlite3

    tree = tmp_path / "t.xml"
    tree.write_text(
        '<root BTCPP_format="4"><BehaviorTree ID="T">'
        '<Sequence><AlwaysSuccess/><Sleep msec="200"/></Sequence></BehaviorTree></root>'
    )
    logs = [tmp_path / "t.btlog", tmp_path / "t.jsonl", tmp_path / "t.db3"]
    args = ["run", str(tree), "--speed", "50", "--btlog", str(logs[0]), "--jsonl", str(logs[1])]
    assert main([*args, "--sqlite", str(logs[2]), "--stats"]) == 0
    assert logs[0].read_bytes().startswith(b"BTCPP4-FileLogger2")
    rows = [json.loads(line) for line in logs[1].read_text().splitlines()]
    assert [(r["path"], r["to"]) for r in rows if r["path"].endswith("Sleep")] == [
        ("T/Sequence/Sleep", "RUNNING"),
        ("T/Sequence/Sleep", "SUCCESS"),
        ("T/Sequence/Sleep", "IDLE"),
    ]
    with sqlite3.connect(logs[2]) as db:
        assert db.execute("SELECT COUNT(*) FROM Transitions").fetchone()[0] == len(rows)
    out = capsys.readouterr().out  # the --stats rendering of the tree, after the trace
    assert "├── ○ AlwaysSuccess [IDLE] ticks=1 ok=1 fail=0" in out
    assert re.search(r"└── ○ Sleep \[IDLE\] ticks=\d+ ok=1 fail=0", out)


def test_run_picks_the_tree_asked_for_and_names_an_unknown_one(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    two = tmp_path / "two.xml"
    two.write_text(
        '<root BTCPP_format="4" main_tree_to_execute="Fails">'
        '<BehaviorTree ID="Fails"><AlwaysFailure/></BehaviorTree>'
        '<BehaviorTree ID="Works"><AlwaysSuccess/></BehaviorTree></root>'
    )
    assert main(["run", str(two)]) == 1
    assert main(["run", str(two), "--tree", "Works"]) == 0
    assert "tree Works: SUCCESS" in capsys.readouterr().out
    assert main(["run", str(two), "--tree", "Work"]) == 2
    assert "did you mean [Works]" in capsys.readouterr().err


def test_a_set_value_of_the_wrong_type_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(BlackboardError, match=r"blackboard \[battery\]: cannot convert 'low'"):
        run_cli.root_blackboard(["battery=low"], patrol.INITIAL_STATE)
