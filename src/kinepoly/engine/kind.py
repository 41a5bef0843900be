"""What every group kind gives the drivers: four functions, the same for each kind (``engine.table``).

- ``find``: the next group of this kind among the links not yet known, or None (``engine.plan``);
- ``place``: its links' poses at every row on top of what is placed, as the assembly policy decides;
  given the placing of the groups after it (``later``), for a kind whose assemblies the policy may carry
  through them; True with the placement when it placed those later groups too (``engine.position``);
- ``velocity``: its tips, rates and sliding velocities in the velocity polygon (``engine.velocity``);
- ``acceleration``: the same in the acceleration polygon (``engine.acceleration``);

and ``batched``: whether a family's members (``model.family``) are placed by the kind in one batch, its group closed
in a form whose dimensions may differ from row to row (it answers the policy's ``by_label``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Generic, TypeVar

from msgspec import Struct

from kinepoly.engine.placement import Placement
from kinepoly.engine.policy import Policy
from kinepoly.engine.results import AccelerationContext, VelocityContext
from kinepoly.model.mechanism import Mechanism

__all__ = ["Kind", "Later", "Placed"]

G = TypeVar("G")

Later = Callable[[Placement], Placement]
"""Place the groups after this one on top of a placement."""

Placed = tuple[Placement, bool]
"""The placement, and whether the groups after this one are placed in it too."""


class Kind(Struct, Generic[G], frozen=True):
    """The four functions of one group kind (see the module)."""

    find: Callable[[Mechanism, set[str]], G | None]
    place: Callable[[Mechanism, G, Placement, Policy, Later], Placed]
    velocity: Callable[[VelocityContext, G], None]
    acceleration: Callable[[AccelerationContext, G], None]
    batched: bool = False
