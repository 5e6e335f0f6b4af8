"""The following server and the robot service as processes over a real router, the
simulation at a speed-up: a box walks a seeded loop in the office's open plan at
0.3 m/s, the robot's tracker sees it in the lidar, the server follows it for 60 s
of sim time, then the box hides for 3 s. Measured on the simulation's truth
(``{ns}/sim/pose``, ``{ns}/sim/target``), which the server never reads."""

from __future__ import annotations

import asyncio
import itertools
import math
import time
from collections.abc import Callable, Sequence

import pytest

from aiobt.msgs import GoalState, Header, Odometry, PoseStamped, TFMessage, Twist
from aiobt.msgs.follow_target import (
    OFFICE_LOOP_CENTRE,
    OFFICE_LOOP_RADII,
    HideTarget,
    StartTarget,
    TargetStarted,
)
from aiobt.msgs.localization import TransformStamped
from aiobt.msgs.remote_actions import FollowObject, FollowObjectError
from aiobt.msgs.sim import Ack
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_namespace
from aiobt_services.robot.target_path import seeded_loop

from ..services import TRUTH, common, up
from .truth import Watch

pytestmark = pytest.mark.integration
Spawn = Callable[[Sequence[str]], ServiceProcess]
SEED, SPEED, HOLD = 11, "4", 1.0
DESIRED, BAND = 1.0, 0.3
FOLLOWING = ["--search-by-rotating", "true", "--controller.v-linear-max", "0.5",
             "--controller.v-angular-max", "1.0"]  # fmt: skip
RETRY, CONTROLLING = 4, 2


async def start_stack(spawn: Spawn, bus: Bus, settings: BusSettings) -> None:
    path = seeded_loop(OFFICE_LOOP_CENTRE, OFFICE_LOOP_RADII, SEED)
    behind, ahead = path.pose_at(path.length - DESIRED), path.pose_at(0.0)
    yaw = math.atan2(ahead.y - behind.y, ahead.x - behind.x)
    start = [str(v) for v in (behind.x, behind.y, yaw)]
    robot = spawn(["-m", "aiobt_services.robot", "--speed", SPEED, "--start", *start, *TRUTH,
                   *common(settings)])  # fmt: skip
    following = spawn(["-m", "aiobt_services.following", "--sim-time", *FOLLOWING,
                       *common(settings)])  # fmt: skip
    await up(bus, "robot", robot)
    await up(bus, "following", following)


