"""Accuracy: a local frame for the solve, error estimates from the conditioning, warnings.

* ``frame``: the scene re-anchored near its own points, so translation costs no accuracy;
* ``estimate``: the estimated relative error of each kind of quantity (u, k, crossing angles);
* ``conditions``: ``transmission-angle`` and ``near-singular`` warnings, singular positions;
* ``summary``: every quantity with its construction and analytic value, difference, estimate.
"""

from kinepoly.accuracy.conditions import (
    MIN_TRANSMISSION_DEG,
    NEAR_SINGULAR_ERROR,
    Transmission,
    near_singular_notice,
    singular_position_error,
    transmission_angles,
    transmission_notices,
)
from kinepoly.accuracy.estimate import ErrorEstimate, componentwise_error, estimate_errors, normwise_error
from kinepoly.accuracy.frame import LocalFrame, localize
from kinepoly.accuracy.summary import AccuracyReport, QuantityError, assess

__all__ = [
    "MIN_TRANSMISSION_DEG",
    "NEAR_SINGULAR_ERROR",
    "AccuracyReport",
    "ErrorEstimate",
    "LocalFrame",
    "QuantityError",
    "Transmission",
    "assess",
    "componentwise_error",
    "estimate_errors",
    "localize",
    "near_singular_notice",
    "normwise_error",
    "singular_position_error",
    "transmission_angles",
    "transmission_notices",
]
