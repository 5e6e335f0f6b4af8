"""Groot2Publisher beyond BT.CPP's behaviour: attaching to a running tree, breakpoints
that do not block the event loop, the heartbeat, bad requests, ports."""

from __future__ import annotations

import asyncio
import json
import socket
import struct
from collections.abc import Callable

import msgpack
import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.leaves import AsyncActionNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.hosts import is_loopback as _is_loopback
from aiobt.loggers import Groot2Publisher
from aiobt.loggers.groot2_monitor import Groot2Monitor
from aiobt.testing.stubs import tree_xml
from tests.groot2_client import Groot2Client, free_port_pair, status_pairs, transitions

pytestmark = pytest.mark.timeout(60)

BODY = """<Sequence name="seq">
  <Counted name="first"/>
  <Wait name="wait"/>
  <Counted name="last"/>
</Sequence>"""
WAIT_UID, LAST_UID = 3, 4


class Wait(AsyncActionNode):
    """RUNNING until its class-level event is set."""

    release: asyncio.Event
    cancelled = 0

    async def run(self) -> Status:
        try:
            await self.release.wait()
        except asyncio.CancelledError:
            Wait.cancelled += 1
            raise
        return Status.SUCCESS


def make_tree(ticks: list[str], clock: ManualClock | None = None) -> Tree:
    Wait.release = asyncio.Event()
    Wait.cancelled = 0
    factory = BehaviorTreeFactory()
    factory.register_simple_action("Counted", lambda node: ticks.append(node.name))
    factory.register_node_type(Wait)
    return factory.create_tree_from_text(tree_xml(BODY), clock=clock)


def hook(uid: int, mode: int, status: str = "SKIPPED", once: bool = False) -> dict[str, object]:
    return {"uid": uid, "mode": mode, "enabled": True, "once": once,
            "desired_status": status, "position": 0}  # fmt: skip


def header(kind: str) -> bytes:
    return struct.pack("<BBI", 2, ord(kind), 7)


async def wait_until(predicate: Callable[[], object], what: str) -> None:
    """Poll ``predicate`` for up to 10 s (the publisher exposes no event for these)."""
    try:
        async with asyncio.timeout(10):
            while not predicate():  # noqa: ASYNC110 - state of the publisher's own tasks
                await asyncio.sleep(0.01)
    except TimeoutError:
        pytest.fail(f"timed out waiting until {what}")


async def test_attaching_to_a_running_tree_shows_running_nodes_at_once() -> None:
    tree = make_tree([])
    assert await tree.tick_exactly_once() is Status.RUNNING
    port = free_port_pair()
    client = Groot2Client(port)
    try:
        async with Groot2Publisher(tree, port):
            statuses = dict(status_pairs((await client.request("S"))[1]))
    finally:
        client.close()
        await tree.halt_tree("test over")
    assert statuses == {1: 1, 2: 2, WAIT_UID: 1, LAST_UID: 0}  # BT.CPP would say all 0


async def test_a_breakpoint_pauses_the_tree_not_the_event_loop() -> None:
    ticks: list[str] = []
    tree = make_tree(ticks)
    port = free_port_pair()
    client = Groot2Client(port)
    loop_turns = 0

    async def spin() -> None:
        nonlocal loop_turns
        while True:
            loop_turns += 1
            await asyncio.sleep(0)

    spinner = asyncio.ensure_future(spin())
    try:
        async with Groot2Publisher(tree, port) as publisher:
            await client.subscribed()
            await client.hook_json("I", hook(LAST_UID, 0))
            running = asyncio.ensure_future(tree.tick_while_running(0.01))
            Wait.release.set()
            notified = await client.notification()
            assert notified[0][:2] == b"\x02N"
            assert notified[1] == str(LAST_UID).encode()
            await wait_until(lambda: tree.paused, "the tree pauses")
            assert tree.events[-1].reason.startswith("Groot2 breakpoint at MainTree/")
            turns, statuses = loop_turns, dict(status_pairs((await client.request("S"))[1]))
            await wait_until(lambda: loop_turns > turns + 100, "the loop goes on")
            assert ticks == ["first"], "the node at the breakpoint was not ticked"
            assert statuses[LAST_UID] == 0, "it still shows its status before the breakpoint"
            assert publisher.monitor.hooks.holding
            assert not running.done()
            await client.hook_json("U", {**hook(LAST_UID, 0), "remove_when_done": True})
            assert await asyncio.wait_for(running, 10) is Status.SUCCESS
            assert ticks == ["first", "last"], "SKIPPED at the unlock lets the node tick"
            assert (await client.request("D"))[1] == b"[]"
    finally:
        spinner.cancel()
        client.close()


