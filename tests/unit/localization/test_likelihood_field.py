import numpy as np
import pytest

from aiobt_services.localization.likelihood_field import LikelihoodField, MapError

from .maps import RES, field, room


def test_hit_term_falls_with_the_distance_to_the_nearest_wall_and_is_capped() -> None:
    f = field()
    on_wall = f.hit_terms(np.array([0.025]), np.array([1.0]))[0]  # the left wall's cell
    half_metre = f.hit_terms(np.array([0.525]), np.array([3.0]))[0]  # 0.5 m from it
    assert on_wall == pytest.approx(0.5)  # z_hit * exp(0)
    assert half_metre == pytest.approx(0.5 * np.exp(-(0.5**2) / (2 * 0.2**2)), rel=1e-3)
    off = f.hit_terms(np.array([-5.0]), np.array([1.0]))[0]
    assert off == pytest.approx(0.5 * np.exp(-(2.0**2) / (2 * 0.2**2)))


def test_where_names_off_map_and_wall_poses() -> None:
    f = field()
    assert f.where(1.0, 1.0) == ""
    assert "off the map" in f.where(7.0, 1.0)
    assert "wall" in f.where(0.01, 1.0)


def test_random_free_poses_are_all_in_free_cells_and_cover_headings() -> None:
    f = field()
    poses = f.random_free_poses(5000, np.random.default_rng(0))
    col = np.floor(poses[:, 0] / RES).astype(int)
    row = np.floor(poses[:, 1] / RES).astype(int)
    assert np.all(f.cells[row, col] == 0)
    assert poses[:, 2].min() < -3.0
    assert poses[:, 2].max() > 3.0


def test_a_map_without_free_cells_is_refused() -> None:
    with pytest.raises(MapError, match="no free cell"):
        LikelihoodField.build(
            np.full((4, 4), 100, np.int8), RES, (0, 0), max_dist=2, z_hit=0.5, sigma_hit=0.2
        )
    with pytest.raises(MapError, match="resolution"):
        LikelihoodField.build(room(), 0.0, (0, 0), max_dist=2, z_hit=0.5, sigma_hit=0.2)
