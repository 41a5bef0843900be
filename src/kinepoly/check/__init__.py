"""The check: an independent analytic solution, the comparison with it, and the accuracy estimates.

The analytic solution (shares no code with the construction):

* ``analytic``: :func:`solve_analytic`, the differentiated loop-closure equations solved;
* ``coordinates``, ``constraints``, ``newton``, ``start``, ``given``: its body coordinates,
  constraint equations, damped Newton and linear solves, start poses, a ``[given]`` body;
* ``compare``: every reported quantity against the analytic value (``CheckReport``).
* ``series``: the course text's approximate slider-crank (two terms of a binomial series) and the
  recognition of a slider-crank's links, for the bench and ``kinepoly sweep --series``.

Accuracy:

* ``frame``: the scene re-anchored near its own points, so translation costs no accuracy;
* ``estimate``: the estimated relative error of each kind of quantity (u, k, crossing angles);
* ``conditions``: ``transmission-angle`` and ``near-singular`` warnings, singular positions;
* ``summary``: every quantity with its construction and analytic value, difference, estimate.

The names below are imported when first used, so that importing one module of this package
(``kinepoly.check.analytic``, say) does not import the others.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from kinepoly.check.analytic import AnalyticSolution, solve_analytic
    from kinepoly.check.compare import CheckReport, Quantity
    from kinepoly.check.conditions import (
        MIN_TRANSMISSION_DEG,
        NEAR_SINGULAR_ERROR,
        near_singular_notice,
        singular_position_error,
        transmission_notices,
    )
    from kinepoly.check.estimate import ErrorEstimate, componentwise_error, estimate_errors, normwise_error
    from kinepoly.check.frame import LocalFrame, localize
    from kinepoly.check.summary import AccuracyReport, QuantityError, assess

_HOME = {
    "AnalyticSolution": "analytic", "solve_analytic": "analytic",
    "CheckReport": "compare", "Quantity": "compare",
    "MIN_TRANSMISSION_DEG": "conditions", "NEAR_SINGULAR_ERROR": "conditions",
    "near_singular_notice": "conditions", "singular_position_error": "conditions", "transmission_notices": "conditions",
    "ErrorEstimate": "estimate", "componentwise_error": "estimate", "estimate_errors": "estimate",
    "normwise_error": "estimate",
    "LocalFrame": "frame", "localize": "frame",
    "AccuracyReport": "summary", "QuantityError": "summary", "assess": "summary",
}

__all__ = [
    "MIN_TRANSMISSION_DEG",
    "NEAR_SINGULAR_ERROR",
    "AccuracyReport",
    "AnalyticSolution",
    "CheckReport",
    "ErrorEstimate",
    "LocalFrame",
    "Quantity",
    "QuantityError",
    "assess",
    "componentwise_error",
    "estimate_errors",
    "localize",
    "near_singular_notice",
    "normwise_error",
    "singular_position_error",
    "solve_analytic",
    "transmission_notices",
]


def __getattr__(name: str) -> Any:
    if name in _HOME:
        return getattr(importlib.import_module(f"kinepoly.check.{_HOME[name]}"), name)
    raise AttributeError(f"module 'kinepoly.check' has no attribute {name!r}")
