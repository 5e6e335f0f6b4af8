"""Navigation messages: odometry, scans, maps, paths, goals, battery.

Path and Goals read and write Nav2's ``;``-separated port strings
(registered with the port converters by :mod:`aiobt.msgs.strings`).
"""

from __future__ import annotations

import reprlib
import threading
import zlib
from enum import IntEnum
from typing import Any, ClassVar, Self

import numpy as np
import numpy.typing as npt
from pydantic import Field, PrivateAttr, ValidationInfo, field_validator, model_validator

from aiobt.msgs._base import Msg
from aiobt.msgs._wire import identity_on_canonical
from aiobt.msgs.geometry import Header, Point, Pose, PoseStamped, Twist

MAX_MAP_CELLS = 100_000_000
_CELL_TYPES = frozenset({int, float})  # exactly: bool (an int subclass) is not a cell


class Odometry(Msg):
    """Pose in ``header.frame_id`` (``odom``) and twist in ``child_frame_id``."""

    header: Header = Field(default_factory=lambda: Header(frame_id="odom"))
    child_frame_id: str = "base_link"
    pose: Pose = Field(default_factory=Pose)
    twist: Twist = Field(default_factory=Twist)


class LaserScan(Msg):
    """A planar scan. A reading outside [range_min, range_max] means "no return"."""

    header: Header = Field(default_factory=lambda: Header(frame_id="base_scan"))
    angle_min: float
    angle_max: float
    angle_increment: float
    time_increment: float = 0.0
    scan_time: float = 0.0
    range_min: float = Field(ge=0.0)
    range_max: float = Field(gt=0.0)
    ranges: list[float]
    intensities: list[float] = Field(default_factory=list)

    @field_validator("angle_increment")
    @classmethod
    def _increment_along_the_sweep(cls, value: float, info: ValidationInfo) -> float:
        if value == 0.0:
            raise ValueError("angle_increment must not be 0")
        sweep = info.data.get("angle_max", 0.0) - info.data.get("angle_min", 0.0)
        if sweep * value < 0.0:  # a clockwise scan has angle_max < angle_min and a negative step
            raise ValueError(
                f"angle_increment {value:g} runs against angle_min -> angle_max ({sweep:+g} rad)"
            )
        return value

    @field_validator("range_max")
    @classmethod
    def _max_above_min(cls, value: float, info: ValidationInfo) -> float:
        if value <= info.data.get("range_min", 0.0):
            raise ValueError("range_max must be greater than range_min")
        return value

    @field_validator("intensities")
    @classmethod
    def _as_long_as_ranges(cls, value: list[float], info: ValidationInfo) -> list[float]:
        if value and len(value) != len(info.data.get("ranges", ())):
            raise ValueError("intensities must be empty or as long as ranges")
        return value

    def ranges_array(self) -> npt.NDArray[np.float64]:
        return np.asarray(self.ranges, dtype=np.float64)

    def angles_array(self) -> npt.NDArray[np.float64]:
        """The beam angle of every reading."""
        return self.angle_min + self.angle_increment * np.arange(len(self.ranges), dtype=np.float64)


class MapMetaData(Msg):
    resolution: float = Field(gt=0.0, description="metres per cell")
    width: int = Field(ge=0)
    height: int = Field(ge=0)
    origin: Pose = Field(default_factory=Pose, description="pose of cell (0, 0)'s corner")


def _inflate(data: bytes, limit: int) -> bytes:
    """Decompress at most ``limit`` + 1 bytes (so a zip bomb costs nothing) and check the size."""
    inflater = zlib.decompressobj()
    try:
        raw = inflater.decompress(data, limit + 1)
    except zlib.error as exc:
        raise ValueError(f"data is not zlib-compressed cells: {exc}") from None
    if len(raw) != limit or not inflater.eof:
        held = f"more than {limit}" if len(raw) > limit else str(len(raw))
        raise ValueError(f"data holds {held} cells, width*height is {limit}")
    return raw


def _decode_cells(data: bytes, meta: MapMetaData) -> npt.NDArray[np.int8]:
    cells = meta.width * meta.height
    if cells > MAX_MAP_CELLS:
        raise ValueError(f"map of {cells} cells exceeds the limit of {MAX_MAP_CELLS}")
    array = np.frombuffer(_inflate(data, limit=cells), dtype=np.int8)
    array = array.reshape(meta.height, meta.width)
    bad = (array < -1) | (array > 100)
    if bad.any():
        row, col = np.argwhere(bad)[0]
        raise ValueError(f"cell (row {row}, col {col}) = {array[row, col]} not in [-1, 100]")
    return array


def _list_cells(value: list[Any]) -> npt.NDArray[np.int8]:
    """The cells of ``data`` given as a plain list: whole numbers in [-1, 100] (``100.0``
    too); a ``ValueError`` names the first bad cell. Vectorised but the type scan."""
    if not _CELL_TYPES.issuperset(map(type, value)):  # strings, None, bools, nested lists
        index = next(i for i, cell in enumerate(value) if type(cell) not in _CELL_TYPES)
        raise ValueError(f"cell {index} = {reprlib.repr(value[index])} is not an integer")
    cells = np.asarray(value)  # int64, float64, or object for integers beyond 64 bits
    if cells.dtype.kind == "f":
        _refuse(cells != np.trunc(cells), value, "is not a whole number")  # NaN too
    _refuse((cells < -1) | (cells > 100), value, "not in [-1, 100]")
    return cells.astype(np.int8)


def _refuse(bad: npt.NDArray[np.bool_], value: list[Any], reason: str) -> None:
    if bad.any():
        index = int(np.argmax(bad))
        raise ValueError(f"cell {index} = {reprlib.repr(value[index])} {reason}")


