"""Nav2's action error-code tables (``nav2_msgs/action/*.action``), same numbers.

``NONE`` (0) is success everywhere. Each table starts at its server's
``UNKNOWN`` code, so a code alone says which server failed (Nav2's
``error_code_names`` aggregation relies on that).
"""

from __future__ import annotations

from enum import IntEnum


class FollowPathError(IntEnum):
    NONE = 0
    UNKNOWN = 100
    INVALID_CONTROLLER = 101
    TF_ERROR = 102
    INVALID_PATH = 103
    PATIENCE_EXCEEDED = 104
    FAILED_TO_MAKE_PROGRESS = 105
    NO_VALID_CONTROL = 106
    CONTROLLER_TIMED_OUT = 107


class ComputePathToPoseError(IntEnum):
    NONE = 0
    UNKNOWN = 200
    INVALID_PLANNER = 201
    TF_ERROR = 202
    START_OUTSIDE_MAP = 203
    GOAL_OUTSIDE_MAP = 204
    START_OCCUPIED = 205
    GOAL_OCCUPIED = 206
    TIMEOUT = 207
    NO_VALID_PATH = 208


class ComputePathThroughPosesError(IntEnum):
    NONE = 0
    UNKNOWN = 300
    INVALID_PLANNER = 301
    TF_ERROR = 302
    START_OUTSIDE_MAP = 303
    GOAL_OUTSIDE_MAP = 304
    START_OCCUPIED = 305
    GOAL_OCCUPIED = 306
    TIMEOUT = 307
    NO_VALID_PATH = 308
    NO_VIAPOINTS_GIVEN = 309


class SmoothPathError(IntEnum):
    NONE = 0
    UNKNOWN = 500
    INVALID_SMOOTHER = 501
    TIMEOUT = 502
    SMOOTHED_PATH_IN_COLLISION = 503
    FAILED_TO_SMOOTH_PATH = 504
    INVALID_PATH = 505


class SpinError(IntEnum):
    NONE = 0
    UNKNOWN = 700
    TIMEOUT = 701
    TF_ERROR = 702
    COLLISION_AHEAD = 703


class BackUpError(IntEnum):
    NONE = 0
    UNKNOWN = 710
    TIMEOUT = 711
    TF_ERROR = 712
    INVALID_INPUT = 713
    COLLISION_AHEAD = 714


class DriveOnHeadingError(IntEnum):
    NONE = 0
    UNKNOWN = 720
    TIMEOUT = 721
    TF_ERROR = 722
    COLLISION_AHEAD = 723
    INVALID_INPUT = 724


class AssistedTeleopError(IntEnum):
    NONE = 0
    UNKNOWN = 730
    TIMEOUT = 731
    TF_ERROR = 732


class WaitError(IntEnum):
    NONE = 0
    UNKNOWN = 740
    TIMEOUT = 741


class ComputeRouteError(IntEnum):
    """nav2_msgs ComputeRoute / ComputeAndTrackRoute (the route server)."""

    NONE = 0
    UNKNOWN = 400
    TF_ERROR = 401
    NO_VALID_GRAPH = 402
    INDETERMINANT_NODES_ON_GRAPH = 403
    TIMEOUT = 404
    NO_VALID_ROUTE = 405
    OPERATION_FAILED = 406  # ComputeAndTrackRoute only
    INVALID_EDGE_SCORER_USE = 407


class ComputeCoveragePathError(IntEnum):
    """opennav_coverage's table (it has no UNKNOWN; 803 has two names there)."""

    NONE = 0
    INTERNAL_F2C_ERROR = 801
    INVALID_MODE_SET = 802
    INVALID_REQUEST = 803
    INVALID_COORDS = 803


class NavigateToPoseError(IntEnum):
    NONE = 0
    UNKNOWN = 9000
    FAILED_TO_LOAD_BEHAVIOR_TREE = 9001
    TF_ERROR = 9002
    TIMEOUT = 9003


class NavigateThroughPosesError(IntEnum):
    NONE = 0
    UNKNOWN = 9100
    FAILED_TO_LOAD_BEHAVIOR_TREE = 9101
    TF_ERROR = 9102
    TIMEOUT = 9103
