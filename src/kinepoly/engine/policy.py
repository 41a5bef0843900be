"""What the executor asks an assembly policy (``engine.assembly`` has the two policies)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

from kinepoly.engine.cam_contact import Candidates, Ints
from kinepoly.engine.closures import Choice, Closure
from kinepoly.engine.groups import CamGroup, NewtonGroup
from kinepoly.engine.placement import Placement
from kinepoly.geom.arrays import Bools
from kinepoly.model.mechanism import Mechanism
from kinepoly.notice import Notice

__all__ = ["Policy"]


class Policy(Protocol):
    """What the executor asks an assembly policy (``engine.assembly`` has the two policies)."""

    def choose(self, mechanism: Mechanism, closure: Closure, placed: Placement,
               later: Callable[[int], Placement]) -> Choice | Placement:
        """The assembly each row takes, or, having carried the assemblies through the later groups
        with ``later``, the whole placement."""

    def newton(self, mechanism: Mechanism, group: NewtonGroup, placed: Placement) -> Placement:
        """Place a group that is not a dyad, starting each row where the policy says."""

    def failed(self, mechanism: Mechanism, closure: Closure, rows: Bools) -> None:
        """Rows where a dyad does not close: a solve raises here, a sweep marks them."""

    def contact(self, mechanism: Mechanism, group: CamGroup, candidates: Candidates,
                placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """The contact of a spline cam each row keeps (-1 where it has none), with any warning."""

    def unreachable(self, message: str) -> None:
        """Rows where a spline cam's follower cannot touch its profile: a solve raises, a sweep marks them."""