async def test_a_replace_hook_decides_a_running_node_without_ticking_it() -> None:
    ticks: list[str] = []
    tree = make_tree(ticks)
    port = free_port_pair()
    client = Groot2Client(port)
    try:
        async with Groot2Publisher(tree, port):
            assert await tree.tick_exactly_once() is Status.RUNNING
            await client.hook_json("I", [hook(WAIT_UID, 1, "FAILURE", once=True)])
            assert await tree.tick_exactly_once() is Status.FAILURE
            assert ticks == ["first"]
            assert Wait.cancelled == 1, "the replaced async leaf was halted"
            statuses = dict(status_pairs((await client.request("S"))[1]))
            assert statuses[WAIT_UID] == 13, "idle, coming from FAILURE"
    finally:
        client.close()
        await tree.halt_tree("test over")


async def test_groot2_going_silent_frees_a_held_breakpoint() -> None:
    ticks: list[str] = []
    tree = make_tree(ticks)
    port = free_port_pair()
    client = Groot2Client(port)
    try:
        async with Groot2Publisher(tree, port, max_heartbeat_delay=0.3) as publisher:
            await client.hook_json("I", hook(LAST_UID, 0))
            Wait.release.set()
            running = asyncio.ensure_future(tree.tick_while_running(0.01))
            await wait_until(lambda: publisher.monitor.hooks.holding, "the breakpoint holds")
            # no request from Groot2 for 0.3 s: every hook is disabled, the tree goes on
            assert await asyncio.wait_for(running, 10) is Status.SUCCESS
            assert ticks == ["first", "last"]
            assert json.loads((await client.request("D"))[1])[0]["enabled"] is False
            hooks = publisher.monitor.hooks
            await wait_until(lambda: hooks.dump()[0].enabled, "enabled again once Groot2 is back")
    finally:
        client.close()


async def test_stopping_the_publisher_frees_a_held_breakpoint() -> None:
    tree = make_tree([])
    port = free_port_pair()
    client = Groot2Client(port)
    publisher = Groot2Publisher(tree, port)
    await publisher.start()
    try:
        await client.hook_json("I", hook(LAST_UID, 0))
        Wait.release.set()
        running = asyncio.ensure_future(tree.tick_while_running(0.01))
        await wait_until(lambda: publisher.monitor.hooks.holding, "the breakpoint holds")
    finally:
        await publisher.stop()
        client.close()
    assert await asyncio.wait_for(running, 10) is Status.SUCCESS
    assert tree.root.config.context.listeners == [], "the monitor detached"


async def test_recording_stamps_transitions_in_tree_clock_time() -> None:
    clock = ManualClock()
    tree = make_tree([], clock)
    monitor = Groot2Monitor(tree, lambda uid: None)
    try:
        monitor.handle([header("r"), b"start"])
        clock.advance(1.5)
        await tree.tick_exactly_once()
        recorded = transitions(monitor.handle([header("t")])[1])
        assert monitor.handle([header("t")])[1] == b"", "reading clears the buffer"
    finally:
        monitor.close()
        await tree.halt_tree("test over")
    assert recorded[0] == (1_500_000, 1, 1)
    assert [(uid, status) for _, uid, status in recorded][1:3] == [(2, 2), (WAIT_UID, 1)]


async def test_blackboard_values_without_a_plain_form_are_nil() -> None:
    tree = make_tree([])
    tree.root_blackboard.set("pose", [1.0, 2.5])
    tree.root_blackboard.set("status", Status.RUNNING)
    tree.root_blackboard.set("thing", object())
    monitor = Groot2Monitor(tree, lambda uid: None)
    try:
        dump = msgpack.unpackb(monitor.handle([header("B"), b"MainTree"])[1])
    finally:
        monitor.close()
    assert dump == {"MainTree": {"pose": [1.0, 2.5], "status": "RUNNING", "thing": None}}


