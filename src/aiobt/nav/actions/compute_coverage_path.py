"""ComputeCoveragePath (opennav_coverage): a path that covers a field."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import ComputeCoveragePath as ComputeCoveragePathAction
from aiobt.msgs import Path
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

POLYGONS = "vector<geometry_msgs::msg::Polygon>"  # values: lists of points, or {points: [...]}


class ComputeCoveragePath(BtAction):
    """``<ComputeCoveragePath polygons="{field}" nav_path="{path}"/>``

    The field is ``polygons`` (the outer boundary first, then cut-outs; each a list
    of points or an object with ``points``) in ``polygons_frame_id``, or a GML
    ``file_field``. SUCCESS: ``nav_path`` (to follow), ``coverage_path`` (swaths and
    turns) and ``planning_time`` (s); FAILURE with the server's ``error_code_id``.
    """

    ACTION = ComputeCoveragePathAction
    PORTS = action_ports(
        "The complete coverage",
        ComputeCoveragePathAction.name,
        input_port("generate_headland", bool, True, "Whether to generate headland."),
        input_port("generate_route", bool, True, "Whether to order the swaths into a route."),
        input_port("generate_path", bool, True, "Whether to connect the route into a path."),
        input_port("file_field", str, description="Path of a field GML file."),
        input_port("file_field_id", int, 0, "Ordered ID of the field in the GML file."),
        input_port("polygons", POLYGONS, description="The field, if not from a file."),
        input_port("polygons_frame_id", str, "map", "Frame of the polygons."),
        output_port("planning_time", float, description="The time to compute the plan (s)."),
        output_port("nav_path", Path, description="The coverage plan as a path to track."),
        output_port("coverage_path", Path, description="The swaths and turns, in order."),
    )

    def make_goal(self) -> Any:
        fields: dict[str, Any] = {
            name: self.get_input(name)
            for name in ("generate_headland", "generate_route", "generate_path")
        }
        gml = self.get_input("file_field", None)
        if gml:
            fields.update(use_gml_file=True, gml_field=gml,
                          gml_field_id=self.get_input("file_field_id"))  # fmt: skip
        else:
            polygons = self.get_input("polygons", None) or []
            fields.update(polygons=[_points(p) for p in polygons],
                          frame_id=self.get_input("polygons_frame_id"))  # fmt: skip
        return self.ACTION.goal_type()(**fields)

    def on_success(self, result: Any) -> Status:
        self.set_output("nav_path", result.nav_path)
        self.set_output("coverage_path", result.coverage_path)
        self.set_output("planning_time", result.planning_time)
        return super().on_success(result)


def _points(polygon: Any) -> Any:
    if isinstance(polygon, dict):
        return polygon.get("points", polygon)
    return getattr(polygon, "points", polygon)
