"""The scene being edited: its text, the undo history, the last answer that solved, and what is on disk.

A ``Document`` is the server's only state. Every change makes a new text, evaluated at once
(``evaluate.evaluate``); a text that does not solve is kept (nothing typed is lost) while the page
keeps the last drawing that did. ``save`` writes the text to the one file the editor was started
on, whole or not at all (``cli.files.write_atomically``), and refuses, unless forced, when the file
changed on disk since it was read or last saved.
"""

from __future__ import annotations

import hashlib
import threading
from pathlib import Path
from typing import IO, Any

from msgspec import Struct

from kinepoly.editor.edits import apply_edit
from kinepoly.editor.evaluate import PAPER, Evaluation, evaluate, redrawn, step_svg
from kinepoly.editor.template_names import TEMPLATES

__all__ = ["TEMPLATES", "ChangedOnDisk", "Document", "template_text"]


_WRITTEN_MOST = 20000
"""The most items' SVG kept between changes (a few sheets' worth)."""


class ChangedOnDisk(Exception):
    """The file changed on disk since the editor read or saved it: saving would overwrite someone's change."""


def template_text(name: str) -> str:
    """The text of template ``name`` (one of ``TEMPLATES``)."""
    from importlib.resources import files

    if name not in TEMPLATES:
        raise KeyError(name)
    return files("kinepoly.editor").joinpath("templates", f"{name}.toml").read_text(encoding="utf-8")


def _stamp(path: Path) -> str | None:
    """The file's content digest, or None when there is no file."""
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except FileNotFoundError:
        return None


class _History(Struct):
    texts: list[str]
    index: int = 0
    merging: bool = False
    """Whether the last change was an edit, which a next edit with ``merge`` joins (a drag is one step to undo)."""


class Document:
    """The text of ``path`` (or ``text`` when given: a new file from a template), edited and evaluated, drawn on
    ``paper``."""

    def __init__(self, path: str, text: str | None = None, paper: tuple[float, float] = PAPER) -> None:
        self.path = Path(path)
        self.paper = paper
        self.source = path
        self._disk = _stamp(self.path)
        self._saved_text = self.path.read_text(encoding="utf-8") if text is None else None
        first = self._saved_text if text is None else text
        assert first is not None
        self._history = _History([first])
        self._lock = threading.Lock()
        self._written: dict[Any, str] = {}
        """The SVG of the sheets' items written so far (``evaluate``'s ``written``), emptied when it grows large."""
        self.current = evaluate(first, self.source, paper=paper, written=self._written)
        self.good: Evaluation | None = self.current if self.current.ok else None

    @property
    def text(self) -> str:
        return self._history.texts[self._history.index]

    def _set(self, text: str, merge: bool, mergeable: bool, draft: bool = False) -> Evaluation:
        history = self._history
        if merge and history.merging and history.index > 0:
            history.texts[history.index] = text
        elif text != self.text:
            del history.texts[history.index + 1:]
            history.texts.append(text)
            history.index += 1
        history.merging = mergeable
        return self._evaluate(draft)

    def _evaluate(self, draft: bool = False) -> Evaluation:
        if len(self._written) > _WRITTEN_MOST:
            self._written.clear()
        self.current = evaluate(self.text, self.source, paper=self.paper, draft=draft, written=self._written)
        if self.current.ok:
            self.good = self.current
        return self.current

    def replace(self, text: str) -> Evaluation:
        """The whole text replaced (the page's TOML field, or a script); one step to undo."""
        with self._lock:
            return self._set(text, merge=False, mergeable=False)

    def edit(self, edit: dict[str, Any], merge: bool = False, draft: bool = False) -> Evaluation:
        """One edit (``edits.apply_edit``) on the current text, from the last solved position; EditError when it
        cannot be made. ``merge``: a move of the same drag as the change before (one step to undo); ``draft``: its
        sheet drawn as a draft (labels unsearched: a move of a drag), which ``full`` draws whole."""
        with self._lock:
            solution = self.good.solution if self.good is not None else None
            return self._set(apply_edit(self.text, edit, solution), merge, mergeable=True, draft=draft)

    def full(self) -> Evaluation:
        """The drawings shown (the current one, the last good one) drawn whole where they are drafts."""
        with self._lock:
            current, good = self.current, self.good
            self.current = redrawn(current, self._written)
            self.good = self.current if good is current else redrawn(good, self._written) if good is not None else None
            return self.current

    def undo(self) -> Evaluation:
        with self._lock:
            self._history.index = max(0, self._history.index - 1)
            self._history.merging = False
            return self._evaluate()

    def redo(self) -> Evaluation:
        with self._lock:
            self._history.index = min(len(self._history.texts) - 1, self._history.index + 1)
            self._history.merging = False
            return self._evaluate()

    def save(self, force: bool = False) -> None:
        """Write the text to the file; ChangedOnDisk (unless ``force``) when the file changed since read or saved."""
        from kinepoly.atomic import write_atomically

        with self._lock:
            if not force and _stamp(self.path) != self._disk:
                raise ChangedOnDisk(f"{self.source} changed on disk since the editor read or saved it")
            text = self.text
            def write(stream: IO[Any]) -> None:
                stream.write(text)

            write_atomically(self.path, write, binary=False)
            self._disk = _stamp(self.path)
            self._saved_text = text
            self._history.merging = False

    def step(self, number: int) -> str | None:
        """Step ``number``'s sheet of the last text that solved."""
        with self._lock:  # the sheets of one layout share its labels' cache: one built at a time
            return step_svg(self.good, number) if self.good is not None else None

    def state(self) -> dict[str, Any]:
        """What the page shows: the current answer (or its errors), the last good drawing, the text, the history.
        Taken under the lock (a change in another thread is seen whole or not at all); call it from a worker."""
        with self._lock:
            return self._state()

    def _state(self) -> dict[str, Any]:
        current, good = self.current, self.good
        out: dict[str, Any] = {
            "ok": current.ok, "result": current.result, "errors": list(current.errors), "exit": current.exit,
            "text": self.text, "path": self.source, "dirty": self.text != self._saved_text,
            "can_undo": self._history.index > 0, "can_redo": self._history.index < len(self._history.texts) - 1,
            "timing_ms": current.timing_ms,
        }
        if good is not None:
            out.update(svg=good.svg, draft=good.draft, view=good.view, handles=good.handles,
                       good_result=good.result if good is not current else None)
        return out

