"""A sparse square system in block triangular form: its diagonal blocks' conditions and its solution.

The analytic check's Jacobian couples each link only with the few links its joints join, and a
mechanism's groups make it block triangular: a perfect matching of rows to columns puts a
nonzero on every diagonal entry, and the strongly connected components of the graph "row i
uses column j" are the diagonal blocks (Duff's method; the blocks are the mechanism's groups as
its equations see them). Solving block by block and judging each block's condition costs time
linear in the number of groups, where a dense SVD or LU of the whole costs its cube.

Pure numpy and Python: rows and columns are indices, the matrix a list of (row, column, value).
"""

from __future__ import annotations

import math

import numpy as np
from msgspec import Struct

__all__ = ["SparseMatrix", "block_condition", "blocks_of", "solve_blocks", "window_condition"]


class SparseMatrix(Struct, frozen=True):
    """An m x n matrix by its nonzero entries (coordinates and values; no zero is stored)."""

    shape: tuple[int, int]
    rows: np.ndarray
    cols: np.ndarray
    values: np.ndarray

    @staticmethod
    def of(shape: tuple[int, int], rows: np.ndarray, cols: np.ndarray, values: np.ndarray) -> SparseMatrix:
        keep = values != 0.0
        return SparseMatrix(shape, rows[keep].astype(int), cols[keep].astype(int), values[keep].astype(float))

    def scaled(self, row_scale: np.ndarray, col_scale: np.ndarray) -> SparseMatrix:
        """diag(row_scale) @ self @ diag(col_scale)."""
        return SparseMatrix.of(self.shape, self.rows, self.cols,
                               self.values * row_scale[self.rows] * col_scale[self.cols])

    def toarray(self) -> np.ndarray:
        out = np.zeros(self.shape)
        np.add.at(out, (self.rows, self.cols), self.values)
        return out

    def row_lists(self) -> list[list[int]]:
        """For each row, the columns of its nonzeros."""
        out: list[list[int]] = [[] for _ in range(self.shape[0])]
        for r, c in zip(self.rows.tolist(), self.cols.tolist(), strict=True):
            out[r].append(c)
        return out


class Blocks(Struct, frozen=True):
    """The block triangular form: ``match[i]`` is the column on row i's diagonal; ``order`` the blocks (each a
    list of rows) in the order they are solved (a block uses only the columns of blocks before it)."""

    match: list[int]
    order: list[list[int]]


def _matching(adjacency: list[list[int]], n: int) -> list[int] | None:
    """A perfect matching row -> column (augmenting paths, cheap first), or None when there is none."""
    m = len(adjacency)
    match_col = [-1] * n  # column -> row
    match_row = [-1] * m
    for r in range(m):  # greedy first: in a chain of groups nearly every row finds a free column at once
        for c in adjacency[r]:
            if match_col[c] < 0:
                match_col[c], match_row[r] = r, c
                break
    for start in range(m):
        if match_row[start] >= 0:
            continue
        # breadth-first search for an augmenting path from the row ``start``
        parent_col: dict[int, int] = {}
        queue = [start]
        found = -1
        head = 0
        while head < len(queue) and found < 0:
            r = queue[head]
            head += 1
            for c in adjacency[r]:
                if c in parent_col:
                    continue
                parent_col[c] = r
                if match_col[c] < 0:
                    found = c
                    break
                queue.append(match_col[c])
        if found < 0:
            return None
        c = found
        while c >= 0:  # flip the path
            r = parent_col[c]
            previous = match_row[r]
            match_row[r], match_col[c] = c, r
            c = previous
    return match_row


def _strong_components(successors: list[list[int]]) -> list[list[int]]:
    """Tarjan's strongly connected components, iteratively; each is emitted after every one it reaches."""
    n = len(successors)
    index = [-1] * n
    low = [0] * n
    on_stack = [False] * n
    stack: list[int] = []
    out: list[list[int]] = []
    counter = 0
    for root in range(n):
        if index[root] >= 0:
            continue
        work = [(root, 0)]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack[root] = True
        while work:
            v, k = work[-1]
            if k < len(successors[v]):
                work[-1] = (v, k + 1)
                w = successors[v][k]
                if index[w] < 0:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack[w] = True
                    work.append((w, 0))
                elif on_stack[w]:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                u = work[-1][0]
                low[u] = min(low[u], low[v])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on_stack[w] = False
                    component.append(w)
                    if w == v:
                        break
                out.append(sorted(component))
    return out


def blocks_of(matrix: SparseMatrix) -> Blocks | None:
    """The block triangular form of a square matrix; None when it is not square or structurally singular."""
    m, n = matrix.shape
    if m != n:
        return None
    adjacency = matrix.row_lists()
    match = _matching(adjacency, n)
    if match is None:
        return None
    row_of_col = [0] * n
    for r, c in enumerate(match):
        row_of_col[c] = r
    # row r uses column c, whose diagonal row is row_of_col[c]: an edge r -> row_of_col[c]
    successors = [[row_of_col[c] for c in adjacency[r] if row_of_col[c] != r] for r in range(m)]
    return Blocks(match, _strong_components(successors))


def _condition(block: np.ndarray) -> float:
    if block.size == 0:
        return 1.0
    sv = np.linalg.svd(block, compute_uv=False)
    return math.inf if sv[-1] == 0.0 else float(sv[0] / sv[-1])


