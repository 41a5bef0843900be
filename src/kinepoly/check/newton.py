"""The scaled constraint system, damped Newton for the position, and linear solves checked for their condition.

Position: damped Newton from a start pose; every linear solve is checked for its condition
first. The Jacobian is made dimensionless before it is judged or solved: theta columns are
multiplied by the mechanism's size L (theta * L is a length) and the angle rows by L.
"""

from __future__ import annotations

import functools
import math

import msgspec
import numpy as np
from msgspec import Struct

from kinepoly.check.blocks import SparseMatrix, block_condition, solve_blocks, window_condition
from kinepoly.check.constraints import Constraint
from kinepoly.check.coordinates import Body, Layout, bodies
from kinepoly.errors import AssemblyError, SingularityError
from kinepoly.geom.tolerances import NEWTON_REL_TOL

__all__ = [
    "NEWTON_REL_TOL",
    "SINGULAR_CONDITION",
    "IndexedLayout",
    "System",
    "condition_number",
    "newton",
    "singular_error",
    "solve_scaled",
]

SINGULAR_CONDITION = 1e7
"""A (dimensionless) velocity Jacobian whose 2-norm condition number exceeds this is singular.

Near a dead-centre the condition grows like 1 / sqrt(distance of the input from it); at the
dead-centre itself Newton finds the (double) root only to about sqrt(unit roundoff), which
leaves a condition of 1e8 to 1e9. Ordinary poses have 1 to 1e3; 1e7 flags inputs within
about 1e-12 rad of a dead-centre of a well-proportioned linkage.
"""

_MAX_NEWTON_STEPS = 100

WINDOW = 60
"""Unknowns (20 moving links) up to which the Jacobian's condition is the whole system's; beyond, a group's
with the groups next to it (``check.blocks.window_condition``): linear in a chain's length."""


class System(Struct, frozen=True, dict=True):
    """The constraints of a mechanism with the scaling that makes Phi_q dimensionless.

    Dr multiplies angle rows by L; Dc multiplies theta columns by 1/L. The scaled Jacobian
    Dr Phi_q Dc is what is judged and solved; x = Dc y for Dr Phi_q Dc y = Dr b.
    """

    constraints: tuple[Constraint, ...]
    layout: Layout
    where: str
    source: str

    @property
    def row_scale(self) -> np.ndarray:
        flags = [f for c in self.constraints for f in c.angle_rows]
        return np.array([self.layout.size if f else 1.0 for f in flags])

    @property
    def col_scale(self) -> np.ndarray:
        return np.tile([1.0, 1.0, 1.0 / self.layout.size], len(self.layout.moving))

    def bodies(self, q: np.ndarray, q_dot: np.ndarray | None = None) -> dict[str, Body]:
        return bodies(self.layout, q, q_dot)

    def phi(self, q: np.ndarray) -> np.ndarray:
        b = self.bodies(q)
        return np.concatenate([c.phi(b) for c in self.constraints])

    def scaled_phi(self, q: np.ndarray) -> np.ndarray:
        """Phi with angle rows in lengths (times L)."""
        return np.asarray(self.row_scale * self.phi(q), dtype=float)

    @functools.cached_property
    def _columns(self) -> dict[str, int]:
        """Each moving link's first column in q."""
        return {link: 3 * k for k, link in enumerate(self.layout.moving)}

    def jacobian(self, q: np.ndarray) -> np.ndarray | SparseMatrix:
        """Phi_q: dense up to WINDOW unknowns; beyond, a sparse matrix of each constraint's rows, derived over
        only the links it joins (so that a long chain costs time linear in its length)."""
        b = self.bodies(q)
        if self.layout.n <= WINDOW:
            return np.vstack([c.jacobian(b, self.layout) for c in self.constraints])
        rows: list[np.ndarray] = []
        cols: list[np.ndarray] = []
        values: list[np.ndarray] = []
        first = 0
        columns = self._columns
        for c in self.constraints:
            links = _links_of(c, columns)
            part = np.asarray(c.jacobian(b, Layout(links, self.layout.ground, self.layout.size)), dtype=float)
            where = np.array([columns[link] + k for link in links for k in range(3)], dtype=int)
            r, k = np.nonzero(part)
            rows.append(r + first)
            cols.append(where[k])
            values.append(part[r, k])
            first += part.shape[0]
        n = self.layout.n
        if not rows:
            return SparseMatrix.of((first, n), np.zeros(0), np.zeros(0), np.zeros(0))
        return SparseMatrix.of((first, n), np.concatenate(rows), np.concatenate(cols), np.concatenate(values))

    def scaled_jacobian(self, q: np.ndarray) -> np.ndarray | SparseMatrix:
        jac = self.jacobian(q)
        if isinstance(jac, SparseMatrix):
            return jac.scaled(self.row_scale, self.col_scale)
        return np.asarray(self.row_scale[:, None] * jac * self.col_scale[None, :], dtype=float)

    def condition(self, scaled_jac: np.ndarray | SparseMatrix) -> float:
        """The condition of the scaled Jacobian as each group sees it (``check.blocks.window_condition``): the
        whole system's 2-norm condition up to WINDOW unknowns, beyond that each group's with its neighbours."""
        if not isinstance(scaled_jac, SparseMatrix):
            return condition_number(scaled_jac)  # at most WINDOW unknowns: judged whole
        angle_rows = np.array([f for c in self.constraints for f in c.angle_rows], dtype=bool)
        angle_columns = np.tile([False, False, True], len(self.layout.moving))
        return window_condition(scaled_jac, WINDOW, angle_columns=angle_columns, angle_rows=angle_rows)

    def nu(self) -> np.ndarray:
        return np.concatenate([c.nu() for c in self.constraints])

    def gamma(self, q: np.ndarray, q_dot: np.ndarray) -> np.ndarray:
        b = self.bodies(q, q_dot)
        return np.concatenate([c.gamma(b) for c in self.constraints])


