"""``aiobt following``'s flags: Nav2's ``following_server`` parameter names (dashes for
underscores; the docking controller's as ``--controller.NAME``), Nav2's defaults."""

from __future__ import annotations

import argparse
import math
from dataclasses import fields

from aiobt.geometry.smooth import RotateParams, SmoothControlParams
from aiobt.system.service import non_negative, positive

from .params import FollowingParams

NO_COLLISION_DETECTION = (  # Nav2's words
    "Collision detection is not supported in the following server. "
    "Please disable the controller.use_collision_detection parameter."
)


def flag(text: str) -> bool:
    if text.lower() not in ("true", "false"):
        raise argparse.ArgumentTypeError(f"must be true or false, got {text}")
    return text.lower() == "true"


def _number(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text}")
    return value


def add_following_arguments(group: argparse._ArgumentGroup) -> None:
    d = FollowingParams()
    add = group.add_argument
    for name, kind, unit in (
        ("controller_frequency", positive, "Hz"),
        ("detection_timeout", positive, "s a detection stays good"),
        ("rotate_to_object_timeout", positive, "s of searching"),
        ("static_object_timeout", _number, "s at a still object before success; <= 0: never"),
        ("linear_tolerance", non_negative, "m"),
        ("angular_tolerance", non_negative, "rad"),
        ("desired_distance", non_negative, "m kept from the object"),
        ("search_angle", non_negative, "rad either side when searching"),
        ("transform_tolerance", non_negative, "s between a detection and the robot pose"),
        ("odom_duration", non_negative, "s (accepted as Nav2; the search reads the raw rate)"),
        ("filter_coef", non_negative, "low-pass weight of a new detection, 0: none"),
    ):
        add(f"--{name.replace('_', '-')}", type=kind, default=getattr(d, name),
            help=f"{unit} (default: %(default)s)")  # fmt: skip
    add("--max-retries", type=int, default=d.max_retries, help="(default: %(default)s)")
    for name in ("skip_orientation", "search_by_rotating"):
        add(f"--{name.replace('_', '-')}", type=flag, default=getattr(d, name), metavar="BOOL",
            help="true/false (default: %(default)s)")  # fmt: skip
    for name in ("base_frame", "fixed_frame", "odom_topic"):
        add(f"--{name.replace('_', '-')}", default=getattr(d, name), help="(default: %(default)s)")
    add("--controller.use-collision-detection", type=flag, default=False, dest="collision",
        metavar="BOOL",
        help="must stay false: Nav2's following server refuses it")  # fmt: skip
    for cls in (SmoothControlParams, RotateParams):
        for f in fields(cls):
            nav2 = f.name.rstrip("_")
            add(f"--controller.{nav2.replace('_', '-')}", type=non_negative, default=f.default,
                dest=f"controller.{nav2}", metavar="X", help="(default: %(default)s)")  # fmt: skip


def following_params(args: argparse.Namespace) -> FollowingParams:
    """The parameters from the flags; ValueError naming a bad one."""
    if args.collision:
        raise ValueError(NO_COLLISION_DETECTION)

    def controller(cls: type) -> dict[str, float]:
        return {f.name: getattr(args, f"controller.{f.name.rstrip('_')}") for f in fields(cls)}

    own = {f.name: getattr(args, f.name) for f in fields(FollowingParams)
           if f.name not in ("controller", "rotate")}  # fmt: skip
    return FollowingParams(**own, controller=SmoothControlParams(**controller(SmoothControlParams)),
                           rotate=RotateParams(**controller(RotateParams)))  # fmt: skip