def block_condition(matrix: SparseMatrix, blocks: Blocks | None = None, *, angle_columns: np.ndarray | None = None,
                    angle_rows: np.ndarray | None = None) -> float:
    """The largest 2-norm condition number of the diagonal blocks (of the whole, dense, without a form).

    With ``angle_columns`` and ``angle_rows`` (masks of the columns that are angles times 1/L and
    the rows that are angles times L, L the whole mechanism's size), each block is judged at its
    own size: where its largest lever arm (its largest entry in an angle column, in units of L) is
    s < 1, its angle columns are divided by s and its angle rows multiplied by s, as if L were
    the group's own size. A group far smaller than the whole mechanism (a loop of a long chain)
    is then as well conditioned as it is alone.
    """
    blocks = blocks if blocks is not None else blocks_of(matrix)
    if blocks is None:
        return _condition(matrix.toarray())
    dense_rows = _row_entries(matrix)
    worst = 1.0
    for rows in blocks.order:
        cols = [blocks.match[r] for r in rows]
        block = _block(dense_rows, rows, cols)
        if angle_columns is not None and angle_rows is not None:
            _at_own_size(block, angle_columns[cols], angle_rows[rows])
        worst = max(worst, _condition(block))
    return worst


def window_condition(matrix: SparseMatrix, limit: int, *, angle_columns: np.ndarray, angle_rows: np.ndarray) -> float:
    """The condition of the equations as each group sees them: the largest, over the diagonal blocks, of the
    2-norm condition of the block together with the blocks it uses (nearest first, about ``limit`` unknowns).

    A matrix of at most ``limit`` unknowns, or one without a block form, is judged whole (one dense
    SVD). Otherwise each window is judged at its own size (``block_condition``'s rescaling), so a
    chain of healthy loops is judged by one loop with its neighbours: the condition does not grow
    with the chain's length, and its cost is linear in it. The window keeps the coupling between a
    group and the groups that drive it, which amplifies errors as much as the group itself does.
    """
    blocks = blocks_of(matrix) if matrix.shape[0] > limit else None
    if blocks is None:
        return _condition(matrix.toarray())
    entries = _row_entries(matrix)
    match = blocks.match
    component = [0] * matrix.shape[0]
    for k, rows in enumerate(blocks.order):
        for r in rows:
            component[r] = k
    row_of_col = {c: r for r, c in enumerate(match)}
    uses = [sorted({component[row_of_col[c]] for r in rows for c in entries[r]} - {k})
            for k, rows in enumerate(blocks.order)]
    worst = 1.0
    for k, rows in enumerate(blocks.order):
        chosen = [k]
        seen = {k}
        size = len(rows)
        queue = list(reversed(uses[k]))  # the nearest (latest solved) first
        head = 0
        while head < len(queue) and size < limit:
            j = queue[head]
            head += 1
            if j in seen:
                continue
            seen.add(j)
            chosen.append(j)
            size += len(blocks.order[j])
            queue += reversed(uses[j])
        window_rows = [r for j in sorted(chosen) for r in blocks.order[j]]
        cols = [match[r] for r in window_rows]
        block = _block(entries, window_rows, cols)
        _at_own_size(block, angle_columns[cols], angle_rows[window_rows])
        worst = max(worst, _condition(block))
    return worst


def _at_own_size(block: np.ndarray, theta: np.ndarray, angle_rows: np.ndarray) -> None:
    """Rescale a block in place as if the mechanism's size were the block's own largest lever arm s < 1:
    its angle columns divided by s, its angle rows multiplied by s."""
    arm = float(np.max(np.abs(block[np.ix_(~angle_rows, theta)]), initial=0.0))
    if 0.0 < arm < 1.0:
        block[:, theta] /= arm
        block[angle_rows, :] *= arm


def _row_entries(matrix: SparseMatrix) -> list[dict[int, float]]:
    out: list[dict[int, float]] = [{} for _ in range(matrix.shape[0])]
    for r, c, v in zip(matrix.rows.tolist(), matrix.cols.tolist(), matrix.values.tolist(), strict=True):
        out[r][c] = out[r].get(c, 0.0) + v
    return out


def _block(entries: list[dict[int, float]], rows: list[int], cols: list[int]) -> np.ndarray:
    out = np.zeros((len(rows), len(cols)))
    where = {c: k for k, c in enumerate(cols)}
    for i, r in enumerate(rows):
        for c, v in entries[r].items():
            k = where.get(c)
            if k is not None:
                out[i, k] = v
    return out


def solve_blocks(matrix: SparseMatrix, rhs: np.ndarray, blocks: Blocks | None = None) -> np.ndarray:
    """matrix x = rhs, block by block in the order of the form (dense when it has none)."""
    blocks = blocks if blocks is not None else blocks_of(matrix)
    if blocks is None:
        return np.asarray(np.linalg.solve(matrix.toarray(), rhs), dtype=float)
    entries = _row_entries(matrix)
    x = np.zeros(matrix.shape[1])
    solved = np.zeros(matrix.shape[1], dtype=bool)
    for rows in blocks.order:
        cols = [blocks.match[r] for r in rows]
        b = np.array([rhs[r] - sum(v * x[c] for c, v in entries[r].items() if solved[c]) for r in rows])
        x[cols] = np.linalg.solve(_block(entries, rows, cols), b)
        solved[cols] = True
    return x
