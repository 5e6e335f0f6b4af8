"""Selectors: default until a message, then the last one; plain text, JSON, std_msgs/String;
one shared latched subscription per key."""

from __future__ import annotations

import logging

import pytest

from aiobt.core.status import Status
from aiobt.msgs import String
from aiobt.nav import NavContext
from aiobt.nav.shared_topics import shared_topics
from aiobt.transport import Bus
from tests.unit.nav.state_support import deliver, nav_tree, wait_received

S, F = Status.SUCCESS, Status.FAILURE
PLANNER = (
    '<PlannerSelector topic_name="planner_selector" default_planner="GridBased" '
    'selected_planner="{planner}"/>'
)

pytestmark = pytest.mark.timeout(60)


async def test_outputs_the_default_until_a_message_then_the_last_message(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, PLANNER)
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["planner"] == "GridBased"
    await deliver(local_bus, "planner_selector", String(data="SmacHybrid"))
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["planner"] == "SmacHybrid"


async def test_the_output_is_written_again_when_another_node_changed_or_unset_it(
    local_bus: Bus,
) -> None:
    tree = nav_tree(local_bus, PLANNER)
    board = tree.root_blackboard
    assert await tree.tick_exactly_once() is S
    written = board.entry("planner")
    assert written is not None
    board["planner"] = "Overwritten"
    assert await tree.tick_exactly_once() is S
    assert board["planner"] == "GridBased"
    board.unset("planner")
    assert written.has_value is False  # a holder of the removed entry can tell
    assert await tree.tick_exactly_once() is S
    assert board["planner"] == "GridBased"
    again = board.entry("planner")
    assert again is not None
    assert again is not written
    sequence = again.sequence_id
    assert await tree.tick_exactly_once() is S
    assert again.sequence_id == sequence  # unchanged: not written again


async def test_no_message_and_no_default_fails(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<ControllerSelector selected_controller="{c}"/>')
    assert await tree.tick_exactly_once() is F


@pytest.mark.parametrize("payload", [b"FollowPathB", b'"FollowPathB"', b'{"data": "FollowPathB"}'])
async def test_raw_text_a_json_string_and_std_msgs_string_all_switch_it(
    local_bus: Bus, payload: bytes
) -> None:
    tree = nav_tree(
        local_bus,
        '<ControllerSelector default_controller="FollowPath" selected_controller="{c}"/>',
    )
    topic = shared_topics(NavContext(bus=local_bus), "test").topic("controller_selector", String)
    local_bus.session.put(f"{local_bus.namespace}/controller_selector", payload)
    await wait_received(topic, 0)
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["c"] == "FollowPathB"


async def test_a_late_selector_gets_the_latched_value(local_bus: Bus) -> None:
    publisher = local_bus.latched_publisher("goal_checker_selector", String)
    publisher.put(String(data="precise_goal_checker"))
    tree = nav_tree(
        local_bus,
        '<GoalCheckerSelector default_goal_checker="general" selected_goal_checker="{g}"/>',
    )
    topic = shared_topics(NavContext(bus=local_bus), "test").topic(
        "goal_checker_selector", String, latched=True
    )
    await wait_received(topic, 0)
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["g"] == "precise_goal_checker"


async def test_two_factories_share_one_subscription_per_key(local_bus: Bus) -> None:
    first = nav_tree(local_bus, PLANNER)
    second = nav_tree(local_bus, PLANNER.replace("{planner}", "{other}"))
    hub = shared_topics(NavContext(bus=local_bus), "test")
    assert hub.subscribed().count(f"{local_bus.namespace}/planner_selector") == 1
    await deliver(local_bus, "planner_selector", String(data="Theta"))
    for tree, key in ((first, "planner"), (second, "other")):
        assert await tree.tick_exactly_once() is S
        assert tree.root_blackboard[key] == "Theta"


async def test_bad_data_keeps_the_last_good_value_and_is_logged_once(
    local_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    tree = nav_tree(local_bus, PLANNER)
    await deliver(local_bus, "planner_selector", String(data="Good"))
    hub = shared_topics(NavContext(bus=local_bus), "test")
    topic = hub.topic("planner_selector", String)
    assert topic.reader is not None
    with caplog.at_level(logging.WARNING):
        for _ in range(6):  # each read while it is the newest
            before = topic.received
            local_bus.session.put(f"{local_bus.namespace}/planner_selector", b'{"data": 5}')
            await wait_received(topic, before)
            assert await tree.tick_exactly_once() is S
            assert tree.root_blackboard["planner"] == "Good"
    assert topic.reader.dropped_invalid == 6
    assert sum("planner_selector" in r.getMessage() for r in caplog.records) == 1


async def test_every_selector_names_its_ports_as_nav2(local_bus: Bus) -> None:
    for node, default, output in (
        ("SmootherSelector", "default_smoother", "selected_smoother"),
        ("ProgressCheckerSelector", "default_progress_checker", "selected_progress_checker"),
        ("PathHandlerSelector", "default_path_handler", "selected_path_handler"),
    ):
        tree = nav_tree(local_bus, f'<{node} {default}="d" {output}="{{out}}"/>')
        assert await tree.tick_exactly_once() is S
        assert tree.root_blackboard["out"] == "d"


async def test_an_unchanged_choice_is_not_rewritten_but_an_overwrite_is_restored(
    local_bus: Bus,
) -> None:
    tree = nav_tree(local_bus, PLANNER)
    assert await tree.tick_exactly_once() is S
    entry = tree.root_blackboard.entry("planner")
    assert entry is not None
    written = entry.sequence_id
    for _ in range(3):
        assert await tree.tick_exactly_once() is S
    assert entry.sequence_id == written  # same choice: no write, no watcher woken
    tree.root_blackboard["planner"] = "SomethingElse"
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["planner"] == "GridBased"
    await deliver(local_bus, "planner_selector", String(data="SmacHybrid"))
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["planner"] == "SmacHybrid"


async def test_a_default_bound_to_the_blackboard_is_read_on_every_tick(local_bus: Bus) -> None:
    xml = '<PlannerSelector default_planner="{fallback}" selected_planner="{planner}"/>'
    tree = nav_tree(local_bus, xml)
    tree.root_blackboard["fallback"] = "GridBased"
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["planner"] == "GridBased"
    tree.root_blackboard["fallback"] = "ThetaStar"
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["planner"] == "ThetaStar"
