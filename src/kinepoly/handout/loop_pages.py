"""The handout's pages of the loop-closure method (``kinepoly handout --loops``): a page per loop.

Each page shows the finished drawing and, in the catalogue's language, the loop (how many loops and why
on the first), its equation with the scene's numbers, its first and second derivatives, and the systems
solved for the rates it gives: Cramer's rule for a loop left with two unknowns; loops whose unknowns are
coupled (a triad's) solved together on the page of the last of them.
"""

from __future__ import annotations

import re

from kinepoly.handout.content import Column, Drawing, Page, Paragraph
from kinepoly.loops.rates import Block, LoopSolution
from kinepoly.loops.text import block_lines, constant_line, count_line, loop_lines
from kinepoly.present.catalogue import Catalogue

__all__ = ["loop_pages"]

_SUBSCRIPT = re.compile(r"([θωαs])(\u0307|\u0308)?_")
"""θ_13, ṡ_43 as the handout's notation writes them (θ13, the digits lowered; ṡ as s and a combining dot);
e^{iθ} as e^(iθ), so that the names in the exponent are typeset too."""


def _notation(line: str) -> str:
    line = (line.replace("ṡ_", "s\u0307_").replace("s̈_", "s\u0308_").replace("{i(", "{i (")
            .replace("{", "(").replace("}", ")"))
    return _SUBSCRIPT.sub(lambda m: m.group(1) + (m.group(2) or ""), line)


def _page_of(block: Block, loops: LoopSolution) -> int:
    """The loop whose page shows ``block``: its loop, or the last of the loops it couples (the first for an input)."""
    return max(block.loops, default=loops.loops[0].number)


def _blocks(loops: LoopSolution, number: int, say: Catalogue) -> list[Paragraph]:
    out: list[Paragraph] = []
    for title, order, blocks in (("loops.velocities", 1, loops.velocity_blocks),
                                 ("loops.accelerations", 2, loops.acceleration_blocks)):
        mine = [b for b in blocks if _page_of(b, loops) == number]
        if not mine:
            continue
        out.append(Paragraph(_notation(say.say(title)), "note"))
        for block in mine:
            if order == 2:
                out += [Paragraph(_notation(constant_line(loops, k, say))) for k in block.loops]
            for line in block_lines(loops, block, order, say):
                text = _notation(line.strip())
                out.append(Paragraph(text, "equation") if line.startswith("    ") else Paragraph(text))
    return out


def loop_pages(loops: LoopSolution, say: Catalogue) -> tuple[Page, ...]:
    """A page per loop, after the answers."""
    pages = []
    total = len(loops.loops)
    for loop in loops.loops:
        head, position, known, *derivatives = (_notation(line) for line in loop_lines(loops, loop, say))
        heading = f"{say.say('loops.heading')} {loop.number}/{total}"
        first: list[Paragraph] = [Paragraph(heading, "heading")]
        if loop.number == 1:
            first.append(Paragraph(_notation(count_line(loops, say)), "note"))
        first += [Paragraph(head), Paragraph(position, "equation"), Paragraph(known)]
        first += [Paragraph(line, "equation" if line.endswith("= 0") else "body") for line in derivatives]
        columns = (Column(tuple(first), fill=True), Column(tuple(_blocks(loops, loop.number, say)), fill=True))
        pages.append(Page("answers", Drawing("answers"), columns, position, heading))
    return tuple(pages)
