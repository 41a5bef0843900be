"""A link's pose over rows (``ArrayPose``) against the one-row pose (``LinkPose``) written with cos and sin.

The two are written independently: ``LinkPose`` turns a point by the rotation matrix of theta, ``ArrayPose``
multiplies by the unit complex e^(i theta). Row k of the array pose must be the row pose at theta_k.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from kinepoly.model.array_pose import ArrayPose, pose_from_point, pose_from_two_points, still_pose
from kinepoly.model.pose import LinkPose

coordinate = st.floats(-500.0, 500.0, allow_nan=False)
angle = st.floats(-3.0 * math.pi, 3.0 * math.pi, allow_nan=False)
poses = st.lists(st.tuples(coordinate, coordinate, angle), min_size=1, max_size=8)
point = st.tuples(coordinate, coordinate)


def _close(a: complex, b: tuple[float, float], scale: float) -> bool:
    return abs(a - complex(*b)) <= 1e-12 * scale


@settings(max_examples=60, deadline=None)
@given(poses, point)
def test_each_row_places_a_point_as_the_row_pose_does(rows: list[tuple[float, float, float]],
                                                         local: tuple[float, float]) -> None:
    array = ArrayPose.of_rows([LinkPose(*r) for r in rows])
    world = array.world(local)
    scale = 1.0 + sum(abs(v) for r in rows for v in r[:2]) + abs(local[0]) + abs(local[1])
    for k, r in enumerate(rows):
        assert _close(complex(world[k]), LinkPose(*r).world(local), scale)
        back = array.to_local(world)[k]
        assert abs(back - complex(*local)) <= 1e-12 * scale


@settings(max_examples=60, deadline=None)
@given(poses)
def test_theta_is_the_rows_angle_in_the_half_open_range(rows: list[tuple[float, float, float]]) -> None:
    array = ArrayPose.of_rows([LinkPose(*r) for r in rows])
    radians, degrees = array.theta(), array.theta(degrees=True)
    for k, (_x, _y, theta) in enumerate(rows):
        assert -math.pi < radians[k] <= math.pi
        # the same direction: the difference a whole number of turns
        turns = (theta - radians[k]) / (2.0 * math.pi)
        assert abs(turns - round(turns)) <= 1e-12 * (1.0 + abs(theta))
        assert abs(degrees[k] - math.degrees(radians[k])) <= 1e-9
        x, y, t = array.row(k)
        assert (x, y) == (rows[k][0], rows[k][1]) or math.hypot(x - rows[k][0], y - rows[k][1]) <= 1e-12 * (
            1.0 + abs(rows[k][0]) + abs(rows[k][1]))
        assert abs(math.remainder(t - theta, 2.0 * math.pi)) <= 1e-12 * (1.0 + abs(theta))


def test_a_direction_exactly_at_minus_pi_reads_as_plus_pi() -> None:
    array = ArrayPose(np.zeros(2, np.complex128), np.array([complex(-1.0, -0.0), complex(0.0, 1.0)]))
    assert array.theta()[0] == math.pi and array.theta(degrees=True)[0] == 180.0


@settings(max_examples=60, deadline=None)
@given(point, point, point, st.floats(0.1, 300.0), angle, st.booleans())
def test_two_points_put_a_on_its_place_and_b_on_the_ray(local_a: tuple[float, float], local_b: tuple[float, float],
                                                        world_a: tuple[float, float], span: float, direction: float,
                                                        rigid: bool) -> None:
    local = complex(local_b[0] - local_a[0], local_b[1] - local_a[1])
    if abs(local) < 1e-3:
        return
    if rigid:
        span = abs(local)  # the caller's promise: world_b is at the link's own length from world_a
    wa = complex(*world_a)
    wb = wa + span * complex(math.cos(direction), math.sin(direction))
    pose = pose_from_two_points(local_a, local_b, np.array([wa]), np.array([wb]), rigid=rigid)
    scale = 1.0 + abs(wa) + abs(local) + span + abs(complex(*local_a))
    assert abs(pose.world(local_a)[0] - wa) <= 1e-12 * scale
    assert abs(abs(pose.rotation[0]) - 1.0) <= 1e-12
    b = pose.world(local_b)[0]
    # b lies on the ray from a towards world_b, at the link's own distance
    assert abs(abs(b - wa) - abs(local)) <= 1e-12 * scale
    ray = (b - wa) / abs(b - wa)
    assert abs(ray - (wb - wa) / abs(wb - wa)) <= 1e-12 * scale


@given(point, point, angle)
def test_a_pose_from_one_point_puts_it_there(local: tuple[float, float], world: tuple[float, float],
                                             theta: float) -> None:
    rotation = np.array([complex(math.cos(theta), math.sin(theta))])
    pose = pose_from_point(local, np.array([complex(*world)]), rotation)
    scale = 1.0 + abs(complex(*world)) + abs(complex(*local))
    assert abs(pose.world(local)[0] - complex(*world)) <= 1e-12 * scale


def test_the_frame_leaves_every_point_where_it_is() -> None:
    frame = still_pose(3)
    assert frame.still
    assert list(frame.world((12.5, -4.0))) == [complex(12.5, -4.0)] * 3
    assert list(frame.theta()) == [0.0, 0.0, 0.0]
