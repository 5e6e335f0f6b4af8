"""ClearEntireCostmap, ClearCostmapExceptRegion, ClearCostmapAroundRobot and
ClearCostmapAroundPose (Nav2): ask a costmap to forget its obstacles."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.ports import PortInfo, input_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import (
    ClearCostmapAroundPose as AroundPoseSrv,
)
from aiobt.msgs import (
    ClearCostmapAroundRobot as AroundRobotSrv,
)
from aiobt.msgs import (
    ClearCostmapExceptRegion as ExceptRegionSrv,
)
from aiobt.msgs import (
    ClearCostmapResponse,
    Msg,
    PoseStamped,
)
from aiobt.msgs import (
    ClearEntireCostmap as ClearEntireSrv,
)
from aiobt.nav.remote import service_ports
from aiobt.nav.services.base import BtService

_PLUGINS = input_port(
    "plugins",
    list[str],
    description="Optional. Costmap plugin names to clear; all clearable layers if empty.",
)
_RESET_DISTANCE = input_port(
    "reset_distance", float, 1.0, "Side of the square around the robot (m)."
)


def _ports(*extra: PortInfo) -> tuple[PortInfo, ...]:
    # Nav2 gives no default service: trees name it, e.g.
    # "local_costmap/clear_entirely_local_costmap" (served by the controller)
    # or "global_costmap/clear_entirely_global_costmap" (the planner).
    return service_ports("", *extra, _PLUGINS)


class _ClearCostmap(BtService):
    """Clears; SUCCESS if the costmap reports success, else FAILURE. Each
    activation adds one to ``number_recoveries`` (Nav2)."""

    RESPONSE = ClearCostmapResponse
    REQUEST: ClassVar[type[Any]]

    def request_fields(self) -> dict[str, Any]:
        return {}

    def make_request(self) -> Msg:
        plugins = self.get_input("plugins", None) or []
        request: Msg = self.REQUEST(plugins=plugins, **self.request_fields())
        return request

    def counts_as_recovery(self) -> bool:
        return True

    def on_completion(self, response: Any) -> Status:
        if not response.success:
            self.log.error("%s: failed to clear costmap layers: %s", self.path, response.message)
            return FAILURE
        return SUCCESS


class ClearEntireCostmap(_ClearCostmap):
    """``<ClearEntireCostmap service_name="local_costmap/clear_entirely_local_costmap"/>``:
    clear every obstacle of the costmap (or of ``plugins``)."""

    REQUEST = ClearEntireSrv.Request
    PORTS = _ports()


class ClearCostmapExceptRegion(_ClearCostmap):
    """``<ClearCostmapExceptRegion service_name="..." reset_distance="2.0"/>``: clear
    everything except a square of side ``reset_distance`` around the robot."""

    REQUEST = ExceptRegionSrv.Request
    PORTS = _ports(_RESET_DISTANCE)

    def request_fields(self) -> dict[str, Any]:
        return {"reset_distance": self.get_input("reset_distance")}


class ClearCostmapAroundRobot(_ClearCostmap):
    """``<ClearCostmapAroundRobot service_name="..." reset_distance="1.0"/>``: clear a
    square of side ``reset_distance`` around the robot."""

    REQUEST = AroundRobotSrv.Request
    PORTS = _ports(_RESET_DISTANCE)

    def request_fields(self) -> dict[str, Any]:
        return {"reset_distance": self.get_input("reset_distance")}


class ClearCostmapAroundPose(_ClearCostmap):
    """``<ClearCostmapAroundPose service_name="..." pose="{pose}" reset_distance="1.0"/>``:
    clear obstacles closer than ``reset_distance`` to ``pose``."""

    REQUEST = AroundPoseSrv.Request
    PORTS = _ports(
        input_port("pose", PoseStamped, description="Pose around which to clear the costmap."),
        input_port(
            "reset_distance",
            float,
            1.0,
            "Distance from the pose under which obstacles are cleared.",
        ),
    )

    def request_fields(self) -> dict[str, Any]:
        return {"pose": self.get_input("pose"), "reset_distance": self.get_input("reset_distance")}
