"""``aiobt validate`` and the rough edges of ``run`` / ``nodes`` (issue 16)."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.cli.main import main

GOOD = """<root BTCPP_format="4" main_tree_to_execute="Main">
  <BehaviorTree ID="Main">
    <Sequence><Sleep msec="10"/><SubTree ID="Other"/></Sequence>
  </BehaviorTree>
  <BehaviorTree ID="Other"><AlwaysSuccess/></BehaviorTree>
</root>"""
BAD_PORT = """<root BTCPP_format="4">
  <BehaviorTree ID="Main">
    <Sequence>
      <Sleep msecs="10"/>
    </Sequence>
  </BehaviorTree>
</root>"""
MODEL = """<root BTCPP_format="4"><TreeNodesModel>
  <Decorator ID="Throttle"><input_port name="hz" type="double"/></Decorator>
  <Condition ID="IsDocked"/>
  <Action ID="Dock"/>
</TreeNodesModel></root>"""
USES_MODEL = """<root BTCPP_format="4"><BehaviorTree ID="Main">
  <Sequence>
    <Throttle hz="2"><Dock/></Throttle>
    <Script code="done := true"/>
    <IsDocked/>
  </Sequence>
</BehaviorTree></root>"""


def _file(tmp_path: Path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_validate_exits_0_when_every_file_and_tree_is_valid(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["validate", _file(tmp_path, "good.xml", GOOD)]) == 0
    out = capsys.readouterr().out
    assert "good.xml (Main, Other)" in out
    assert "1 of 1 files valid" in out


def test_validate_names_file_line_node_and_port_and_checks_every_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = _file(tmp_path, "bad.xml", BAD_PORT)
    good = _file(tmp_path, "good.xml", GOOD)
    assert main(["validate", bad, good]) == 1
    err = capsys.readouterr().err
    assert f"INVALID {bad}:4: attribute [msecs] is not a port of [Sleep]" in err
    assert "(did you mean [msec]?)" in err
    assert "(node Main/Sequence/Sleep)" in err
    assert "1 of 2 files valid" in err


def test_validate_a_file_of_node_models_an_empty_file_and_a_missing_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    model = _file(tmp_path, "model.xml", MODEL)
    empty = _file(tmp_path, "empty.xml", '<root BTCPP_format="4"/>')
    assert main(["validate", model]) == 0
    assert capsys.readouterr().out.splitlines()[0] == f"ok      {model} (3 node models, no tree)"
    assert main(["validate", model, empty, str(tmp_path / "gone.xml")]) == 1
    err = capsys.readouterr().err
    assert f"INVALID {empty}: no <BehaviorTree> and no <TreeNodesModel> in this file" in err
    assert "gone.xml" in err
    assert "1 of 3 files valid" in err


def test_validate_every_shipped_nav2_file_as_the_readme_does(
    capsys: pytest.CaptureFixture[str],
) -> None:
    nav2 = Path(__file__).parents[3] / "trees" / "nav2"
    files = sorted(str(p) for p in nav2.rglob("*.xml"))  # main's, kilted/, jazzy/, main/
    assert len(files) == 43
    assert main(["validate", *files]) == 0
    out = capsys.readouterr().out
    assert "nav2_tree_nodes.xml (" in out
    assert out.splitlines()[-1] == f"{len(files)} of {len(files)} files valid"


def test_an_unknown_id_mentions_plugin_and_nodes_model_without_a_misleading_guess(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    xml = '<root BTCPP_format="4"><BehaviorTree ID="M"><ID hz="1"><AlwaysSuccess/></ID>'
    xml += "</BehaviorTree></root>"
    path = _file(
        tmp_path,
        "ids.xml",
        xml.replace("ID hz", "RateControllr hz").replace("/ID", "/RateControllr"),
    )
    assert main(["validate", path]) == 1
    err = capsys.readouterr().err
    assert "unknown node ID [RateControllr] (did you mean [RateController]?)" in err
    assert "--plugin MODULE registers its implementation" in err
    assert "--nodes-model XML declares its ports" in err
    far = xml.replace("ID hz", "MyControllerPicker hz").replace("/ID", "/MyControllerPicker")
    main(["validate", _file(tmp_path, "far.xml", far)])
    assert "did you mean" not in capsys.readouterr().err


def test_validate_with_a_nodes_model_accepts_its_nodes(tmp_path: Path) -> None:
    model = _file(tmp_path, "model.xml", MODEL)
    tree = _file(tmp_path, "tree.xml", USES_MODEL)
    assert main(["validate", tree]) == 1
    assert main(["validate", tree, "--nodes-model", model]) == 0


def test_run_stub_missing_stubs_only_unimplemented_nodes_and_passes_through_decorators(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    model = _file(tmp_path, "model.xml", MODEL)
    tree = _file(tmp_path, "tree.xml", USES_MODEL)
    args = ["run", tree, "--nodes-model", model, "--trace", "all", "--speed", "50"]
    assert main([*args, "--stub-missing", "SUCCESS:0.5"]) == 0
    out = capsys.readouterr().out
    assert "RUNNING  Main/Sequence/Throttle/Dock" not in out  # names are short: no tree prefix
    assert "SUCCESS  Script" in out  # the real Script ran, it was not stubbed
    assert "RUNNING  Dock" in out  # the stubbed action took its 0.5 s
    assert "SUCCESS  Throttle" in out
    assert "tree Main: SUCCESS" in out


def test_run_with_a_model_only_decorator_and_no_stub_fails_clearly(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    model = _file(tmp_path, "model.xml", MODEL)
    tree = _file(tmp_path, "tree.xml", USES_MODEL)
    assert main(["run", tree, "--nodes-model", model, "--trace", "none"]) == 1
    assert "Throttle" in capsys.readouterr().err


def test_a_delayed_stub_on_a_condition_answers_at_once_so_a_reactive_tree_ends(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    xml = """<root BTCPP_format="4"><BehaviorTree ID="R">
      <ReactiveSequence><IsDocked/><Dock/></ReactiveSequence>
    </BehaviorTree></root>"""
    tree = _file(tmp_path, "reactive.xml", xml)
    model = _file(tmp_path, "model.xml", MODEL)
    args = ["run", tree, "--nodes-model", model, "--stub", "*=SUCCESS:0.5", "--speed", "50"]
    assert main([*args, "--max-time", "20"]) == 0
    out = capsys.readouterr().out
    assert "RUNNING  IsDocked" not in out
    assert "tree R: SUCCESS after" in out


def test_run_a_file_without_trees_names_the_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    model = _file(tmp_path, "model.xml", MODEL)
    assert main(["run", model]) == 2
    assert capsys.readouterr().err.strip() == f"aiobt run: {model}: no <BehaviorTree> in this file"


def test_run_several_trees_without_a_main_one_asks_for_tree(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _file(tmp_path, "two.xml", GOOD.replace(' main_tree_to_execute="Main"', ""))
    assert main(["run", path]) == 2
    err = capsys.readouterr().err
    assert f"{path}: 2 trees (Main, Other) and no main_tree_to_execute" in err
    assert "--tree ID" in err
    assert main(["run", path, "--tree", "Other", "--trace", "none"]) == 0


def test_nodes_takes_a_nodes_model(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    model = _file(tmp_path, "model.xml", MODEL)
    assert main(["nodes", "--nodes-model", model, "--list"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert "Decorator  Throttle" in out
    assert "Condition  IsDocked" in out
