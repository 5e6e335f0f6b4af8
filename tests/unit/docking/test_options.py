"""``aiobt docking``'s flags: Nav2's names and defaults, the set-up shipped for aiobt's
robot, and a bad parameter named before anything starts."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from aiobt_services.docking.main import add_arguments, database_or_explain, footprint_of, run
from aiobt_services.docking.options import settings_from


def parse(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    return parser.parse_args(list(argv))


def test_nav2s_defaults_and_the_shipped_set_up() -> None:
    settings = settings_from(parse())
    d = settings.docking
    assert (d.controller_frequency, d.max_retries, d.fixed_frame) == (50.0, 3, "odom")
    assert (d.dock_approach_timeout, d.undock_linear_tolerance) == (30.0, 0.05)
    [plugin] = settings.plugins
    assert plugin.name == "simple_charging_dock"
    assert plugin.params.use_external_detection_pose
    assert plugin.params.filter_coef == 0.1  # Nav2's, not overridden
    assert settings.controller.law.k_phi == 5.0


def test_param_overrides_the_set_up() -> None:
    settings = settings_from(parse("--param", "controller.k_phi=3.0", "--param",
                                   "simple_charging_dock.staging_x_offset=-0.7"))  # fmt: skip
    assert settings.controller.law.k_phi == 3.0
    assert settings.plugins[0].params.staging_x_offset == -0.7


@pytest.mark.parametrize(
    ("argv", "problem"),
    [
        (["--param", "dock2.docking_threshold=0.1"], "'dock2' is neither 'controller' nor"),
        (["--param", "controller.k_phy=1"], "controller.k_phy: no such parameter"),
        (
            ["--param", "controller.costmap_topic=local_costmap/costmap_raw"],
            "controller.costmap_topic: not read: aiobt's controller publishes no",
        ),
        (["--param", "controller.transform_tolerance=0.1"], "transform_tolerance: not read"),
        (["--param", "controller.projection_time=0"], "projection_time .* must be > 0"),
        (["--param", "controller.use_collision_detection=maybe"], "bad value 'maybe'"),
        (["--param", "simple_charging_dock.plugin=opennav_docking::Pallet"], "no dock plugin"),
        (["--param", "simple_charging_dock.filter_coef=1.5"], "filter_coef must be within"),
        (
            ["--param", "simple_charging_dock.detector_service_name=dock/*"],
            "detector_service_name: service 'dock/[*]' is not a valid key",
        ),
        (["--fixed-frame", "world"], "fixed_frame must be odom or map"),
        (["--dock-plugins", ""], "Charging dock plugins empty"),
        (["--docks", "d1", "--param", "d1.pose=[0,0,0]"], "Dock d1 has no dock 'type'"),
        (["--docks", "d1", "--param", "d2.type=t"], "nor the docks \\(d1\\)"),
    ],
)
def test_a_bad_parameter_is_named(argv: list[str], problem: str) -> None:
    with pytest.raises(ValueError, match=problem):
        settings_from(parse(*argv))


def test_the_command_exits_2_on_a_bad_parameter(caplog: pytest.LogCaptureFixture) -> None:
    assert run(parse("--param", "controller.k_phy=1")) == 2
    assert "controller.k_phy: no such parameter" in caplog.text


def test_the_footprint_is_nav2s_string_or_the_robots_circle() -> None:
    np.testing.assert_allclose(footprint_of(parse("--footprint", "[[0.3, 0.2], [0.3, -0.2], "
                                                  "[-0.2, 0]]")),
                               [[0.3, 0.2], [0.3, -0.2], [-0.2, 0.0]])  # fmt: skip
    for argv in ((), ("--footprint", "[]")):  # Nav2's default "[]": the radius
        circle = footprint_of(parse("--robot-radius", "0.3", *argv))
        assert circle.shape == (16, 2)
        np.testing.assert_allclose(np.hypot(circle[:, 0], circle[:, 1]), 0.3)
        np.testing.assert_allclose(circle[0], [0.3, 0.0], atol=1e-12)


def test_a_bad_footprint_stops_the_command(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        parse("--footprint", "[[0, 0], [1, 1]]")
    assert "needs at least 3 [x, y] points" in capsys.readouterr().err


DOCKS = ("--docks", "dock1, dock2", "--param", "dock1.type=simple_charging_dock",
         "--param", "dock1.pose=[1.0, 2.0, 3.14]", "--param", "dock2.type=",
         "--param", "dock2.pose=[0, 0, 0]", "--param", "dock2.frame=odom",
         "--param", "dock2.id=tag_2")  # fmt: skip


def test_docks_from_the_parameters_without_a_database() -> None:
    args = parse(*DOCKS)
    docks, problem = database_or_explain(args, settings_from(args).docks)
    assert problem == ""
    assert list(docks) == ["dock1", "dock2"]
    d1, d2 = docks["dock1"], docks["dock2"]
    assert (d1.type, d1.frame, d1.pose.x, d1.pose.y, d1.pose.yaw) == (
        "simple_charging_dock", "map", 1.0, 2.0, 3.14)  # fmt: skip
    assert (d2.type, d2.frame, d2.id) == ("", "odom", "tag_2")


def test_the_database_file_comes_first_as_in_nav2(caplog: pytest.LogCaptureFixture) -> None:
    args = parse(*DOCKS, "--dock-database", "office")
    docks, _ = database_or_explain(args, settings_from(args).docks)
    assert list(docks) == ["home_dock"]
    assert "docks: ignored, dock_database" in caplog.text
    args = parse(*DOCKS, "--dock-database", "office", "--dock-database", "")  # aiobt up's, undone
    docks, _ = database_or_explain(args, settings_from(args).docks)
    assert list(docks) == ["dock1", "dock2"]


def test_neither_database_nor_docks_serves_goals_by_pose(caplog: pytest.LogCaptureFixture) -> None:
    args = parse()
    assert database_or_explain(args, settings_from(args).docks) == ({}, "")
    assert "Dock database filepath nor dock parameters set" in caplog.text


def test_a_non_charging_dock_plugin_by_nav2s_type() -> None:
    kind = "pallet.plugin=opennav_docking::SimpleNonChargingDock"
    [plugin] = settings_from(parse("--dock-plugins", "pallet", "--param", kind,
                                   "--param", "pallet.staging_x_offset=-0.5")).plugins  # fmt: skip
    assert plugin.params.staging_x_offset == -0.5
    with pytest.raises(ValueError, match=r"pallet\.charging_threshold: no such parameter"):
        settings_from(parse("--dock-plugins", "pallet", "--param", kind,
                            "--param", "pallet.charging_threshold=1.0"))  # fmt: skip