class IndexedLayout(Layout, frozen=True, dict=True):
    """A Layout whose columns are looked up in a table (``Layout.column`` scans the links: quadratic in a chain)."""

    @functools.cached_property
    def _columns(self) -> dict[str, int]:
        return {link: 3 * k for k, link in enumerate(self.moving)}

    def column(self, link: str) -> int | None:
        return None if link == self.ground else self._columns[link]


def _links_of(constraint: Constraint, moving: dict[str, int]) -> tuple[str, ...]:
    """The moving links a constraint joins: its fields that name a moving link."""
    names = [getattr(constraint, f.name) for f in msgspec.structs.fields(constraint)]  # type: ignore[arg-type]
    return tuple(dict.fromkeys(n for n in names if isinstance(n, str) and n in moving))


# --------------------------------------------------------------------------------------------
# Linear solves, each checked for its condition first
# --------------------------------------------------------------------------------------------


def condition_number(matrix: np.ndarray | SparseMatrix) -> float:
    """2-norm condition number by SVD (inf when singular); a sparse matrix is judged block by block.

    A ``SparseMatrix`` (the Jacobian) of more than WINDOW unknowns is put in block triangular form (``check.blocks``)
    and the largest condition number of its diagonal blocks is returned: the matrix is singular exactly
    when one of them is, and each group's conditioning is judged on its own, in time linear in
    the number of groups, instead of by one dense SVD whose condition also grows with the length
    of a chain of healthy loops.
    """
    if isinstance(matrix, SparseMatrix):
        if matrix.shape[1] > WINDOW:
            return block_condition(matrix)
        matrix = matrix.toarray()  # a small system: one dense SVD is cheaper than finding its blocks
    if matrix.size == 0:
        return 1.0
    sv = np.linalg.svd(matrix, compute_uv=False)
    return math.inf if sv[-1] == 0.0 else float(sv[0] / sv[-1])


