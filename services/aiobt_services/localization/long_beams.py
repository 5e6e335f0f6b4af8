"""Kidnap evidence that obstacles missing from the map cannot give (not Nav2's).

AMCL's recovery (:mod:`.recovery`) draws random particles when the scans fit the
particles worse than they used to. Obstacles that are not on the map cut the fit
too, and on a long drive past them the random particles take a robot that was
never lost to a look-alike place (``bench.localization.kidnap --corridor``). The
two differ in the *sign* of the error: an obstacle missing from the map makes a
beam shorter than the map predicts from the right pose (it stands in front of a
mapped wall), never longer; a wrong pose also makes beams longer than predicted
(the lidar sees free space where the map has a wall in front of the estimate).

:func:`long_beam_share` is the share of a scan's beams that reach more than
``margin`` beyond the first occupied cell the map has along them from a pose,
and end more than ``margin`` from every mapped obstacle (``far_term``: the
likelihood field's hit term there). The second half is for the other way a map
goes stale: an obstacle on the map that is gone (a crate moved away) lengthens
beams from the right pose too, but they end on the mapped wall behind it; from a
wrong pose most long beams end in the open. One ray march per beam (``max_beams``
of them) through the occupancy grid, in half-cell steps, vectorised over beams
and steps. :class:`.Amcl` computes it from the heaviest particle when the
recovery averages ask for random particles, and draws them only while it is at
least ``recovery_min_long_beams``.
"""

from __future__ import annotations

import numpy as np

from .laser_model import Beams
from .likelihood_field import OCCUPIED, LikelihoodField
from .se2 import FloatArray

MARGIN_SIGMAS = 2.0  # a beam is long when it reaches 2 sigma_hit past the map's wall


def long_beam_share(
    field: LikelihoodField,
    pose: FloatArray,
    beams: Beams,
    margin: float,
    far_term: float | None = None,
) -> float:
    """The share (0..1) of ``beams`` seen from ``pose`` (x, y, yaw in the map) that
    pass an occupied cell more than ``margin`` metres before their end and, with
    ``far_term``, end where the field's hit term is below it (away from every
    mapped obstacle); 0 without beams."""
    if beams.ranges.size == 0:
        return 0.0
    step = 0.5 * field.resolution
    reach = beams.ranges - margin  # a wall before this along the beam: the beam is long
    t = np.arange(step, max(float(reach.max()), step) + step, step)
    angle = pose[2] + beams.bearings
    x = pose[0] + np.outer(np.cos(angle), t)  # (beams, steps)
    y = pose[1] + np.outer(np.sin(angle), t)
    row, col, inside = field.cell_index(x, y)
    rows, cols = field.shape
    cells = field.cells[np.clip(row, 0, rows - 1), np.clip(col, 0, cols - 1)]
    wall = inside & (cells == OCCUPIED)
    long = np.any(wall & (t < reach[:, np.newaxis]), axis=1)
    if far_term is not None:
        ex = pose[0] + beams.ranges * np.cos(angle)
        ey = pose[1] + beams.ranges * np.sin(angle)
        long &= field.hit_terms(ex, ey) < far_term
    return float(np.count_nonzero(long)) / len(long)
