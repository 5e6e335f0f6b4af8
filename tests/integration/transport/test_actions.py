"""The action protocol between two sessions via a real router."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest
import zenoh

from aiobt.core.clock import ManualClock, SystemClock
from aiobt.msgs import (
    ComputePathToPose,
    FollowPath,
    GoalState,
    GoalStatus,
    Path,
    PoseStamped,
    Wait,
    decode,
)
from aiobt.transport import (
    ActionServer,
    Bus,
    BusSettings,
    Execute,
    GoalHandle,
    GoalRejected,
    ServerUnavailable,
    open_bus,
)

pytestmark = pytest.mark.integration
WaitHandle = GoalHandle[Wait.Goal, Wait.Result, Wait.Feedback]
PlanHandle = GoalHandle[
    ComputePathToPose.Goal, ComputePathToPose.Result, ComputePathToPose.Feedback
]


def serve_wait(bus: Bus, **kwargs: object) -> list[str]:
    """A wait server on ``bus``; returns a log of what happened to its executions."""
    events: list[str] = []
    bus.action_server("wait", Wait, serve_wait_execute(events), **kwargs)  # type: ignore[arg-type]
    return events


def serve_wait_execute(events: list[str]) -> Execute[Wait.Goal, Wait.Result, Wait.Feedback]:
    """A wait execute logging its start and end into ``events``."""

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        events.append(f"start {handle.goal_id}")
        try:
            for step in range(round(goal.time / 0.02)):
                handle.publish_feedback(Wait.Feedback(time_left=goal.time - 0.02 * step))
                await asyncio.sleep(0.02)
            return Wait.Result(total_elapsed_time=goal.time)
        finally:
            events.append(f"end {handle.goal_id}")

    return execute


async def test_goal_with_feedback_and_result(bus: Bus, client_bus: Bus) -> None:
    serve_wait(bus)
    client = client_bus.action_client("wait", Wait)
    goal = await client.send_goal(Wait.Goal(time=0.2), server_timeout=5.0)
    feedback = [fb.time_left async for fb in goal.feedback()]
    result = await goal.result(timeout=5.0)
    assert goal.status is GoalState.SUCCEEDED
    assert result.error_code == 0
    assert result.total_elapsed_time == pytest.approx(0.2)
    assert len(feedback) >= 5
    assert feedback == sorted(feedback, reverse=True)
    state, fetched = await client.fetch_result(goal.goal_id)
    assert (state, fetched) == (GoalState.SUCCEEDED, result)


async def test_error_code_result_is_aborted(bus: Bus, client_bus: Bus) -> None:
    async def plan(goal: ComputePathToPose.Goal, handle: PlanHandle) -> ComputePathToPose.Result:
        code = ComputePathToPose.ErrorCode.NO_VALID_PATH
        return ComputePathToPose.Result(error_code=code, error_msg="no path to goal")

    bus.action_server("compute_path_to_pose", ComputePathToPose, plan)
    client = client_bus.action_client("compute_path_to_pose", ComputePathToPose)
    goal = await client.send_goal(
        ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(1, 2)), server_timeout=5.0
    )
    result = await goal.result(timeout=5.0)
    assert (goal.status, result.error_code, result.error_msg) == (
        GoalState.ABORTED,
        208,
        "no path to goal",
    )


async def test_crash_in_execute_is_unknown_error(bus: Bus, client_bus: Bus) -> None:
    async def plan(goal: ComputePathToPose.Goal, handle: PlanHandle) -> ComputePathToPose.Result:
        raise ZeroDivisionError("bad costmap")

    bus.action_server("compute_path_to_pose", ComputePathToPose, plan)
    client = client_bus.action_client("compute_path_to_pose", ComputePathToPose)
    goal = await client.send_goal(
        ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(1, 2)), server_timeout=5.0
    )
    result = await goal.result(timeout=5.0)
    assert goal.status is GoalState.ABORTED
    assert result.error_code == ComputePathToPose.ErrorCode.UNKNOWN
    assert "ZeroDivisionError: bad costmap" in result.error_msg


async def test_rejection_with_a_reason(bus: Bus, client_bus: Bus) -> None:
    serve_wait(bus, accept=lambda goal: "too long" if goal.time > 10 else None)
    client = client_bus.action_client("wait", Wait)
    with pytest.raises(GoalRejected, match="too long") as caught:
        await client.send_goal(Wait.Goal(time=60), server_timeout=5.0)
    assert caught.value.reason == "too long"
    accepted = await client.send_goal(Wait.Goal(time=0.0), server_timeout=5.0)
    await accepted.result(timeout=5.0)
    assert accepted.status is GoalState.SUCCEEDED


async def test_malformed_goal_is_rejected_naming_the_field(bus: Bus, client_bus: Bus) -> None:
    serve_wait(bus)
    client = client_bus.action_client("wait", Wait)
    with pytest.raises(GoalRejected, match=r"bad goal: .*'time'"):
        await client.send_goal(Wait.Goal.model_construct(time=-1.0), server_timeout=5.0)


async def test_cancel_one_goal(bus: Bus, client_bus: Bus) -> None:
    events = serve_wait(bus)
    client = client_bus.action_client("wait", Wait)
    goal = await client.send_goal(Wait.Goal(time=30.0), server_timeout=5.0)
    async for _ in goal.feedback():
        break
    result = await goal.cancel(timeout=5.0)
    assert goal.status is GoalState.CANCELED
    assert result is not None
    assert result.error_code == 0
    assert events == [f"start {goal.goal_id}", f"end {goal.goal_id}"]


async def test_cancel_all_goals(bus: Bus, client_bus: Bus) -> None:
    serve_wait(bus)
    client = client_bus.action_client("wait", Wait)
    goal = await client.send_goal(Wait.Goal(time=30.0), server_timeout=5.0)
    assert await client.cancel_all(timeout=5.0) == [goal.goal_id]
    await goal.result(timeout=5.0)
    assert goal.status is GoalState.CANCELED
    assert await client.cancel_all(timeout=5.0) == []


async def test_new_goal_aborts_the_running_one(bus: Bus, client_bus: Bus) -> None:
    events = serve_wait(bus)
    client = client_bus.action_client("wait", Wait)
    first = await client.send_goal(Wait.Goal(time=30.0), server_timeout=5.0)
    second = await client.send_goal(Wait.Goal(time=0.1), server_timeout=5.0)
    first_result = await first.result(timeout=5.0)
    await second.result(timeout=5.0)
    assert first.status is GoalState.ABORTED
    assert first_result.error_msg == f"preempted by goal {second.goal_id}"
    assert second.status is GoalState.SUCCEEDED
    # the first execution was cleaned up before the second started
    assert events == [
        f"start {first.goal_id}",
        f"end {first.goal_id}",
        f"start {second.goal_id}",
        f"end {second.goal_id}",
    ]


async def test_replace_policy_hands_the_new_goal_to_the_running_execute(
    bus: Bus, client_bus: Bus
) -> None:
    starts: list[str] = []
    FollowHandle = GoalHandle[FollowPath.Goal, FollowPath.Result, FollowPath.Feedback]

    async def follow(goal: FollowPath.Goal, handle: FollowHandle) -> FollowPath.Result:
        starts.append(goal.controller_id)
        path = goal.path
        while path.header.frame_id != "done":
            handle.publish_feedback(FollowPath.Feedback(distance_to_goal=len(path.poses)))
            if (newer := handle.take_new_goal()) is not None:
                path = newer.path
            await asyncio.sleep(0.01)
        return FollowPath.Result(error_msg=f"followed {len(path.poses)} poses")

    bus.action_server("follow_path", FollowPath, follow, preemption="replace")
    client = client_bus.action_client("follow_path", FollowPath)
    first = await client.send_goal(
        FollowPath.Goal(path=Path(), controller_id="A"), server_timeout=5.0
    )
    async for _ in first.feedback():
        break
    done_path = Path(poses=[PoseStamped.from_xy_yaw(1, 1)] * 3)
    done_path.header.frame_id = "done"
    second = await client.send_goal(
        FollowPath.Goal(path=done_path, controller_id="B"), server_timeout=5.0
    )
    second_result = await second.result(timeout=5.0)
    first_result = await first.result(timeout=5.0)
    assert second.status is GoalState.SUCCEEDED
    assert second_result.error_msg == "followed 3 poses"
    assert first.status is GoalState.ABORTED
    assert first_result.error_msg == f"preempted by goal {second.goal_id}"
    assert starts == ["A"]  # one execution throughout: no stop between the paths


async def test_server_timeout_bounds_acceptance(client_bus: Bus) -> None:
    client = client_bus.action_client("nobody", Wait)
    loop = asyncio.get_running_loop()
    start = loop.time()
    with pytest.raises(ServerUnavailable, match=r"within 0\.3 s"):
        await client.send_goal(Wait.Goal(time=1.0), server_timeout=0.3)
    assert 0.25 < loop.time() - start < 1.0


async def test_first_goal_is_never_lost(bus_settings: BusSettings, client_bus: Bus) -> None:
    client = client_bus.action_client("wait", Wait)
    for _ in range(5):
        sending = asyncio.create_task(client.send_goal(Wait.Goal(time=0.0), server_timeout=5.0))
        async with open_bus(bus_settings) as server_bus:  # the server comes up after the send
            serve_wait(server_bus)
            goal = await sending
            await goal.result(timeout=5.0)
            assert goal.status is GoalState.SUCCEEDED


async def test_status_is_published_for_observers(bus: Bus, client_bus: Bus) -> None:
    serve_wait(bus)
    statuses: list[GoalStatus] = []
    key = f"{bus.namespace}/action/wait/status/*"
    observer = client_bus.session.declare_subscriber(
        key, lambda s: statuses.append(decode(GoalStatus, s.payload.to_bytes()))
    )
    await asyncio.sleep(0.2)
    client = client_bus.action_client("wait", Wait)
    goal = await client.send_goal(Wait.Goal(time=0.05), server_timeout=5.0)
    await goal.result(timeout=5.0)
    await asyncio.sleep(0.2)
    observer.undeclare()  # type: ignore[no-untyped-call]
    assert [s.status for s in statuses] == [
        GoalState.ACCEPTED,
        GoalState.EXECUTING,
        GoalState.SUCCEEDED,
    ]
    assert {s.goal_id for s in statuses} == {goal.goal_id}


async def observe_statuses(
    bus: Bus, server: ActionServer[Any, Any, Any], seen: list[GoalStatus]
) -> zenoh.Subscriber[None]:
    """Subscribe to ``server``'s statuses (into ``seen``) and wait until it sees the watcher."""
    observer = bus.session.declare_subscriber(
        f"{server.keys.base}/status/*",
        lambda s: seen.append(decode(GoalStatus, s.payload.to_bytes())),
    )
    async with asyncio.timeout(5.0):
        while not server._observed("status"):  # noqa: ASYNC110 - set in Zenoh's thread
            await asyncio.sleep(0.01)
    return observer