def singular_error(system: System, condition: float) -> SingularityError:
    return SingularityError(
        f"{system.source}: input: the velocity equations are singular at {system.where}: the condition "
        f"number of the velocity Jacobian is {condition:.3g} (above {SINGULAR_CONDITION:.0e}); the mechanism "
        "is at a dead-centre (change point) there and its velocities are not determined by the input; "
        "choose another input value"
    )


def solve_scaled(system: System, scaled_jac: np.ndarray | SparseMatrix, rhs: np.ndarray) -> np.ndarray:
    """Solve Phi_q x = rhs through the scaled system (its condition checked by the caller)."""
    y = _solve(scaled_jac, system.row_scale * rhs)
    return np.asarray(system.col_scale * y, dtype=float)


def _solve(matrix: np.ndarray | SparseMatrix, rhs: np.ndarray) -> np.ndarray:
    """matrix y = rhs; a Jacobian of more than WINDOW unknowns block by block (linear in the number of groups)."""
    if isinstance(matrix, SparseMatrix):
        if matrix.shape[1] > WINDOW:
            return solve_blocks(matrix, np.asarray(rhs, dtype=float))
        matrix = matrix.toarray()  # a small system: one dense solve is cheaper than finding its blocks
    return np.asarray(np.linalg.solve(matrix, rhs), dtype=float)


# --------------------------------------------------------------------------------------------
# Position: damped Newton
# --------------------------------------------------------------------------------------------


def newton(system: System, q0: np.ndarray) -> tuple[np.ndarray, float]:
    """Damped Newton on Phi(q) = 0 from q0; returns q and max |Phi| (angle rows times L).

    Step: Phi_q dq = -Phi, halved until max |Phi| strictly decreases; where the Jacobian is
    singular (condition above SINGULAR_CONDITION) the least-squares step is taken instead.
    It runs until no step decreases the residual (rounding level), so that even at a
    dead-centre, where Newton converges only linearly, the pose is as exact as doubles allow.
    Converged when max |Phi| <= NEWTON_REL_TOL * L.
    """
    tol = NEWTON_REL_TOL * system.layout.size
    q = q0.astype(float).copy()
    f = system.scaled_phi(q)
    norm = float(np.max(np.abs(f)))
    for _ in range(_MAX_NEWTON_STEPS):
        if norm == 0.0:
            break
        step = system.col_scale * _newton_step(system, system.scaled_jacobian(q), f)
        # converged already: only a full step may polish the last digits; halving it would spend
        # forty residual evaluations to move q by less than its rounding
        improved = _line_search(system, q, step, norm, halvings=0 if norm <= tol else 40)
        if improved is None:
            break
        q, f, norm = improved
    if norm > tol:
        raise AssemblyError(
            f"{system.source}: the mechanism does not close at {system.where}: Newton's method on the "
            f"loop equations stopped at a residual of {norm:.3g} (tolerance {tol:.3g}, lengths); expected an "
            "input the linkage can reach and a start pose near that assembly"
        )
    return q, norm


def _newton_step(system: System, jac: np.ndarray | SparseMatrix, f: np.ndarray) -> np.ndarray:
    """Solve jac y = -f, by least squares where jac is singular (its condition checked first)."""
    if condition_number(jac) <= SINGULAR_CONDITION:  # singular exactly when a diagonal block is
        return _solve(jac, -f)
    dense = jac.toarray() if isinstance(jac, SparseMatrix) else jac
    return np.asarray(np.linalg.lstsq(dense, -f, rcond=None)[0], dtype=float)


def _line_search(
    system: System, q: np.ndarray, step: np.ndarray, norm: float, halvings: int = 40
) -> tuple[np.ndarray, np.ndarray, float] | None:
    """q + lam step for the first lam = 1, 1/2, ... (``halvings`` times) that decreases max |Phi|; None if none."""
    lam = 1.0
    for _ in range(halvings + 1):
        trial = q + lam * step
        f_trial = system.scaled_phi(trial)
        n_trial = float(np.max(np.abs(f_trial)))
        if n_trial < norm:
            return trial, f_trial, n_trial
        lam *= 0.5
    return None
