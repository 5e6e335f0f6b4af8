"""The pose estimate as AMCL publishes it: the mean of the heaviest cluster of
particles, with the covariance of the whole set (``pf_cluster_stats`` and
``getMaxWeightHyp``).

Clusters are connected groups of occupied histogram bins (the KLD bins; bins
touching in x, y or heading, the heading wrapping around), found with one
labelling of the dense bin grid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy import ndimage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from .kld import BIN_SIZE, bin_keys
from .se2 import FloatArray

YAW_BINS = int(np.ceil(2.0 * np.pi / BIN_SIZE[2]))  # 36
_NEIGHBOURS = np.ones((3, 3, 3), dtype=bool)


@dataclass(slots=True, frozen=True)
class Estimate:
    """``mean`` (x, y, yaw) of the heaviest cluster; ``covariance`` 3x3 of the set
    (x, y block and the circular variance of the heading); ``clusters`` found and
    the heaviest one's share of the weight."""

    mean: FloatArray
    covariance: FloatArray
    clusters: int
    weight: float


def cluster_labels(particles: FloatArray) -> tuple[npt.NDArray[np.intp], int]:
    """The cluster of each particle (0..count-1) and the count."""
    keys = bin_keys(particles)
    keys[:, 2] = np.mod(keys[:, 2], YAW_BINS)
    low = keys.min(axis=0)
    low[2] = 0
    idx = keys - low
    shape = (int(idx[:, 0].max()) + 1, int(idx[:, 1].max()) + 1, YAW_BINS + 1)
    grid = np.zeros(shape, dtype=bool)
    grid[idx[:, 0], idx[:, 1], idx[:, 2]] = True
    grid[:, :, YAW_BINS] = grid[:, :, 0]  # a copy of the first heading bin: wrap-around
    labels, count = ndimage.label(grid, structure=_NEIGHBOURS)
    # the copy and the original are one bin: join the labels they carry
    a, b = labels[:, :, 0].ravel(), labels[:, :, YAW_BINS].ravel()
    pairs = a > 0
    graph = coo_matrix(
        (np.ones(int(pairs.sum())), (a[pairs], b[pairs])), shape=(count + 1, count + 1)
    )
    _, merged = connected_components(graph, directed=False)
    used, cluster_of_label = np.unique(merged[1:], return_inverse=True)
    per_particle = labels[idx[:, 0], idx[:, 1], idx[:, 2]]
    return cluster_of_label[per_particle - 1], len(used)


def estimate(particles: FloatArray, weights: FloatArray) -> Estimate:
    """The estimate of a weighted particle set (weights need not be normalised)."""
    w = weights / weights.sum()
    labels, count = cluster_labels(particles)
    cluster_weight = np.bincount(labels, weights=w, minlength=count)
    best = int(np.argmax(cluster_weight))
    mine = labels == best
    wb = w[mine] / cluster_weight[best]
    pb = particles[mine]
    yaw = np.arctan2(np.sum(wb * np.sin(pb[:, 2])), np.sum(wb * np.cos(pb[:, 2])))
    mean = np.array([np.sum(wb * pb[:, 0]), np.sum(wb * pb[:, 1]), yaw])
    return Estimate(mean, set_covariance(particles, w), count, float(cluster_weight[best]))


def set_covariance(particles: FloatArray, w: FloatArray) -> FloatArray:
    """x, y covariance and ``-2 ln R`` for the heading (R the mean resultant length)."""
    xy = particles[:, :2]
    centred = xy - w @ xy
    cov = np.zeros((3, 3))
    cov[:2, :2] = (centred * w[:, np.newaxis]).T @ centred
    resultant = np.hypot(w @ np.cos(particles[:, 2]), w @ np.sin(particles[:, 2]))
    cov[2, 2] = -2.0 * np.log(max(float(resultant), 1e-300))
    return cov
