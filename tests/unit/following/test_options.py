"""``aiobt following``'s flags: Nav2's names and defaults, bad values named."""

from __future__ import annotations

import argparse
import math

import pytest

from aiobt_services.following.main import add_arguments, run
from aiobt_services.following.options import following_params


def parse(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    return parser.parse_args(list(argv))


def test_defaults_are_nav2s() -> None:
    p = following_params(parse())
    assert (p.controller_frequency, p.detection_timeout, p.rotate_to_object_timeout) == (
        50.0, 2.0, 10.0)  # fmt: skip
    assert (p.desired_distance, p.linear_tolerance, p.angular_tolerance) == (1.0, 0.15, 0.15)
    assert (p.max_retries, p.search_by_rotating, p.search_angle) == (3, False, math.pi / 2)
    assert (p.fixed_frame, p.base_frame, p.filter_coef, p.skip_orientation) == (
        "odom", "base_link", 0.1, True)  # fmt: skip
    assert (p.controller.v_linear_max, p.controller.v_angular_max) == (0.25, 0.75)
    assert p.rotate.rotate_to_heading_angular_vel == 1.0


def test_nav2_names_set_them() -> None:
    p = following_params(parse("--desired-distance", "1.5", "--search-by-rotating", "true",
                               "--controller.v-linear-max", "0.5", "--controller.lambda", "1.5",
                               "--controller.rotate-to-heading-angular-vel", "0.8"))  # fmt: skip
    assert (p.desired_distance, p.search_by_rotating) == (1.5, True)
    assert (p.controller.v_linear_max, p.controller.lambda_) == (0.5, 1.5)
    assert p.rotate.rotate_to_heading_angular_vel == 0.8


def test_bad_values_are_named(caplog: pytest.LogCaptureFixture) -> None:
    with pytest.raises(ValueError, match="Collision detection is not supported"):
        following_params(parse("--controller.use-collision-detection", "true"))
    with pytest.raises(ValueError, match="filter_coef"):
        following_params(parse("--filter-coef", "2"))
    with pytest.raises(ValueError, match=r"controller\.v_linear_min"):
        following_params(parse("--controller.v-linear-min", "0.6"))
    assert run(parse("--controller.use-collision-detection", "true")) == 2
    assert "controller.use_collision_detection" in caplog.text