# the cells the ``data`` validator just decoded in this thread, with the data and
# metadata they came from, for model_post_init (which runs right after it)
_just_decoded = threading.local()


class OccupancyGrid(Msg):
    """A grid of int8 cells (-1 unknown, 0 free .. 100 occupied), row-major from the origin.

    On the wire ``data`` is the zlib-compressed cells, base64 in JSON; a plain list
    of whole numbers in [-1, 100] is accepted too. Inside, :attr:`array` is a
    read-only numpy view of shape ``(height, width)``.
    """

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    info: MapMetaData
    data: bytes
    _array: npt.NDArray[np.int8] = PrivateAttr()

    @field_validator("data", mode="before")
    @classmethod
    def _compress_list(cls, value: Any) -> Any:
        if isinstance(value, list):
            return zlib.compress(_list_cells(value).tobytes())
        return value

    @field_validator("data")
    @classmethod
    def _check_cells(cls, value: bytes, info: ValidationInfo) -> bytes:
        meta = info.data.get("info")
        if isinstance(meta, MapMetaData):  # decoded once: model_post_init takes the cells
            _just_decoded.cells = (value, meta, _decode_cells(value, meta))
        return value

    def model_post_init(self, context: Any, /) -> None:
        decoded = getattr(_just_decoded, "cells", None)
        _just_decoded.cells = None
        if decoded is not None and decoded[0] is self.data and decoded[1] is self.info:
            self._array = decoded[2]
        else:
            self._array = _decode_cells(self.data, self.info)

    @property
    def array(self) -> npt.NDArray[np.int8]:
        return self._array

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, OccupancyGrid):
            return NotImplemented
        same_meta = self.header == other.header and self.info == other.info
        return same_meta and bool(np.array_equal(self._array, other._array))

    __hash__ = None  # type: ignore[assignment]

    @classmethod
    def from_array(
        cls,
        cells: npt.ArrayLike,
        resolution: float,
        origin: Pose | None = None,
        frame_id: str = "map",
        stamp: float = 0.0,
    ) -> Self:
        """A grid from a ``(height, width)`` array of occupancy values."""
        array = np.ascontiguousarray(cells, dtype=np.int8)
        if array.ndim != 2:
            raise ValueError(f"cells must be 2-D (height, width), got shape {array.shape}")
        height, width = array.shape
        info = MapMetaData(
            resolution=resolution, width=width, height=height, origin=origin or Pose()
        )
        return cls(
            header=Header(stamp=stamp, frame_id=frame_id),
            info=info,
            data=zlib.compress(array.tobytes(), level=6),
        )


class Path(Msg):
    __bt_type_name__: ClassVar[str] = "nav_msgs::msg::Path"

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    poses: list[PoseStamped] = Field(default_factory=list)

    def xy_array(self) -> npt.NDArray[np.float64]:
        """``(n, 2)`` array of the positions."""
        if not self.poses:
            return np.zeros((0, 2))
        return np.array([(p.pose.position.x, p.pose.position.y) for p in self.poses])


class Goals(Msg):
    """A list of goal poses (``nav_msgs/Goals``); a bare JSON list is accepted too."""

    __bt_type_name__: ClassVar[str] = "nav_msgs::msg::Goals"

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    goals: list[PoseStamped] = Field(default_factory=list)

    @model_validator(mode="before")
    @classmethod
    @identity_on_canonical  # a long form is an object, not a list
    def _bare_list(cls, data: Any) -> Any:
        return {"goals": data} if isinstance(data, list) else data


class PowerSupplyStatus(IntEnum):
    UNKNOWN = 0
    CHARGING = 1
    DISCHARGING = 2
    NOT_CHARGING = 3
    FULL = 4


class BatteryState(Msg):
    header: Header = Field(default_factory=Header)
    voltage: float = Field(default=0.0, ge=0.0)
    current: float = 0.0
    charge: float = Field(default=0.0, ge=0.0, description="Ah")
    capacity: float = Field(default=0.0, ge=0.0, description="Ah")
    percentage: float = Field(default=1.0, ge=0.0, le=1.0, description="0..1")
    power_supply_status: PowerSupplyStatus = PowerSupplyStatus.UNKNOWN
    present: bool = True


class TrackingFeedback(Msg):
    """Nav2's ``nav2_msgs/TrackingFeedback``: how well the controller follows the
    path (published on ``{ns}/tracking_feedback`` each control cycle; read by
    IsWithinPathTrackingBounds)."""

    __bt_type_name__: ClassVar[str] = "nav2_msgs::msg::TrackingFeedback"

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    current_path_index: int = Field(default=0, ge=0)
    cross_track_error: float = Field(default=0.0, description="m, > 0: robot left of the path")
    heading_error: float = Field(default=0.0, description="rad, robot yaw - path tangent")
    distance_to_goal: float = Field(default=0.0, ge=0.0)
    remaining_path_length: float = Field(default=0.0, ge=0.0)
    robot_position: Point = Field(default_factory=Point)


class WaypointState(IntEnum):
    """``nav2_msgs/WaypointStatus`` states."""

    PENDING = 0
    COMPLETED = 1
    SKIPPED = 2
    FAILED = 3


class WaypointStatus(Msg):
    """Nav2's ``nav2_msgs/WaypointStatus``: what became of one waypoint of a multi-goal
    navigation (RemovePassedGoals marks the passed ones COMPLETED)."""

    __bt_type_name__: ClassVar[str] = "nav2_msgs::msg::WaypointStatus"

    waypoint_status: WaypointState = WaypointState.PENDING
    waypoint_index: int = Field(default=0, ge=0)
    waypoint_pose: PoseStamped = Field(default_factory=PoseStamped)
    error_code: int = Field(default=0, ge=0)
    error_msg: str = ""