async def wait_for_statuses(seen: list[GoalStatus], goal_id: str, count: int) -> list[GoalStatus]:
    async with asyncio.timeout(5.0):
        while len(mine := [s for s in seen if s.goal_id == goal_id]) < count:  # noqa: ASYNC110
            await asyncio.sleep(0.01)
    return mine


async def test_statuses_are_stamped_with_the_time_of_each_change(bus: Bus, client_bus: Bus) -> None:
    server = bus.action_server("wait", Wait, serve_wait_execute([]))
    seen: list[GoalStatus] = []
    observer = await observe_statuses(client_bus, server, seen)
    try:
        client = client_bus.action_client("wait", Wait)
        before = SystemClock().now()  # the server's default clock
        done = await client.send_goal(Wait.Goal(time=0.05), server_timeout=5.0)
        await done.result(timeout=5.0)
        canceled = await client.send_goal(Wait.Goal(time=30.0), server_timeout=5.0)
        async for _ in canceled.feedback():
            break
        await canceled.cancel(timeout=5.0)
        after = SystemClock().now()
        done_statuses = await wait_for_statuses(seen, done.goal_id, 3)
        canceled_statuses = await wait_for_statuses(seen, canceled.goal_id, 4)
    finally:
        observer.undeclare()  # type: ignore[no-untyped-call]
    assert [s.status for s in canceled_statuses] == [
        GoalState.ACCEPTED,
        GoalState.EXECUTING,
        GoalState.CANCELING,
        GoalState.CANCELED,
    ]
    for statuses in (done_statuses, canceled_statuses):
        stamps = [s.stamp for s in statuses]
        assert all(before <= stamp <= after for stamp in stamps), (before, stamps, after)
        assert stamps == sorted(stamps)
    assert done_statuses[-1].stamp <= canceled_statuses[0].stamp


