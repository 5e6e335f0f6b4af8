"""AMCL's parameters: Nav2's names and defaults (``nav2_amcl/src/amcl_node.cpp``).

The laser models ``likelihood_field`` (Nav2's default) and
``likelihood_field_prob`` (with beam skipping) and the differential motion model
exist here; the beam model's parameters (``z_short``, ``z_max``,
``lambda_short``) are accepted with Nav2's defaults so a Nav2 params file loads,
and the beam model, ``do_beamskip: true`` with ``likelihood_field`` (which never
skips beams) or another model type is refused.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from .long_beams import MARGIN_SIGMAS

LASER_MODEL_TYPES = ("likelihood_field", "likelihood_field_prob")  # Nav2's also: "beam"


class ParamError(ValueError):
    """A parameter has a bad value (the message names it)."""


@dataclass(slots=True, frozen=True)
class InitialPose:
    """``initial_pose.{x,y,z,yaw}``."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    yaw: float = 0.0


@dataclass(slots=True, frozen=True)
class AmclParams:
    """``amcl.ros__parameters`` as Nav2 reads them."""

    alpha1: float = 0.2
    alpha2: float = 0.2
    alpha3: float = 0.2
    alpha4: float = 0.2
    alpha5: float = 0.2
    base_frame_id: str = "base_footprint"
    beam_skip_distance: float = 0.5
    beam_skip_error_threshold: float = 0.9
    beam_skip_threshold: float = 0.3
    do_beamskip: bool = False
    global_frame_id: str = "map"
    lambda_short: float = 0.1
    laser_likelihood_max_dist: float = 2.0
    laser_max_range: float = 100.0
    laser_min_range: float = -1.0
    laser_model_type: str = "likelihood_field"
    set_initial_pose: bool = False
    initial_pose: InitialPose = field(default_factory=InitialPose)
    max_beams: int = 60
    max_particles: int = 2000
    min_particles: int = 500
    odom_frame_id: str = "odom"
    pf_err: float = 0.05
    pf_z: float = 0.99
    recovery_alpha_fast: float = 0.0
    recovery_alpha_slow: float = 0.0
    recovery_reset_after_injection: bool = True  # not Nav2's (pf.c resets): recovery.py
    recovery_min_long_beams: float = 0.0  # not Nav2's (0: no gate): long_beams.py
    resample_interval: int = 1
    robot_model_type: str = "nav2_amcl::DifferentialMotionModel"
    save_pose_rate: float = 0.5
    sigma_hit: float = 0.2
    tf_broadcast: bool = True
    transform_tolerance: float = 1.0
    update_min_a: float = 0.2
    update_min_d: float = 0.25
    z_hit: float = 0.5
    z_max: float = 0.05
    z_rand: float = 0.5
    z_short: float = 0.05
    first_map_only: bool = False
    always_reset_initial_pose: bool = False
    scan_topic: str = "scan"
    map_topic: str = "map"
    random_seed: int = -1

    def __post_init__(self) -> None:
        for name in ("alpha1", "alpha2", "alpha3", "alpha4", "alpha5", "z_hit", "z_rand"):
            _check(name, getattr(self, name), low=0.0)
        for name in ("laser_likelihood_max_dist", "sigma_hit", "update_min_d", "update_min_a"):
            _check(name, getattr(self, name), low=0.0, strict=name.startswith(("laser", "sigma")))
        _check("pf_err", self.pf_err, low=0.0, strict=True, high=1.0)
        _check("pf_z", self.pf_z, low=0.0, strict=True, high=1.0)
        _check("recovery_alpha_slow", self.recovery_alpha_slow, low=0.0, high=1.0)
        _check("recovery_alpha_fast", self.recovery_alpha_fast, low=0.0, high=1.0)
        _check("recovery_min_long_beams", self.recovery_min_long_beams, low=0.0, high=1.0)
        _check("beam_skip_distance", self.beam_skip_distance, low=0.0)
        _check("beam_skip_threshold", self.beam_skip_threshold, low=0.0, high=1.0)
        _check("beam_skip_error_threshold", self.beam_skip_error_threshold, low=0.0, high=1.0)
        if self.recovery_min_long_beams > 0.0 and self.laser_likelihood_max_dist <= (
            MARGIN_SIGMAS * self.sigma_hit
        ):
            raise ParamError(
                "recovery_min_long_beams needs laser_likelihood_max_dist > 2 sigma_hit (the "
                f"gate's margin), got {self.laser_likelihood_max_dist} and {self.sigma_hit}"
            )
        if self.z_hit + self.z_rand <= 0.0:
            raise ParamError("z_hit + z_rand must be > 0")
        if not self.max_beams >= 2:
            raise ParamError(f"max_beams must be >= 2, got {self.max_beams}")
        if not 1 <= self.min_particles <= self.max_particles:
            raise ParamError(
                f"need 1 <= min_particles <= max_particles, got {self.min_particles} "
                f"and {self.max_particles}"
            )
        if self.resample_interval < 1:
            raise ParamError(f"resample_interval must be >= 1, got {self.resample_interval}")
        self._check_models()

    def _check_models(self) -> None:
        if self.laser_model_type == "beam":
            raise ParamError(
                "laser_model_type 'beam': Nav2's beam model (a ray cast per particle and "
                "beam) is not implemented here; use 'likelihood_field' or "
                "'likelihood_field_prob'"
            )
        if self.laser_model_type not in LASER_MODEL_TYPES:
            raise ParamError(
                f"laser_model_type {self.laser_model_type!r}: must be one of "
                f"{', '.join(repr(t) for t in LASER_MODEL_TYPES)}"
            )
        if self.do_beamskip and self.laser_model_type != "likelihood_field_prob":
            raise ParamError(
                f"do_beamskip: true does nothing with laser_model_type "
                f"{self.laser_model_type!r} (Nav2 skips beams only in "
                "'likelihood_field_prob'); set it false or use that model"
            )
        model = self.robot_model_type.rsplit("::", 1)[-1]
        if model != "DifferentialMotionModel":
            raise ParamError(
                f"robot_model_type {self.robot_model_type!r}: only "
                "'nav2_amcl::DifferentialMotionModel' exists here"
            )

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any]) -> AmclParams:
        """From a Nav2 params mapping (``amcl.ros__parameters``), dotted or nested
        ``initial_pose``; an unknown name is refused with the known ones."""
        known = {f.name: f for f in dataclasses.fields(cls)}
        kwargs: dict[str, Any] = {}
        pose: dict[str, float] = {}
        for name, value in values.items():
            if name == "initial_pose" and isinstance(value, Mapping):
                pose.update(
                    {str(k): _typed(f"initial_pose.{k}", v, float) for k, v in value.items()}
                )
            elif name.startswith("initial_pose."):
                pose[name.split(".", 1)[1]] = _typed(name, value, float)
            elif name in ("use_sim_time", "allow_parameter_qos_overrides", "introspection_mode"):
                continue  # ROS plumbing, nothing to do here
            elif name in known and name != "initial_pose":
                kwargs[name] = _typed(name, value, type(getattr(cls(), name)))
            else:
                raise ParamError(f"unknown AMCL parameter {name!r} (known: {', '.join(known)})")
        if pose:
            unknown = set(pose) - {"x", "y", "z", "yaw"}
            if unknown:
                raise ParamError(f"unknown initial_pose fields {sorted(unknown)}")
            kwargs["initial_pose"] = InitialPose(**pose)
        return cls(**kwargs)


def _typed(name: str, value: Any, kind: type) -> Any:
    if kind is float and isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    if isinstance(value, kind) and not (kind is int and isinstance(value, bool)):
        return value
    raise ParamError(f"parameter {name} must be {kind.__name__}, got {value!r}")


def _check(
    name: str, value: float, *, low: float, strict: bool = False, high: float = math.inf
) -> None:
    ok = math.isfinite(value) and (value > low if strict else value >= low) and value <= high
    if not ok:
        bound = f"{'>' if strict else '>='} {low:g}" + (
            f" and <= {high:g}" if high < math.inf else ""
        )
        raise ParamError(f"parameter {name} must be finite and {bound}, got {value}")
