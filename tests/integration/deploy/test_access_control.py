"""Mutual TLS and access control in one real router on loopback, a client per identity.

The router runs as the deployment runs it (`aiobt router --config router-robot.json5
--access-control deploy/access-control.json5`); each client presents the certificate
`aiobt certs` made for its name. A put that must not arrive is checked against a
control put sent right after it on the same session (goal_pose, which everyone may
put): once the controls arrive, the forbidden put would have too.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator
from pathlib import Path

import pytest

from aiobt.deploy.certs import CertPlan
from aiobt.msgs import Empty, Msg, OccupancyGrid, Odometry, PoseStamped, Twist
from aiobt.msgs.sim import ObstacleList
from aiobt.testing.bus import ServiceProcess, running_router
from aiobt.transport import (
    Bus,
    BusSettings,
    BusUnavailable,
    ServiceUnavailable,
    open_bus,
    open_session,
)
from aiobt.transport.endpoints import free_port
from aiobt.transport.keys import SIM_POSE, sim_namespace

from .conftest import ACCESS_CONTROL, make_certs

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]
CONTROLS = 5  # control puts that must arrive before a missing put counts as refused


def identity(certs: Path, name: str, endpoint: str, timeout: float = 10.0) -> BusSettings:
    return BusSettings(
        connect=(endpoint,), config_file=str(certs / f"{name}.json5"), connect_timeout=timeout
    )


@contextlib.asynccontextmanager
async def as_(certs: Path, name: str, endpoint: str) -> AsyncIterator[Bus]:
    async with open_bus(identity(certs, name, endpoint)) as bus:
        yield bus


async def put_reaches(receiver: Bus, sender: Bus, topic: str, message: Msg) -> bool:
    """Whether ``sender``'s puts on ``topic`` reach ``receiver``, puts alternating with
    control puts on goal_pose until CONTROLS of those arrived (10 s at most)."""
    arrived: list[Msg] = []
    controls: list[Msg] = []
    sub = receiver.subscribe(topic, type(message), callback=arrived.append)
    control_sub = receiver.subscribe("goal_pose", PoseStamped, callback=controls.append)
    pub = sender.publisher(topic, type(message), reliable=True)
    control = sender.publisher("goal_pose", PoseStamped, reliable=True)
    async with asyncio.timeout(10.0):
        while len(controls) < CONTROLS:
            pub.put(message)
            control.put(PoseStamped.from_xy_yaw(1.0, 2.0))
            await asyncio.sleep(0.05)
    for entity in (pub, control, sub, control_sub):
        entity.close()
    return bool(arrived)


@pytest.mark.parametrize("driver", ["controller", "behaviors", "collision_monitor", "teleop"])
async def test_the_drivers_may_put_cmd_vel(
    certs: Path, secure_router: tuple[ServiceProcess, str], driver: str
) -> None:
    _, endpoint = secure_router
    async with as_(certs, "robot", endpoint) as robot, as_(certs, driver, endpoint) as sender:
        assert await put_reaches(robot, sender, "cmd_vel", Twist.planar(0.3, 0.0))


@pytest.mark.parametrize("viewer", ["web", "laptop", "planner", "navigator"])
async def test_viewers_and_base_services_may_not_put_cmd_vel_but_may_put_goals(
    certs: Path, secure_router: tuple[ServiceProcess, str], viewer: str
) -> None:
    router, endpoint = secure_router
    async with as_(certs, "robot", endpoint) as robot, as_(certs, viewer, endpoint) as sender:
        assert not await put_reaches(robot, sender, "cmd_vel", Twist.planar(0.3, 0.0))
    line = f"denied Put from {viewer} (session "
    assert router.wait_for_output(line, 10.0), router.output()
    assert "on robot/cmd_vel" in router.output()


async def test_only_the_robot_publishes_its_sensors(
    certs: Path, secure_router: tuple[ServiceProcess, str]
) -> None:
    _, endpoint = secure_router
    async with (
        as_(certs, "web", endpoint) as web,
        as_(certs, "robot", endpoint) as robot,
        as_(certs, "controller", endpoint) as controller,
    ):
        assert await put_reaches(web, robot, "odom", Odometry())
        assert not await put_reaches(web, controller, "odom", Odometry())


@pytest.mark.parametrize(
    ("sender", "topic", "arrives"),
    [("velocity_smoother", "cmd_vel_smoothed", True), ("controller", "cmd_vel_nav", True),
     ("web", "cmd_vel_smoothed", False), ("laptop", "cmd_vel_nav", False),
     ("localization", "cmd_vel", False)],
)  # fmt: skip
async def test_the_safety_chain_s_commands_are_the_drivers_only(
    certs: Path, secure_router: tuple[ServiceProcess, str], sender: str, topic: str, arrives: bool
) -> None:
    """With the chain on, the commands go cmd_vel_nav -> cmd_vel_smoothed -> cmd_vel: a
    put on either of the first two drives the base as surely as one on cmd_vel."""
    _, endpoint = secure_router
    async with as_(certs, "robot", endpoint) as robot, as_(certs, sender, endpoint) as source:
        assert await put_reaches(robot, source, topic, Twist.planar(0.3, 0.0)) is arrives


@pytest.mark.parametrize(
    ("sender", "arrives"),
    [("robot", True), ("localization", True), ("controller", False), ("laptop", False)],
)
async def test_the_pose_is_the_robot_s_or_localization_s(
    certs: Path, secure_router: tuple[ServiceProcess, str], sender: str, arrives: bool
) -> None:
    _, endpoint = secure_router
    async with as_(certs, "web", endpoint) as web, as_(certs, sender, endpoint) as source:
        pose = PoseStamped.from_xy_yaw(1.0, 2.0)
        assert await put_reaches(web, source, "pose", pose) is arrives


@pytest.mark.parametrize(
    ("who", "may"),
    [("laptop", True), ("web", True), ("localization", False), ("controller", False),
     ("following", False), ("planner", False), ("navigator", False)],
)  # fmt: skip
async def test_the_simulation_s_namespace_is_not_the_navigation_services_(
    certs: Path, secure_router: tuple[ServiceProcess, str], who: str, may: bool
) -> None:
    """The truth reaches the laptop and a viewer, and they may call the simulation's
    services; a navigation service may do neither, nor get them through a wider
    subscription or query (``{ns}/**``)."""
    _, endpoint = secure_router
    async with as_(certs, "robot", endpoint) as robot, as_(certs, who, endpoint) as other:
        sim = sim_namespace(robot.namespace)
        robot.serve("obstacles/list", Empty, ObstacleList, lambda _: ObstacleList(), namespace=sim)
        wide: list[str] = []
        other.session.declare_subscriber(
            f"{robot.namespace}/**", lambda s: wide.append(str(s.key_expr))
        )
        truth = PoseStamped.from_xy_yaw(1.0, 2.0)
        assert await put_reaches(other, robot, SIM_POSE, truth) is may
        assert any(key.startswith(f"{sim}/") for key in wide) is may, wide
        if may:
            await other.call("obstacles/list", Empty(), ObstacleList, timeout=5.0, namespace=sim)
        else:
            with pytest.raises(ServiceUnavailable):
                await other.call("obstacles/list", Empty(), ObstacleList, 2.0, namespace=sim)
        replies = await asyncio.to_thread(
            lambda: [
                str(r.ok.key_expr)
                for r in other.session.get(f"{robot.namespace}/**", timeout=2.0)
                if r.ok
            ]
        )
        assert any(key.startswith(f"{sim}/") for key in replies) is may, replies


async def test_a_certificate_named_nowhere_may_do_nothing(
    tmp_path: Path, certs: Path, secure_router: tuple[ServiceProcess, str]
) -> None:
    """Signed by the deployment's CA but not named in the rules: the session opens,
    and nothing it sends gets through (the default permission is deny)."""
    router, endpoint = secure_router
    extra = tmp_path / "extra"
    extra.mkdir()
    for name in ("ca.pem", "ca-key.pem"):
        (extra / name).write_bytes((certs / name).read_bytes())
    make_certs(extra, CertPlan(services=("intruder",), hosts={}), renew=True)
    async with as_(certs, "robot", endpoint) as robot, as_(extra, "intruder", endpoint) as bad:
        control = bad.publisher("goal_pose", PoseStamped, reliable=True)
        goals: list[PoseStamped] = []
        robot.subscribe("goal_pose", PoseStamped, callback=goals.append)
        await asyncio.sleep(0)
        assert router.wait_for_output("certificate 'intruder'", 10.0), router.output()
        for _ in range(20):
            control.put(PoseStamped.from_xy_yaw(9.0, 9.0))
        async with as_(certs, "web", endpoint) as web:  # a good one, after: it arrives
            assert await put_reaches(robot, web, "goal_pose", PoseStamped.from_xy_yaw(3.0, 4.0))
        assert goals, "not even the good identity's goals arrived"
        assert all(goal.pose.position.x != 9.0 for goal in goals), goals
    assert "is named nowhere in the access-control file" in router.output()


async def test_another_ca_is_refused_at_connect_with_a_clear_message(
    certs: Path, other_ca_certs: Path, secure_router: tuple[ServiceProcess, str]
) -> None:
    router, endpoint = secure_router
    with pytest.raises(BusUnavailable) as trusts_other:
        await open_session(identity(other_ca_certs, "web", endpoint, timeout=0.5))
    assert f"the router at {endpoint} has a certificate that" in str(trusts_other.value)
    assert "this session trusts another CA than the router's" in str(trusts_other.value)
    assert router.wait_for_output("a TLS client refused this router's certificate", 10.0)

    # our CA trusted, but the certificate presented is another CA's: the router refuses
    mixed = other_ca_certs / "mixed.json5"
    mixed.write_text(
        (other_ca_certs / "web.json5")
        .read_text()
        .replace(str(other_ca_certs / "ca.pem"), str(certs / "ca.pem"))
    )
    settings = BusSettings(connect=(endpoint,), config_file=str(mixed), connect_timeout=0.5)
    with pytest.raises(BusUnavailable) as refused:
        await open_session(settings)
    assert f"the router at {endpoint} refused this session's certificate" in str(refused.value)
    assert router.wait_for_output(
        "refused a TLS session: its certificate is not signed by this deployment's CA", 10.0
    ), router.output()


async def test_a_latched_map_reaches_a_late_viewer_and_only_the_robot_s_counts(
    certs: Path, secure_router: tuple[ServiceProcess, str]
) -> None:
    """The history of a latched topic lives under ``@adv`` keys, which no wildcard
    matches: the rules name them, or a late subscriber never gets the map."""
    _, endpoint = secure_router
    grid = OccupancyGrid.model_validate(
        {"info": {"resolution": 0.1, "width": 2, "height": 1}, "data": [0, 100]}
    )
    async with as_(certs, "robot", endpoint) as robot, as_(certs, "planner", endpoint) as fake:
        robot.latched_publisher("map", OccupancyGrid).put(grid)
        fake_grid = OccupancyGrid.model_validate(
            {"info": {"resolution": 0.1, "width": 3, "height": 1}, "data": [1, 1, 1]}
        )
        fake.latched_publisher("map", OccupancyGrid).put(fake_grid)
        async with as_(certs, "web", endpoint) as web:  # joins after the puts
            sub = web.subscribe("map", OccupancyGrid, latched=True, queue_size=10)
            first = await sub.next(10.0)
            assert first.info.width == 2  # the robot's
            with pytest.raises(TimeoutError):
                await sub.next(1.0)  # the planner's map never comes


async def test_without_the_denial_log_the_rules_still_hold(certs: Path) -> None:
    args = ["--config", str(certs / "router-robot.json5"), "--access-control",
            str(ACCESS_CONTROL), "--no-denial-log"]  # fmt: skip
    with running_router(f"tls/127.0.0.1:{free_port()}", args) as (router, endpoint):
        assert router.wait_for_output("listening on", 10.0), router.output()
        async with as_(certs, "robot", endpoint) as robot, as_(certs, "web", endpoint) as web:
            assert not await put_reaches(robot, web, "cmd_vel", Twist.planar(0.3, 0.0))
        assert "denied" not in router.output()