@pytest.mark.parametrize(
    ("kind", "payload", "message"),
    [
        ("I", b"{not json", "hook insert: the payload is not JSON"),
        ("I", json.dumps({"uid": 3}).encode(), "hook insert: missing key [mode]"),
        ("I", json.dumps({**hook(3, 0), "uid": "3"}).encode(), "key [uid] has the wrong type"),
        ("I", json.dumps({**hook(3, 0), "mode": 7}).encode(), "mode 7 is neither"),
        ("I", json.dumps(hook(3, 0, "MAYBE")).encode(), "desired_status 'MAYBE'"),
        ("I", json.dumps(hook(99, 0)).encode(), "Node ID not found"),
        ("I", b"[1]", "expected a JSON object"),
        ("R", json.dumps({"uid": 3}).encode(), "hook remove: missing key [position]"),
        ("U", json.dumps({"uid": 3, "position": 0}).encode(), "missing key [desired_status]"),
        ("r", b"pause", "expected 'start' or 'stop'"),
    ],
)
async def test_bad_requests_get_an_error_naming_what_is_wrong(
    kind: str, payload: bytes, message: str
) -> None:
    monitor = Groot2Monitor(make_tree([]), lambda uid: None)
    try:
        reply = monitor.handle([header(kind), payload])
    finally:
        monitor.close()
    assert reply[0] == b"error"
    assert message in reply[1].decode()


async def test_a_request_without_frames_or_of_type_n_is_refused() -> None:
    monitor = Groot2Monitor(make_tree([]), lambda uid: None)
    try:
        assert monitor.handle([]) == [b"error", b"wrong request header"]
        assert monitor.handle([header("N")]) == [b"error", b"Request not recognized"]
    finally:
        monitor.close()


async def test_a_taken_port_is_an_error_naming_it() -> None:
    port = free_port_pair()
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", port + 1))
        taken.listen()
        with pytest.raises(OSError, match=f"port {port + 1}"):
            await Groot2Publisher(make_tree([]), port).start()


def test_bad_ports_and_delays_are_refused() -> None:
    with pytest.raises(ValueError, match="port 65535"):
        Groot2Publisher(make_tree([]), 65535)
    with pytest.raises(ValueError, match="max_heartbeat_delay"):
        Groot2Publisher(make_tree([]), 1667, max_heartbeat_delay=0)


def test_only_loopback_addresses_bind_without_a_warning() -> None:
    assert _is_loopback("127.0.0.1")
    assert _is_loopback("::1")
    assert _is_loopback("localhost")
    assert not _is_loopback("0.0.0.0")
    assert not _is_loopback("192.168.1.10")


async def test_a_large_tree_is_served_whole() -> None:
    leaves = "".join(f'<AlwaysSuccess name="a{i}"/>' for i in range(3000))
    tree = BehaviorTreeFactory().create_tree_from_text(tree_xml(f"<Sequence>{leaves}</Sequence>"))
    monitor = Groot2Monitor(tree, lambda uid: None)
    try:
        await tree.tick_exactly_once()
        statuses = status_pairs(monitor.handle([header("S")])[1])
        xml = monitor.handle([header("T")])[1]
    finally:
        monitor.close()
    assert len(statuses) == 3001
    assert statuses[-1] == (3001, 12)
    assert b'_uid="3001"' in xml


def test_a_uid_beyond_16_bits_is_refused_naming_the_node() -> None:
    tree = make_tree([])
    tree.find("last").config.uid = 70_000
    with pytest.raises(ValueError, match=r"Seq.*last.* has uid 70000; .* 1\.\.65535"):
        Groot2Monitor(tree, lambda uid: None)


async def test_one_publisher_shows_each_tree_attached_in_turn() -> None:
    """As the navigator uses it: bound once, no tree at first, then a tree per run."""
    first, second = make_tree([]), make_tree([])
    port = free_port_pair()
    client = Groot2Client(port)
    try:
        async with Groot2Publisher(None, port) as publisher:
            assert await client.request("T") == [b"error", b"no tree is running yet"]
            publisher.attach(first)
            shown_first = await client.request("T")
            assert await second.tick_exactly_once() is Status.RUNNING
            publisher.attach(second)
            shown_second = await client.request("T")
            statuses = dict(status_pairs((await client.request("S"))[1]))
    finally:
        client.close()
        await second.halt_tree("test over")
    assert b"<Wait" in shown_first[1]
    assert shown_first[1] == shown_second[1]
    assert shown_first[0][6:] != shown_second[0][6:]  # a new tree UUID: Groot2 reloads
    assert statuses == {1: 1, 2: 2, WAIT_UID: 1, LAST_UID: 0}  # the second, running tree


async def test_attaching_before_start_is_refused() -> None:
    with pytest.raises(RuntimeError, match="not started"):
        Groot2Publisher(None, free_port_pair()).attach(make_tree([]))
