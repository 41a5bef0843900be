"""Which of a dyad's two assemblies each row takes, followed continuously from the seed row.

The rule, row after row away from the seed in both directions: take the assembly whose
telling point (the inner joint, say) lies nearest to where the last two rows point, that is
to 2 p[k-1] - p[k-2] (nearest to p[k-1] when only one row is behind). Extrapolating, not
just taking the nearest, is what carries a parallelogram through its change points, where
both assemblies meet and part again: the parallelogram's joint keeps its course and never
flips to the anti-parallelogram.

Where the dyad cannot be assembled the rows are skipped, and the sweep resumes beyond on the
assembly with the same label (the same side of the line, or the same end of the slide) as
before the gap; the caller reports that no motion connects the two sides.

The rule is sequential, but the answer only changes where the two assemblies come near each
other. Those rows are found with array operations (``keep``: with two rows of one label
behind, would the rule keep that label?); the walk jumps over every stretch where it would,
and steps row by row only at the few rows where it might not.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from msgspec import Struct

from kinepoly.geom.arrays import Bools, Points, Reals

__all__ = ["Labels", "follow_branch", "follow_members"]

Labels = npt.NDArray[np.int8]


def _keep(c: tuple[Points, Points], label: int) -> Bools:
    """keep[k]: with rows k-2 and k-1 on ``label``, the rule keeps ``label`` at row k (k >= 2)."""
    own, other = c[label], c[1 - label]
    out = np.zeros(len(own), np.bool_)
    if len(own) > 2:
        predicted = 2.0 * own[1:-1] - own[:-2]
        out[2:] = np.abs(own[2:] - predicted) <= np.abs(other[2:] - predicted)
    return out


class _Walk(Struct):
    """One walk along a sequence of rows (seed first): labels in sequence order."""

    c: tuple[Points, Points]
    ok: Bools
    labels: Labels

    def run(self, start: int, label: int, stop_at_gap: bool, end: int) -> int:
        """Walk rows start..end-1 of the sequence (row ``start`` takes ``label``); return where it stopped."""
        c, ok = self.c, self.ok
        bad = [np.flatnonzero(~(_keep(c, lab) & ok)) for lab in (0, 1)]
        history: list[tuple[int, complex]] = []
        k = start
        while k < end:
            if not ok[k]:
                if stop_at_gap:
                    return k
                later = np.flatnonzero(ok[k:end])
                if later.size == 0:
                    self.labels[k:end] = label
                    return end
                j = k + int(later[0])
                self.labels[k:j] = label
                history, k = [], j
                continue
            if len(history) == 2 and history[0][0] == history[1][0] == label:
                positions = bad[label]
                nxt = positions[np.searchsorted(positions, k)] if positions.size and positions[-1] >= k else end
                nxt = min(int(nxt), end)
                if nxt > k:
                    self.labels[k:nxt] = label
                    history = [(label, complex(c[label][nxt - 2])), (label, complex(c[label][nxt - 1]))]
                    k = nxt
                    continue
            if history:
                last = history[-1][1]
                predicted = last if len(history) == 1 else 2.0 * last - history[-2][1]
                mine, theirs = abs(complex(c[label][k]) - predicted), abs(complex(c[1 - label][k]) - predicted)
                if theirs < mine:
                    label = 1 - label
            self.labels[k] = label
            history = [*history[-1:], (label, complex(c[label][k]))]
            k += 1
        return end


def _walk(c: tuple[Points, Points], ok: Bools, order: npt.NDArray[np.intp], label: int,
          stop_at_gap: bool) -> tuple[Labels, int]:
    walk = _Walk((c[0][order], c[1][order]), ok[order], np.full(len(order), label, np.int8))
    stop = walk.run(0, label, stop_at_gap, len(order))
    return walk.labels, stop


def follow_branch(c0: Points, c1: Points, ok: Bools, seed: int, label: int, periodic: bool,
                  gap: Reals | None = None) -> int | Labels:
    """The label of every row (one int when every row keeps the seed's), the seed row ``seed`` on
    ``label``; ``c0``, ``c1`` the telling points, ``gap`` their distance where the caller knows it.

    ``periodic``: the rows are a full turn of the input, so the last row neighbours the first;
    the walk then goes round both ways from the seed until it meets a gap, and the rows beyond
    the gaps are walked forward, resuming on the label of the last row before them.
    """
    n = len(c0)
    c = (c0, c1)
    if _no_switch_possible(c, ok, periodic, label, gap):
        return label
    labels = np.full(n, label, np.int8)
    if not periodic:
        for order in (np.arange(seed, n), np.arange(seed, -1, -1)):
            labels[order] = _walk(c, ok, order, label, stop_at_gap=False)[0]
        return labels
    forward = (seed + np.arange(n)) % n
    ahead, stop = _walk(c, ok, forward, label, stop_at_gap=True)
    labels[forward[:stop]] = ahead[:stop]
    if stop == n:
        return labels
    backward = (seed - np.arange(n)) % n
    behind, back_stop = _walk(c, ok, backward, label, stop_at_gap=True)
    labels[backward[:back_stop]] = behind[:back_stop]
    rest = forward[stop:n - back_stop + 1] if back_stop > 0 else forward[stop:]
    if rest.size:
        last = int(ahead[stop - 1]) if stop > 0 else label
        labels[rest] = _walk(c, ok, rest, last, stop_at_gap=False)[0]
    return labels


def _no_switch_possible(c: tuple[Points, Points], ok: Bools, periodic: bool, label: int,
                        gap: Reals | None) -> bool:
    """True when every step of the seed's label is shorter than a quarter of the gap between the
    two assemblies: then, with p[k-1] and p[k-2] on that label, the prediction misses its point
    by at most two steps and the other point by at least the gap less that, so the rule never
    switches (and the rows beyond a gap resume on it too)."""
    every = bool(np.logical_and.reduce(ok))  # ok.all(), and the reductions below, without their Python wrappers
    if not every and not ok.any():
        return True
    own = c[label]
    step = own[1:] - own[:-1]  # np.diff's own subtraction, without its Python wrapper
    step2 = step.real * step.real
    step2 += step.imag * step.imag
    if not every:
        step2 = step2[ok[1:] & ok[:-1]]
    longest2 = float(np.maximum.reduce(step2)) if step2.size else 0.0
    if periodic and ok[0] and ok[-1]:
        longest2 = max(longest2, abs(complex(own[0]) - complex(own[-1])) ** 2)
    if gap is None:
        gap = np.abs(c[0] - c[1])
    shortest = float(np.minimum.reduce(gap if every else gap[ok]))
    return bool(16.0 * longest2 < shortest * shortest)


def follow_members(c0: Points, c1: Points, ok: Bools, rows_each: int, seed: int, label: int, periodic: bool,
                   gap: Reals | None = None) -> int | Labels:
    """``follow_branch`` for a family (``model.family``): the rows are its members' rows one member after
    another, ``rows_each`` each, and every member's row ``seed`` takes ``label``. Each member is followed on
    its own rows; the members whose steps are all short of a quarter of their assemblies' gap (the rule keeps
    the label there, as ``_no_switch_possible`` says for one member) are settled together by array operations."""
    members = len(c0) // rows_each
    every = bool(ok.all())
    own = (c0 if label == 0 else c1).reshape(members, rows_each)
    fine = ok.reshape(members, rows_each)
    step = own[:, 1:] - own[:, :-1]
    step2 = step.real * step.real
    step2 += step.imag * step.imag
    if not every:
        step2 = np.where(fine[:, 1:] & fine[:, :-1], step2, 0.0)
    longest2 = step2.max(axis=1) if rows_each > 1 else np.zeros(members)
    if periodic:
        wrap = own[:, 0] - own[:, -1]
        longest2 = np.where(fine[:, 0] & fine[:, -1],
                            np.maximum(longest2, wrap.real * wrap.real + wrap.imag * wrap.imag), longest2)
    apart = (np.abs(c0 - c1) if gap is None else np.broadcast_to(gap, c0.shape)).reshape(members, rows_each)
    shortest = (apart if every else np.where(fine, apart, np.inf)).min(axis=1)
    settled = ~fine.any(axis=1) | (16.0 * longest2 < shortest * shortest)
    if settled.all():
        return label
    labels = np.full(len(c0), label, np.int8)
    for member in np.flatnonzero(~settled):
        rows = slice(member * rows_each, (member + 1) * rows_each)
        found = follow_branch(c0[rows], c1[rows], ok[rows], seed, label, periodic,
                              None if gap is None else apart[member])
        labels[rows] = found
    return labels
