import numpy as np
import pytest

from aiobt_services.localization.initial_pose import (
    DEFAULT_COVARIANCE,
    InitialPoseError,
    checked,
    covariance_from_6x6,
    sample,
)

from .maps import field


def test_covariance_from_ros_6x6_takes_x_y_and_yaw() -> None:
    six = np.zeros((6, 6))
    six[0, 0], six[1, 1], six[5, 5], six[0, 1], six[1, 0] = 0.1, 0.2, 0.3, 0.01, 0.01
    np.testing.assert_allclose(
        covariance_from_6x6(six.ravel()), [[0.1, 0.01, 0], [0.01, 0.2, 0], [0, 0, 0.3]]
    )
    with pytest.raises(InitialPoseError, match="36 entries"):
        covariance_from_6x6([0.0] * 9)


@pytest.mark.parametrize(
    ("pose", "cov", "message"),
    [
        ((10.0, 1.0, 0.0), DEFAULT_COVARIANCE, "off the map"),
        ((0.01, 1.0, 0.0), DEFAULT_COVARIANCE, "wall"),
        ((1.0, float("nan"), 0.0), DEFAULT_COVARIANCE, "not finite"),
        ((1.0, 1.0, 0.0), np.diag([0.1, 0.0, 0.1]), "not positive definite"),
        ((1.0, 1.0, 0.0), np.diag([0.1, -1.0, 0.1]), "not positive definite"),
        ((1.0, 1.0, 0.0), np.diag([0.1, np.nan, 0.1]), "finite 3x3"),
    ],
)
def test_bad_initial_poses_are_refused_naming_the_source(
    pose: tuple[float, float, float], cov: np.ndarray, message: str
) -> None:
    with pytest.raises(InitialPoseError, match=message) as err:
        checked(*pose, cov, field(), "robot/initialpose")
    assert str(err.value).startswith("robot/initialpose: ")


def test_particles_follow_the_given_gaussian() -> None:
    pose = checked(1.0, 2.0, 3.1, np.diag([0.04, 0.01, 0.0025]), field(), "t")
    drawn = sample(pose, 20000, np.random.default_rng(0))
    np.testing.assert_allclose(drawn[:, :2].std(axis=0), [0.2, 0.1], rtol=0.03)
    assert np.all((drawn[:, 2] >= -np.pi) & (drawn[:, 2] < np.pi))  # wrapped across pi