@pytest.mark.timeout(240)
async def test_follows_a_walking_box_and_finds_it_again_after_it_hides(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    await start_stack(spawn, bus, bus_settings)
    watch = Watch.on(bus)
    sim = sim_namespace(bus.namespace)  # the simulation's services
    started = await bus.call("follow_target/start", StartTarget(seed=SEED, hold=HOLD),
                             TargetStarted, namespace=sim)  # fmt: skip
    assert started.ok, started.message
    client = bus.action_client(FollowObject.name, FollowObject)
    goal = await client.send_goal(FollowObject.Goal(pose_topic="dynamic_pose", max_duration=80.0),
                                  server_timeout=10.0)  # fmt: skip

    async def feedback() -> None:
        async for f in goal.feedback():
            watch.states.append((watch.now, f.state))

    listening = asyncio.create_task(feedback())
    await watch.until(0.0, wall=30.0)
    t0 = watch.now + HOLD
    await watch.until(t0 + 60.0, wall=120.0)
    hidden = await bus.call("follow_target/hide", HideTarget(seconds=3.0), Ack, namespace=sim)
    assert hidden.ok, hidden.message
    t_hide = watch.now
    result = await goal.result(timeout=90.0)
    listening.cancel()

    assert result.error_code == 0, result
    run = watch.distances(t0, t0 + 60.0)
    # the truth at 10 Hz of sim time over the minute (best effort: a loaded machine drops some)
    assert len(run) > 300, len(run)
    assert run[-1][0] - run[0][0] > 58.0, (run[0], run[-1])
    inside = sum(abs(d - DESIRED) <= BAND for _, d in run) / len(run)
    print(
        f"within {BAND} m of {DESIRED} m: {inside:.1%} of {len(run)} samples; "
        f"closest {min(d for _, d in run):.2f} m"
    )
    assert inside >= 0.9
    assert not [b for b in watch.bumps if b.pressed], watch.bumps
    assert min(d for _, d in watch.distances(0.0, math.inf)) > 0.22 + 0.2 * math.sqrt(2)
    assert result.num_retries == 1  # lost once, by the hide
    retry = next(i for i, (t, s) in enumerate(watch.states) if s == RETRY and t >= t_hide)
    assert any(s == CONTROLLING for _, s in watch.states[retry:])  # searched, then followed
    found = next(t for t, s in watch.states[retry:] if s == CONTROLLING)
    farthest = max(d for _, d in watch.distances(t_hide, math.inf))
    print(
        f"hidden at {t_hide:.1f} s: searching from {watch.states[retry][0] - t_hide:.1f} s, "
        f"found again at {found - t_hide:.1f} s, at most {farthest:.2f} m away"
    )
    after = watch.distances(t_hide + 12.0, math.inf)
    assert after
    assert all(abs(d - DESIRED) <= BAND for _, d in after)  # re-acquired and caught up


async def test_an_object_never_seen_fails_naming_it_and_the_server_runs_on(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    server = spawn(["-m", "aiobt_services.following", "--detection-timeout", "0.3",
                    "--max-retries", "1", *common(bus_settings)])  # fmt: skip
    await up(bus, "following", server)
    client = bus.action_client(FollowObject.name, FollowObject)
    for goal, code, words in (
        ({"pose_topic": "people/alice"}, FollowObjectError.FAILED_TO_DETECT_OBJECT,
         f"'{bus_settings.namespace}/people/alice'"),
        ({"tracked_frame": "cart"}, FollowObjectError.FAILED_TO_DETECT_OBJECT,
         "tracked_frame 'cart': no transform to frame 'cart' on tf"),
        ({"pose_topic": "sim/target"}, FollowObjectError.FAILED_TO_DETECT_OBJECT, "truth"),
    ):  # fmt: skip
        handle = await client.send_goal(FollowObject.Goal.model_validate(goal), server_timeout=10)
        result = await handle.result(timeout=10.0)
        assert result.error_code == code, result
        assert words in result.error_msg
    assert server.popen.poll() is None


async def test_a_cancelled_goal_stops_the_robot(spawn: Spawn, bus: Bus, bus_settings: BusSettings):
    """A tracker and odometry from the test (the robot standing, the object 3 m ahead):
    the server drives toward it; cancelled, it answers CANCELED and sends a stop."""
    server = spawn(["-m", "aiobt_services.following", *common(bus_settings)])
    await up(bus, "following", server)
    commands: list[Twist] = []
    driving, stopped = asyncio.Event(), asyncio.Event()

    def on_command(cmd: Twist) -> None:
        commands.append(cmd)
        if cmd.linear.x > 0.1:
            driving.set()
        elif cmd == Twist():
            stopped.set()

    bus.subscribe("cmd_vel", Twist, on_command)
    odom, seen = bus.publisher("odom", Odometry), bus.publisher("dynamic_pose", PoseStamped)

    async def robot_and_tracker() -> None:
        for tick in itertools.count():
            now = time.monotonic()  # the server's wall clock (CLOCK_MONOTONIC, system-wide)
            odom.put(Odometry(header=Header(stamp=now, frame_id="odom")))
            if tick % 5 == 0:
                seen.put(PoseStamped.from_xy_yaw(3.0, 0.0, 0.0, "base_link", now))
            await asyncio.sleep(0.02)

    feeding = asyncio.create_task(robot_and_tracker())
    try:
        client = bus.action_client(FollowObject.name, FollowObject)
        goal = await client.send_goal(FollowObject.Goal(pose_topic="dynamic_pose"),
                                      server_timeout=10.0)  # fmt: skip
        async with asyncio.timeout(10.0):
            await driving.wait()
        stopped.clear()
        result = await goal.cancel(timeout=5.0)
    finally:
        feeding.cancel()
    assert result is not None
    assert goal.status is GoalState.CANCELED
    async with asyncio.timeout(5.0):
        await stopped.wait()
    assert commands[-1] == Twist()  # the stop is the last command


def tf_link(parent: str, child: str, x: float, stamp: float) -> TransformStamped:
    return TransformStamped.model_validate({"header": {"stamp": stamp, "frame_id": parent},
                                            "child_frame_id": child,
                                            "transform": {"translation": {"x": x}}})  # fmt: skip


async def test_a_tracked_frame_on_tf_is_followed(spawn: Spawn, bus: Bus, bus_settings: BusSettings):
    """A tracker publishing the object as a frame on ``{ns}/tf`` (``odom`` -> ``cart_base``
    -> ``cart``, 3 m ahead of the standing robot): the server drives toward it and
    shows its filtered pose in ``odom``."""
    server = spawn(["-m", "aiobt_services.following", *common(bus_settings)])
    await up(bus, "following", server)
    driving = asyncio.Event()
    bus.subscribe("cmd_vel", Twist, lambda cmd: driving.set() if cmd.linear.x > 0.1 else None)
    filtered = bus.subscribe("filtered_dynamic_pose", PoseStamped, queue_size=1)
    odom, tf = bus.publisher("odom", Odometry), bus.publisher("tf", TFMessage)

    async def robot_and_tracker() -> None:
        for tick in itertools.count():
            now = time.monotonic()  # the server's wall clock
            odom.put(Odometry(header=Header(stamp=now, frame_id="odom")))
            if tick % 5 == 0:
                tf.put(TFMessage(transforms=[tf_link("odom", "cart_base", 2.0, now),
                                             tf_link("cart_base", "cart", 1.0, now)]))  # fmt: skip
            await asyncio.sleep(0.02)

    feeding = asyncio.create_task(robot_and_tracker())
    try:
        client = bus.action_client(FollowObject.name, FollowObject)
        goal = await client.send_goal(FollowObject.Goal(tracked_frame="cart"), server_timeout=10.0)
        async with asyncio.timeout(10.0):
            await driving.wait()
        shown = await filtered.next(timeout=5.0)
        await goal.cancel(timeout=5.0)
    finally:
        feeding.cancel()
    assert shown.header.frame_id == "odom"
    assert shown.x == pytest.approx(3.0, abs=0.01)
    assert "Following frame: cart instead of pose" in server.output()