async def test_statuses_are_stamped_by_the_injected_clock(bus: Bus, client_bus: Bus) -> None:
    clock = ManualClock(start=100.0)

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        clock.advance(goal.time)  # EXECUTING went out before execute began
        return Wait.Result(total_elapsed_time=goal.time)

    server = bus.action_server("wait", Wait, execute, clock=clock)  # closed with the bus
    seen: list[GoalStatus] = []
    observer = await observe_statuses(client_bus, server, seen)
    try:
        client = client_bus.action_client("wait", Wait)
        goal = await client.send_goal(Wait.Goal(time=2.5), server_timeout=5.0)
        await goal.result(timeout=5.0)
        statuses = await wait_for_statuses(seen, goal.goal_id, 3)
    finally:
        observer.undeclare()  # type: ignore[no-untyped-call]
    assert [(s.status, s.stamp) for s in statuses] == [
        (GoalState.ACCEPTED, 100.0),
        (GoalState.EXECUTING, 100.0),
        (GoalState.SUCCEEDED, 102.5),
    ]


async def test_feedback_and_result_are_published_for_observers(bus: Bus, client_bus: Bus) -> None:
    serve_wait(bus)
    seen: list[tuple[str, bytes, bytes]] = []  # (key, attachment, payload)

    def observe(sample: zenoh.Sample) -> None:
        tag = sample.attachment.to_bytes() if sample.attachment is not None else b""
        seen.append((str(sample.key_expr), tag, sample.payload.to_bytes()))

    base = f"{bus.namespace}/action/wait"
    observers = [
        client_bus.session.declare_subscriber(f"{base}/{kind}/*", observe)
        for kind in ("feedback", "result")
    ]
    await asyncio.sleep(0.2)
    client = client_bus.action_client("wait", Wait)
    goal = await client.send_goal(Wait.Goal(time=0.06), server_timeout=5.0)
    result = await goal.result(timeout=5.0)
    await asyncio.sleep(0.2)
    for observer in observers:
        observer.undeclare()  # type: ignore[no-untyped-call]
    feedback = [
        decode(Wait.Feedback, p) for k, _, p in seen if k == f"{base}/feedback/{goal.goal_id}"
    ]
    results = [(tag, p) for k, tag, p in seen if k == f"{base}/result/{goal.goal_id}"]
    assert len(feedback) >= 2
    assert feedback[0].time_left == pytest.approx(0.06)
    assert [tag for tag, _ in results] == [b"result:4"]
    assert decode(Wait.Result, results[0][1]) == result


