"""Request/response services: costmap clearing and path validity (``nav2_msgs/srv``).

Each service groups ``Request`` and ``Response``, like the actions do; pass them
to ``bus.serve(name, X.Request, X.Response, handler)`` and ``bus.call(...)``.
"""

from __future__ import annotations

from typing import ClassVar, TypeAlias

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.action import Empty
from aiobt.msgs.geometry import PoseStamped
from aiobt.msgs.nav import Path


class ClearCostmapResponse(Msg):
    success: bool = True
    message: str = ""


class _ClearEntireRequest(Msg):
    plugins: list[str] = Field(default_factory=list, description="empty: every clearable layer")


class _ClearRegionRequest(Msg):
    reset_distance: float = Field(default=1.0, ge=0.0, description="side of the square (m)")
    plugins: list[str] = Field(default_factory=list)


class _ClearAroundPoseRequest(Msg):
    pose: PoseStamped
    reset_distance: float = Field(default=1.0, ge=0.0)
    plugins: list[str] = Field(default_factory=list)


class _ClearService:
    verb: ClassVar[str]

    @classmethod
    def service_name(cls, costmap: str) -> str:
        """Nav2's default name, e.g. ``global_costmap/clear_entirely_global_costmap``."""
        return f"{costmap}/{cls.verb}_{costmap}"


class ClearEntireCostmap(_ClearService):
    verb = "clear_entirely"
    Request: TypeAlias = _ClearEntireRequest
    Response: TypeAlias = ClearCostmapResponse


class ClearCostmapExceptRegion(_ClearService):
    """Clear everything except a square of side ``reset_distance`` around the robot."""

    verb = "clear_except"
    Request: TypeAlias = _ClearRegionRequest
    Response: TypeAlias = ClearCostmapResponse


class ClearCostmapAroundRobot(_ClearService):
    """Clear a square of side ``reset_distance`` around the robot."""

    verb = "clear_around"
    Request: TypeAlias = _ClearRegionRequest
    Response: TypeAlias = ClearCostmapResponse


class ClearCostmapAroundPose(_ClearService):
    """Clear obstacles closer than ``reset_distance`` to ``pose``."""

    verb = "clear_around_pose"
    Request: TypeAlias = _ClearAroundPoseRequest
    Response: TypeAlias = ClearCostmapResponse


class _IsPathValidRequest(Msg):
    """nav2_msgs/IsPathValid: checked from the path's pose closest to the robot."""

    path: Path
    max_cost: int = Field(default=253, ge=0, le=255)
    consider_unknown_as_obstacle: bool = False
    layer_name: str = ""  # "": the full costmap; else one layer's own costs
    footprint: str = ""  # "[[x, y], ...]": checked with this polygon; "": the robot's
    stop_at_first_collision: bool = True
    max_lookahead_distance: float = -1.0  # m along the path from the closest pose; < 0: all


class _IsPathValidResponse(Msg):
    is_valid: bool
    invalid_pose_indices: list[int] = Field(default_factory=list)
    success: bool = True  # False: the check could not be made (``message`` says why)
    message: str = ""


class IsPathValid:
    service_name: ClassVar[str] = "is_path_valid"
    Request: TypeAlias = _IsPathValidRequest
    Response: TypeAlias = _IsPathValidResponse


class _Acknowledgement(Msg):
    """The answer of a service without a result (``std_srvs/Empty`` in Nav2):
    ``ok`` false with the reason in ``message``."""

    ok: bool = True
    message: str = ""
    id: str = ""


class ReinitializeGlobalLocalization:
    """Scatter the localization estimate and relocalize (the robot service)."""

    service_name: ClassVar[str] = "reinitialize_global_localization"
    Request: TypeAlias = Empty
    Response: TypeAlias = _Acknowledgement


class _GetCostsRequest(Msg):
    use_footprint: bool = False
    poses: list[PoseStamped] = Field(default_factory=list)


class _GetCostsResponse(Msg):
    costs: list[float] = Field(default_factory=list, description="one per pose, 0..255")
    success: bool = True


class GetCosts:
    """The costs of a costmap at some poses (the robot's footprint there, or the point)."""

    @staticmethod
    def service_name(costmap: str) -> str:
        """Nav2's default name, e.g. ``global_costmap/get_cost_global_costmap``."""
        return f"{costmap}/get_cost_{costmap}"

    Request: TypeAlias = _GetCostsRequest
    Response: TypeAlias = _GetCostsResponse


class _ToggleRequest(Msg):
    enable: bool = True


class Toggle:
    """Switch a component on or off (Nav2's collision monitor ``toggle``)."""

    Request: TypeAlias = _ToggleRequest
    Response: TypeAlias = ClearCostmapResponse  # success and message, as nav2_msgs/Toggle
