"""``aiobt docking``'s flags: Nav2's names and defaults, the set-up shipped for aiobt's
robot, and a bad parameter named before anything starts."""

from __future__ import annotations

import argparse

import pytest

from aiobt_services.docking.main import add_arguments, run
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
        (["--param", "controller.projection_time=0"], "projection_time .* must be > 0"),
        (["--param", "controller.use_collision_detection=maybe"], "bad value 'maybe'"),
        (["--param", "simple_charging_dock.plugin=opennav_docking::Pallet"], "no dock plugin"),
        (["--fixed-frame", "world"], "fixed_frame must be odom or map"),
        (["--dock-plugins", ""], "Charging dock plugins empty"),
    ],
)
def test_a_bad_parameter_is_named(argv: list[str], problem: str) -> None:
    with pytest.raises(ValueError, match=problem):
        settings_from(parse(*argv))


def test_the_command_exits_2_on_a_bad_parameter(caplog: pytest.LogCaptureFixture) -> None:
    assert run(parse("--param", "controller.k_phy=1")) == 2
    assert "controller.k_phy: no such parameter" in caplog.text