async def test_oversized_goal_is_refused(bus_settings: BusSettings, client_bus: Bus) -> None:
    small = BusSettings(
        connect=bus_settings.connect, namespace=bus_settings.namespace, max_payload=2000
    )
    async with open_bus(small) as server_bus:

        async def follow(goal: FollowPath.Goal, handle: object) -> FollowPath.Result:
            return FollowPath.Result()

        server_bus.action_server("follow_path", FollowPath, follow)
        client = client_bus.action_client("follow_path", FollowPath)
        long_path = Path(poses=[PoseStamped.from_xy_yaw(i, 0) for i in range(50)])
        with pytest.raises(GoalRejected, match="exceeds the limit of 2000 bytes"):
            await client.send_goal(FollowPath.Goal(path=long_path), server_timeout=5.0)
        short = await client.send_goal(FollowPath.Goal(path=Path()), server_timeout=5.0)
        await short.result(timeout=5.0)
        assert short.status is GoalState.SUCCEEDED


def raw_goal(bus: Bus, server: str, goal_id: str, payload: bytes) -> list[tuple[str, bytes]]:
    """The goal stream as a plain Zenoh get sees it: (attachment or "ERR", payload) per reply."""
    replies = bus.session.get(
        f"{bus.namespace}/action/{server}/goal?id={goal_id}",
        payload=payload,
        consolidation=zenoh.ConsolidationMode.NONE,
        timeout=5.0,
    )
    out: list[tuple[str, bytes]] = []
    for reply in replies:
        if reply.ok is not None:
            tag = reply.ok.attachment.to_bytes() if reply.ok.attachment else b""
            out.append((tag.decode(), reply.ok.payload.to_bytes()))
        else:
            assert reply.err is not None
            out.append(("ERR", reply.err.payload.to_bytes()))
    return out


