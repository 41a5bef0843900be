"""Assembly policies: which of a group's assemblies each row takes, and what a row that fails means.

The executor (``engine.position``) and the group kinds ask a policy two kind-neutral questions:

- ``assemble(mechanism, question, placed)``: a group's assemblies, put as a ``Question`` that the group's kind
  answers for each policy in its own way (a dyad's two closed-form assemblies, a cam's contacts, a Newton group's
  start at every row);
- ``cannot_close(error)``: rows of a group do not close; ``error`` makes the error that says why.

Three policies:

- ``NearestGuess``, for a solve (a batch of one row): the assembly whose points lie nearest the ``[guess]``
  (where nothing tells the assemblies apart, the documented default with a ``default-assembly`` warning); a
  group that does not close raises its error.
- ``Continuity``, for a sweep: the seed row takes the solve's assembly and every other row follows it
  continuously; rows that do not close are marked, not raised.
- ``FamilyContinuity``, for a family of mechanisms (``model.family``; its rows are the members' rows, one member
  after another): every member's seed row takes the assembly the scene's own solve takes, by label, and follows
  it over the member's rows.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Protocol, TypeVar

from msgspec import Struct, field

from kinepoly.engine.placement import Placement
from kinepoly.errors import KinepolyError
from kinepoly.geom.arrays import Reals
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose

__all__ = ["Continuity", "FamilyContinuity", "NearestGuess", "Policy", "Question", "guess_coordinate"]

Vec = tuple[float, float]
T = TypeVar("T", covariant=True)


class Question(Protocol[T]):
    """A group's assemblies, as its kind answers for each policy."""

    def by_guess(self, policy: NearestGuess, mechanism: Mechanism, placed: Placement) -> T:
        """The assembly nearest the policy's ``[guess]``."""

    def by_seed(self, policy: Continuity, mechanism: Mechanism, placed: Placement) -> T:
        """The seed row's assembly, followed over the rows."""

    def by_label(self, policy: FamilyContinuity, mechanism: Mechanism, placed: Placement) -> T:
        """Each member's assembly of the scene's label, followed over the member's rows."""


class Policy(Protocol):
    """What the executor and the group kinds ask a policy (see the module)."""

    def assemble(self, mechanism: Mechanism, question: Question[T], placed: Placement) -> T:
        """The group's assemblies at every row, as this policy takes them."""

    def cannot_close(self, error: Callable[[], KinepolyError]) -> None:
        """Rows of a group do not close: a solve raises ``error()``, a sweep marks them."""


class NearestGuess(Struct, frozen=True):
    """The solve's policy (row 0 of a batch of one): nearest the ``[guess]``."""

    guess: Mapping[str, Vec]
    origin: Vec = (0.0, 0.0)
    """Where the mechanism's frame origin lies in the user's frame, for messages."""

    def assemble(self, mechanism: Mechanism, question: Question[T], placed: Placement) -> T:
        return question.by_guess(self, mechanism, placed)

    def cannot_close(self, error: Callable[[], KinepolyError]) -> None:
        raise error()


class Continuity(Struct, frozen=True):
    """The sweep's policy: row ``seed_row`` takes the assembly of ``seed``; the others follow it.

    ``seed`` is the solve's positions at the seed row, or a function that solves them when asked: with ``guess``,
    a dyad whose inner joint is the only guessed point of its links takes, at the seed row, the assembly that
    puts the joint nearest its guess, as ``NearestGuess`` would, without solving the seed row apart; anything
    else asks for the seed.
    """

    seed_row: int
    seed: Mapping[str, LinkPose] | Callable[[], Mapping[str, LinkPose]]
    periodic: bool
    progress: Callable[[int, int], None] | None = None
    guess: Mapping[str, Vec] = field(default_factory=dict)
    run_only: bool = False
    """Only the run of rows about the seed row that close is wanted (a range's search, ``sweep.inputs``): a kind
    that walks row by row from the seed may stop each way at the first row that does not close, the rows beyond it
    left not closing."""

    def seed_poses(self) -> Mapping[str, LinkPose]:
        return self.seed() if callable(self.seed) else self.seed

    def assemble(self, mechanism: Mechanism, question: Question[T], placed: Placement) -> T:
        return question.by_seed(self, mechanism, placed)

    def cannot_close(self, error: Callable[[], KinepolyError]) -> None:
        """Rows that do not close are marked by the executor; nothing to raise."""


class FamilyContinuity(Struct, frozen=True):
    """A family's policy: every member's row ``seed_row`` (of its ``rows_each``) takes the assembly of the label
    the scene's own solve takes (found on ``base``, the scene's mechanism, at its solve's poses ``seed`` and its
    inputs' values ``values`` there), and the member's other rows follow it continuously; the dyads named in
    ``flipped`` take the other label (their other assembly, the groups after them placed on it)."""

    seed_row: int
    rows_each: int
    periodic: bool
    base: Mechanism
    seed: Mapping[str, LinkPose]
    values: tuple[Reals, ...]
    flipped: frozenset[str] = frozenset()

    def assemble(self, mechanism: Mechanism, question: Question[T], placed: Placement) -> T:
        return question.by_label(self, mechanism, placed)

    def cannot_close(self, error: Callable[[], KinepolyError]) -> None:
        """Rows that do not close are marked by the executor; nothing to raise."""


def guess_coordinate(local: float, origin: float) -> str:
    """A coordinate for a ``[guess]`` the messages propose: 4 significant digits of the mechanism's own size,
    wherever the mechanism is (``origin``: where its frame's origin lies in the user's frame)."""
    if origin == 0.0:
        return f"{local:.4g}"
    decimals = max(0, 3 - math.floor(math.log10(abs(local)))) if local != 0.0 else 2
    return f"{local + origin:.{decimals}f}"
