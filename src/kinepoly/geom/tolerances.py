"""Every tolerance of kinepoly, named, in one place."""

__all__ = [
    "ASSEMBLY_REL_TOL",
    "COINCIDENT_SIN",
    "COLLINEAR_SIN",
    "LOUD_ERROR",
    "NEAR_SINGULAR_SIN",
    "PARALLEL_SIN",
    "UNIT_ROUNDOFF",
]

UNIT_ROUNDOFF = 2.0**-53
"""u: half the spacing of doubles near 1."""

PARALLEL_SIN = 1e-12
"""Two construction lines whose angle has a sine below this are parallel: no finite crossing."""

NEAR_SINGULAR_SIN = 1e-4
"""Below this sine two construction lines still cross, with a near-singular warning."""

COLLINEAR_SIN = 0.2
"""An image triangle flatter than this is built by proportional division instead of two angles."""

ASSEMBLY_REL_TOL = 1e-12
"""Relative slack allowed when a circle just touches another circle or a line (a dead point)."""

COINCIDENT_SIN = 1e-10
"""Two points (or two lines) whose unit homogeneous vectors in a local frame make an angle with a
sine below this are one point (one line): no line runs through them (they meet in no one point)."""

LOUD_ERROR = 1e-9
"""A construction that disagrees with the analytic solution by more than this is reported loudly."""