async def test_goal_stream_on_the_wire(bus: Bus, client_bus: Bus) -> None:
    serve_wait(bus)
    await client_bus.action_client("wait", Wait).wait_for_server(5.0)
    await asyncio.sleep(0.2)  # let the goal queryable's route settle
    quick = await asyncio.to_thread(raw_goal, client_bus, "wait", "quick1", b'{"time": 0.0}')
    assert [tag for tag, _ in quick] == ["result:4"]  # done at once: the result alone
    assert decode(Wait.Result, quick[0][1]).error_code == 0
    slow = await asyncio.to_thread(raw_goal, client_bus, "wait", "slow1", b'{"time": 0.06}')
    tags = [tag for tag, _ in slow]
    assert tags[0] == "accepted"
    assert set(tags[1:-1]) == {"feedback"}
    assert tags[-1] == "result:4"


async def test_garbage_goal_gets_an_error_reply_and_the_server_keeps_serving(
    bus: Bus, client_bus: Bus
) -> None:
    serve_wait(bus)
    client = client_bus.action_client("wait", Wait)
    await client.wait_for_server(5.0)
    await asyncio.sleep(0.2)
    garbage = await asyncio.to_thread(raw_goal, client_bus, "wait", "bad1", b"not json")
    assert len(garbage) == 1
    assert garbage[0][0] == "ERR"
    assert b"bad goal" in garbage[0][1]
    assert b"field '<payload>'" in garbage[0][1]
    no_id = await asyncio.to_thread(raw_goal, client_bus, "wait", "", b'{"time": 0.0}')
    assert no_id[0][0] == "ERR"
    assert b"goal id" in no_id[0][1]
    goal = await client.send_goal(Wait.Goal(time=0.0), server_timeout=5.0)
    await goal.result(timeout=5.0)
    assert goal.status is GoalState.SUCCEEDED


async def test_feedback_sent_with_the_acceptance_reaches_the_callback(
    bus: Bus, client_bus: Bus
) -> None:
    """A server whose first step is one feedback, then nothing until told (the route
    tracker's shape: it says more only once the robot moves, which the client does on
    that feedback). The feedback arrives with the acceptance: ``on_feedback`` must get it
    even so (it was set only after the acceptance was awaited, and missed it)."""
    release = asyncio.Event()

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        handle.publish_feedback(Wait.Feedback(time_left=goal.time))
        await release.wait()
        return Wait.Result(total_elapsed_time=goal.time)

    bus.action_server("wait", Wait, execute)
    client = client_bus.action_client("wait", Wait)
    for attempt in range(20):  # the two replies land in one batch often, not always
        heard: list[Wait.Feedback] = []
        goal = await client.send_goal(
            Wait.Goal(time=float(attempt)), server_timeout=5.0, on_feedback=heard.append
        )
        async with asyncio.timeout(5.0):
            async for _ in goal.feedback():  # the stream has it: so must the callback
                break
        assert [fb.time_left for fb in heard] == [float(attempt)], f"attempt {attempt}: {heard}"
        release.set()
        await goal.result(timeout=5.0)
        release.clear()
