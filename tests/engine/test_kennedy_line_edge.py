"""The circle diagram's line edges: a higher pair known at once as a line (its common normal), not a point.

Planning only (no geometry): a line edge needs one triangle whose two other edges are known points, a point
two; only the centers on the path to the asked ones are derived. The geometry is tested against the velocity
poles in ``tests/engine/test_cam_line_edge.py``.
"""

from __future__ import annotations

from kinepoly.engine.circle_diagram import plan_kennedy


def test_a_line_edge_closes_with_one_triangle() -> None:
    links = ("1", "2", "3")
    pins = frozenset({("1", "2"), ("1", "3")})
    plan = plan_kennedy(links, pins, (("2", "3"),), frozenset({("2", "3")}))
    assert plan.order == (("2", "3"),) and plan.chosen[("2", "3")] == ("1",)
    assert plan.sides(("2", "3")) == (("1", "2"), ("1", "3")) and not plan.unreachable
    # the same edge as a point would need two triangles: three links have only one
    plan = plan_kennedy(links, pins, (("2", "3"),))
    assert plan.order == () and plan.unreachable == (("2", "3"),)


def test_a_cam_on_a_coupler_first_needs_the_couplers_center() -> None:
    """Cam 2 on the frame, its follower 3 a coupler held by rockers 4 and 5: I23 needs I13 first (triangles
    134 and 135), then the line I12 I13 crossed with the common normal; I45, not on the path, is not planned."""
    links = ("1", "2", "3", "4", "5")
    pins = frozenset({("1", "2"), ("1", "4"), ("1", "5"), ("3", "4"), ("3", "5")})
    plan = plan_kennedy(links, pins, (("2", "3"),), frozenset({("2", "3")}))
    assert plan.order == (("1", "3"), ("2", "3"))
    assert plan.chosen == {("1", "3"): ("4", "5"), ("2", "3"): ("1",)}
    # asking I24 goes through I23: the line edge found, it is an ordinary known center
    plan = plan_kennedy(links, pins, (("2", "4"),), frozenset({("2", "3")}))
    assert plan.order == (("1", "3"), ("2", "3"), ("2", "4"))
    assert set(plan.chosen[("2", "4")]) == {"1", "3"}


def test_a_line_edge_that_is_also_a_joint_is_a_point() -> None:
    plan = plan_kennedy(("1", "2", "3"), frozenset({("1", "2"), ("2", "3")}), (("2", "3"),), frozenset({("2", "3")}))
    assert plan.order == () and plan.lines == frozenset() and not plan.unreachable
