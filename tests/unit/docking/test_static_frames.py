"""``{ns}/tf_static`` as Nav2's tf2 buffer reads it: a detection given in a camera's
optical frame (z ahead, x right, y down) reaches ``base_link`` through the robot's static
links, in 3D; a dock given in a frame of its own reaches ``map``; a missing link is named.
On the simulation, DockRobot docks from detections given in the camera's optical frame."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.geometry.quaternion import quat_from_rpy, quat_from_yaw, quat_mul
from aiobt.geometry.static_frames import Rigid3D, StaticFrames
from aiobt.msgs import Odometry, PoseStamped, TFMessage
from aiobt.msgs.geometry import Header, Pose, Quaternion, Vector3
from aiobt.msgs.localization import Transform, TransformStamped
from aiobt.msgs.remote_actions import DockRobot
from aiobt_services.docking.frames import RobotFrames

from .simbase import Feedback, SimBase, docked_error, docking_server, office_sim

OPTICAL = quat_from_rpy(-math.pi / 2, 0.0, -math.pi / 2)  # camera_link -> its optical frame
CAMERA = Rigid3D(np.array([0.1, 0.0, 0.3]), quat_from_yaw(0.0))  # on base_link


def link(parent: str, child: str, at: Rigid3D) -> TransformStamped:
    x, y, z, w = (float(c) for c in at.q)
    return TransformStamped(
        header=Header(frame_id=parent), child_frame_id=child,
        transform=Transform(translation=Vector3(x=float(at.t[0]), y=float(at.t[1]),
                                                z=float(at.t[2])),
                            rotation=Quaternion(x=x, y=y, z=z, w=w)),
    )  # fmt: skip


def camera_links() -> StaticFrames:
    statics = StaticFrames()
    statics.add(TFMessage(transforms=[link("base_link", "camera_link", CAMERA)]))
    statics.add(TFMessage(transforms=[  # another publisher, its own links
        link("camera_link", "camera_optical", Rigid3D(np.zeros(3), OPTICAL))]))  # fmt: skip
    return statics


def seen(x: float, y: float, z: float, frame: str = "camera_optical") -> StampedPose3D:
    return StampedPose3D(x, y, z, np.array([0.0, 0.0, 0.0, 1.0]), 1.0, frame)


def base_link_or_odom(frame: str) -> bool:
    return frame in ("base_link", "odom")


def test_a_detection_in_the_optical_frame_reaches_base_link_in_3d() -> None:
    statics = camera_links()
    ahead = statics.lift(seen(0.0, 0.0, 1.0), base_link_or_odom)  # 1 m along the optical z
    assert ahead.frame == "base_link"
    np.testing.assert_allclose((ahead.x, ahead.y, ahead.z), (1.1, 0.0, 0.3), atol=1e-12)
    right_down = statics.lift(seen(0.5, 0.2, 1.0), base_link_or_odom)  # right and below
    np.testing.assert_allclose((right_down.x, right_down.y, right_down.z), (1.1, -0.5, 0.1),
                               atol=1e-12)  # fmt: skip
    np.testing.assert_allclose(np.abs(right_down.q), np.abs(OPTICAL), atol=1e-12)
    assert right_down.stamp == 1.0
    same = seen(1.0, 0.0, 0.0, "odom")
    assert statics.lift(same, base_link_or_odom) is same


def test_a_missing_link_and_a_loop_are_named() -> None:
    statics = StaticFrames()
    statics.add(TFMessage(transforms=[link("camera_link", "camera_optical", Rigid3D.identity())]))
    with pytest.raises(LookupError, match="'camera_link' \\(a parent of 'camera_optical'\\)"):
        statics.lift(seen(0.0, 0.0, 1.0), base_link_or_odom)
    statics.add(TFMessage(transforms=[link("camera_optical", "camera_link", Rigid3D.identity())]))
    with pytest.raises(LookupError, match="a loop"):
        statics.up_to("camera_link", base_link_or_odom)


def test_the_inverse_undoes_a_link() -> None:
    at = Rigid3D(np.array([0.4, -0.2, 0.3]), quat_mul(quat_from_yaw(0.7), OPTICAL))
    back = at.compose(at.inverse())
    np.testing.assert_allclose(back.t, 0.0, atol=1e-12)
    np.testing.assert_allclose(np.abs(back.q), [0.0, 0.0, 0.0, 1.0], atol=1e-12)


def test_a_dock_in_a_frame_of_its_own_reaches_map_and_odom() -> None:
    statics = StaticFrames()
    bay = Rigid3D(np.array([10.0, 5.0, 0.0]), quat_from_yaw(math.pi / 2))
    statics.add(TFMessage(transforms=[link("map", "bay", bay)]))
    odom = Odometry(header=Header(stamp=1.0, frame_id="odom"),
                    pose=Pose.from_xy_yaw(1.0, 0.0, 0.0))  # fmt: skip
    pose = PoseStamped.from_xy_yaw(11.0, 5.0, 0.0, "map")  # map = odom + (10, 5)
    frames = RobotFrames(lambda: pose, lambda: [odom], statics)
    dock = frames.transform(Pose2D(1.0, 0.0, 0.0), "bay", "map")  # 1 m along the bay's x
    assert (dock.x, dock.y, dock.yaw) == pytest.approx((10.0, 6.0, math.pi / 2))
    in_odom = frames.transform(Pose2D(1.0, 0.0, 0.0), "bay", "odom")
    assert (in_odom.x, in_odom.y) == pytest.approx((0.0, 1.0))
    robot = frames.robot("bay")  # the robot at (11, 5) in map: 1 m along the bay's -y
    assert (robot.x, robot.y, robot.yaw) == pytest.approx((0.0, -1.0, -math.pi / 2))
    back = frames.transform(dock, "map", "bay")
    assert (back.x, back.y, back.yaw) == pytest.approx((1.0, 0.0, 0.0))


@pytest.mark.timeout(60)
async def test_docks_from_detections_in_the_cameras_optical_frame() -> None:
    statics = camera_links()
    _, optical_in_base = statics.up_to("camera_optical", lambda f: f == "base_link")
    to_optical = optical_in_base.inverse()
    with office_sim() as sim:
        base = SimBase(sim)
        in_base = base.detection

        def in_optical() -> StampedPose3D | None:  # what a camera's detector would give
            d = in_base()
            if d is None:
                return None
            p = to_optical.compose(Rigid3D(np.array([d.x, d.y, d.z]), d.q))
            x, y, z = (float(c) for c in p.t)
            return StampedPose3D(x, y, z, p.q, d.stamp, "camera_optical")

        base.detection = in_optical  # type: ignore[method-assign]
        server = docking_server(base, no_navigation, statics=statics)
        base.place(Pose2D(1.49, 9.75, math.pi))
        result = await server.dock_robot(DockRobot.Goal(dock_id="home_dock",
                                                        navigate_to_staging_pose=False),
                                         Feedback())  # fmt: skip
        assert result.success, result.error_msg
        distance, heading = docked_error(sim)
        assert distance <= 0.02
        assert heading <= 0.05


async def no_navigation(pose: Pose2D, frame: str, max_time: float) -> None:
    raise AssertionError("no navigation expected")


@pytest.mark.timeout(60)
async def test_the_staging_pose_of_a_dock_in_its_own_frame_goes_to_the_navigator_in_map() -> None:
    went: list[tuple[Pose2D, str]] = []
    statics = StaticFrames()
    bay = Rigid3D(np.array([1.49, 9.75, 0.0]), quat_from_yaw(math.pi))  # the staging pose
    statics.add(TFMessage(transforms=[link("map", "bay", bay)]))
    with office_sim() as sim:
        base = SimBase(sim)

        async def navigate(pose: Pose2D, frame: str, max_time: float) -> None:
            went.append((pose, frame))
            base.place(pose)

        server = docking_server(base, navigate, statics=statics)
        dock = server.docks["home_dock"]
        server.docks["home_dock"] = replace(dock, pose=Pose2D(1.0, 0.0, 0.0), frame="bay")
        base.place(Pose2D(3.0, 10.2, 0.0))
        result = await server.dock_robot(DockRobot.Goal(dock_id="home_dock"), Feedback())
        assert result.success, result.error_msg
        [(staging, frame)] = went
        assert frame == "map"
        assert (staging.x, staging.y) == pytest.approx((1.49, 9.75))
        assert docked_error(sim)[0] <= 0.02
