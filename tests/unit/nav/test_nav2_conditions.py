"""Nav2 conditions: error-code checks and timers on the tree's clock; port manifest."""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.convert import convert, type_name
from aiobt.core.errors import NodeError, PortError
from aiobt.core.status import Status
from aiobt.msgs.nav import Path
from aiobt.testing.stubs import tree_xml
from aiobt.xml.model import read_tree_nodes_model
from tests.unit.nav.test_nav2_support import Script, build, nav2_factory

S, F = Status.SUCCESS, Status.FAILURE
NAV2_IDS = [
    "PipelineSequence",
    "RecoveryNode",
    "RoundRobin",
    "NonblockingSequence",
    "PersistentSequence",
    "RateController",
    "SingleTrigger",
    "GoalUpdatedController",
    "AreErrorCodesPresent",
    "WouldAControllerRecoveryHelp",
    "WouldAPlannerRecoveryHelp",
    "WouldASmootherRecoveryHelp",
    "WouldARouteRecoveryHelp",
    "TimeExpired",
    "PathExpiringTimer",
]


def test_ports_match_the_nav2_manifest() -> None:
    ours = nav2_factory().manifests
    nav2 = {m.id: m for m in read_tree_nodes_model("trees/nav2/nav2_tree_nodes.xml")}
    for node_id in NAV2_IDS:
        mine, theirs = ours[node_id], nav2[node_id]
        assert mine.kind == theirs.kind, node_id
        assert set(mine.ports) == set(theirs.ports), node_id
        for name, port in mine.ports.items():
            other = theirs.ports[name]
            # typed by class (PoseStamped, Path ...), exported under Nav2's names
            ours_type, theirs_type = type_name(port.type), type_name(other.type)
            assert (ours_type, port.direction) == (theirs_type, other.direction), (node_id, name)
            if other.has_default:
                assert port.default == convert(other.default, other.type), (node_id, name)
            else:
                assert not port.has_default, (node_id, name)


async def _check(xml: str, code: int) -> Status:
    tree = build(Script(), xml)
    tree.root_blackboard["code"] = code
    return await tree.tick_exactly_once()


@pytest.mark.parametrize("codes", ["101,107,119", "101;107;119", " 101 , 107 "])
async def test_are_error_codes_present_accepts_both_separators(codes: str) -> None:
    xml = f'<AreErrorCodesPresent error_code="{{code}}" error_codes_to_check="{codes}"/>'
    assert await _check(xml, 107) is S
    assert await _check(xml, 102) is F


async def test_are_error_codes_present_reads_the_list_from_the_blackboard() -> None:
    tree = build(Script(), '<AreErrorCodesPresent error_code="{c}" error_codes_to_check="{l}"/>')
    tree.root_blackboard["c"] = 5
    tree.root_blackboard["l"] = [4, 5]
    assert await tree.tick_exactly_once() is S
    tree.root_blackboard["l"] = [6]
    assert await tree.tick_exactly_once() is F


async def test_are_error_codes_present_without_an_error_code_names_the_port() -> None:
    tree = build(Script(), '<AreErrorCodesPresent error_code="{c}" error_codes_to_check="1"/>')
    with pytest.raises((NodeError, PortError), match="error_code"):
        await tree.tick_exactly_once()


HELP = {
    "WouldAControllerRecoveryHelp": ({100, 104, 105, 106}, {0, 101, 102, 103, 107, 208}),
    "WouldAPlannerRecoveryHelp": ({200, 207, 208, 300, 307, 308}, {0, 201, 206, 309, 104}),
    "WouldASmootherRecoveryHelp": ({500, 502, 503, 504}, {0, 501, 505, 100}),
    "WouldARouteRecoveryHelp": ({400, 404, 405}, {0, 401, 402, 403, 406, 500}),
}


@pytest.mark.parametrize("node_id", sorted(HELP))
async def test_would_a_recovery_help_uses_nav2_codes(node_id: str) -> None:
    helps, does_not = HELP[node_id]
    xml = f'<{node_id} error_code="{{code}}"/>'
    assert [await _check(xml, c) for c in sorted(helps)] == [S] * len(helps)
    assert [await _check(xml, c) for c in sorted(does_not)] == [F] * len(does_not)


async def test_would_a_recovery_help_honours_an_explicit_list() -> None:
    xml = '<WouldAControllerRecoveryHelp error_code="{code}" error_codes_to_check="103"/>'
    assert await _check(xml, 103) is S
    assert await _check(xml, 100) is F


async def test_time_expired_counts_from_its_activation() -> None:
    clock = ManualClock()
    tree = build(Script(), '<TimeExpired seconds="1.0"/>', clock)
    node = tree.root
    results = []
    for _ in range(5):  # t = 0, 0.5, 1.0, 1.5, 2.0, ticked without resets
        results.append(await node.tick())
        clock.advance(0.5)
    assert results == [F, F, S, F, S]


async def test_time_expired_never_expires_when_reset_every_tick_nav2_behaviour() -> None:
    clock = ManualClock()
    tree = build(Script(), '<TimeExpired seconds="0.5"/>', clock)
    results = []
    for _ in range(4):  # the tree resets a finished root to IDLE after each tick
        results.append(await tree.tick_exactly_once())
        clock.advance(1.0)
    assert results == [F, F, F, F]


async def test_path_expiring_timer_restarts_on_a_new_path() -> None:
    clock = ManualClock()
    tree = build(Script(), '<PathExpiringTimer seconds="1.0" path="{path}"/>', clock)
    bb = tree.root_blackboard
    first = Path()
    bb["path"] = first
    results = [await tree.tick_exactly_once()]  # t=0: starts, FAILURE
    clock.set(0.6)
    results.append(await tree.tick_exactly_once())
    clock.set(1.0)
    results.append(await tree.tick_exactly_once())  # expired (survives the tree's resets)
    clock.set(1.5)
    bb["path"] = Path()  # equal value, another object: not a new path
    results.append(await tree.tick_exactly_once())
    clock.set(2.0)
    bb["path"] = Path(poses=[])
    results.append(await tree.tick_exactly_once())  # expired: equal paths do not reset
    clock.set(2.2)
    bb["path"] = first.model_copy(update={"header": first.header.model_copy(update={"stamp": 9.0})})
    results.append(await tree.tick_exactly_once())  # a really new path: restart at 2.2
    clock.set(3.1)
    results.append(await tree.tick_exactly_once())
    clock.set(3.2)
    results.append(await tree.tick_exactly_once())
    assert results == [F, F, S, F, S, F, F, S]


def test_nav2_nodes_export_in_the_tree_nodes_model() -> None:
    xml = nav2_factory().tree_nodes_model_xml(include_builtins=True)
    assert '<Control ID="RecoveryNode">' in xml
    assert 'name="number_of_retries" type="int" default="1"' in xml
    assert tree_xml("<x/>")  # helper still importable
