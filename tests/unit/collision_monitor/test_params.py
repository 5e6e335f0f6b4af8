"""Nav2 parameter files load; what cannot run is refused naming the place and parameter."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from aiobt_services.collision_monitor import MonitorConfigError, load_params
from aiobt_services.collision_monitor.__main__ import main
from aiobt_services.collision_monitor.main import DEFAULT_PARAMS

from .nav2_setup import config, polygon

NAV2_EXAMPLE = """
collision_monitor:
  ros__parameters:
    base_frame_id: "base_footprint"
    odom_frame_id: "odom"
    cmd_vel_in_topic: "cmd_vel_smoothed"
    cmd_vel_out_topic: "cmd_vel"
    state_topic: "collision_monitor_state"
    transform_tolerance: 0.5
    source_timeout: 5.0
    base_shift_correction: true
    stop_pub_timeout: 2.0
    polygons: ["PolygonStop", "FootprintApproach"]
    PolygonStop:
      type: "polygon"
      points: "[[0.3, 0.3], [0.3, -0.3], [0.0, -0.3], [0.0, 0.3]]"
      action_type: "stop"
      min_points: 4
      visualize: true
      polygon_pub_topic: "polygon_stop"
      enabled: true
    PolygonSlow:
      type: "polygon"
      points: "[[0.4, 0.4], [0.4, -0.4], [-0.4, -0.4], [-0.4, 0.4]]"
      action_type: "slowdown"
    FootprintApproach:
      type: "polygon"
      action_type: "approach"
      footprint_topic: "/local_costmap/published_footprint"
      time_before_collision: 2.0
      simulation_time_step: 0.1
      min_points: 6
      visualize: false
      enabled: true
    observation_sources: ["scan"]
    scan:
      type: "scan"
      topic: "scan"
      enabled: true
"""


def test_nav2s_own_example_loads() -> None:
    params = load_params(yaml.safe_load(NAV2_EXAMPLE))
    assert [z.name for z in params.polygons] == ["PolygonStop", "FootprintApproach"]
    stop, approach = params.polygons
    assert (stop.action_type, stop.min_points, stop.sources_names) == ("stop", 4, ("scan",))
    assert approach.shape.radius == pytest.approx(0.22)  # the footprint: the robot's disc
    assert (params.source_timeout, params.stop_pub_timeout) == (5.0, 2.0)
    assert params.sources[0].source_timeout == 5.0  # the node's, unless the source sets one


def test_nav2s_defaults() -> None:
    params = load_params(config({"Stop": {"points": "[[1, 1], [1, -1], [0, -1]]",
                                          "action_type": "stop"}}))  # fmt: skip
    zone = params.polygons[0]
    assert (zone.min_points, zone.slowdown_ratio, zone.linear_limit, zone.angular_limit) == (
        4, 0.5, 0.5, 0.5)  # fmt: skip
    assert (zone.time_before_collision, zone.simulation_time_step, zone.enabled) == (2.0, 0.1, True)
    bare = load_params({"polygons": ["Stop"], "observation_sources": ["s"],
                        "Stop": {"points": [[1, 1], [1, -1], [0, -1]], "action_type": "stop"},
                        "s": {}})  # fmt: skip
    assert (bare.source_timeout, bare.stop_pub_timeout, bare.base_shift_correction) == (
        2.0, 1.0, True)  # fmt: skip
    assert (bare.cmd_vel_in_topic, bare.cmd_vel_out_topic) == ("cmd_vel_smoothed", "cmd_vel")


def test_the_shipped_default_loads() -> None:
    params = load_params(yaml.safe_load(DEFAULT_PARAMS.read_text()))
    assert {z.action_type for z in params.polygons} == {"stop", "approach"}
    assert (
        next(z for z in params.polygons if z.action_type == "approach").time_before_collision == 1.5
    )


@pytest.mark.parametrize(
    ("polygons", "top", "message"),
    [
        ({"P": polygon("polygon", 1.0, "stop", points="[[0, 0], [1, 0]]")}, {},
         "polygon 'P' has 2 points"),
        ({"P": polygon("polygon", 1.0, "stop", points="[[0, 0], [1, 1], [1, 0], [0, 1]]")}, {},
         "polygon 'P' is self-intersecting"),
        ({"P": polygon("polygon", 1.0, "limit", linear_limit=-0.1)}, {},
         "polygon 'P': linear_limit is -0.1: it must be >= 0"),
        ({"P": polygon("polygon", 1.0, "slowdown", slowdown_ratio=1.5)}, {},
         "polygon 'P': slowdown_ratio is 1.5: it must be <= 1"),
        ({"P": polygon("polygon", 1.0, "stop", sources_names=["lidar2"])}, {},
         "polygon 'P': source 'lidar2' is not one of the observation_sources"),
        ({"P": polygon("polygon", 1.0, "brake")}, {}, "polygon 'P': unknown action_type 'brake'"),
        ({"P": polygon("hexagon", 1.0, "stop")}, {}, "polygon 'P': unknown polygon type 'hexagon'"),
        ({"P": polygon("circle", -1.0, "stop")}, {}, "circle 'P': radius must be a number > 0"),
        ({"P": polygon("polygon", 1.0, "stop", min_point=3)}, {},
         "polygon 'P': unknown parameter(s) ['min_point']"),
        ({"P": polygon("polygon", 1.0, "stop")}, {"source_timeout": -1.0},
         "collision_monitor: source_timeout is -1.0"),
        ({"P": polygon("polygon", 1.0, "stop")}, {"Scan": {"type": "sonar"}},
         "source 'Scan': unknown source type 'sonar'"),
        ({"P": polygon("polygon", 1.0, "stop")}, {"polygons": ["P", "Q"]},
         "polygons names 'Q', which has no section"),
    ],
)  # fmt: skip
def test_what_cannot_run_is_refused_by_name(
    polygons: dict[str, Any], top: dict[str, Any], message: str
) -> None:
    escaped = (
        message.replace("[", r"\[").replace("]", r"\]").replace("(", r"\(").replace(")", r"\)")
    )
    with pytest.raises(MonitorConfigError, match=escaped):
        load_params(config(polygons, **top))


def test_the_service_refuses_a_bad_file_before_opening_the_bus(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    bad = config({"Stop": polygon("polygon", 1.0, "stop", points="[[0, 0], [1, 0]]")})
    path = tmp_path / "cm.yaml"
    path.write_text(yaml.safe_dump(bad))
    assert main(["--params-file", str(path), "--connect", "tcp/127.0.0.1:1"]) == 2
    assert f"{path}: polygon 'Stop' has 2 points" in caplog.text
