"""The one exception tree of kinepoly.

::

    KinepolyError                 base; every error the CLI turns into a message and an exit code
    ├── SceneError                the scene (or an answers file, or a command-line value) is wrong: exit 2
    │   └── MobilityError         the links and joints do not make a one-degree-of-freedom mechanism
    ├── OutputError               an output path or option that cannot be written or used: exit 2
    ├── CatalogueError            a message catalogue with missing, unknown or bad keys: exit 2
    ├── HandoutError              a handout that cannot be laid out on the asked paper: exit 2
    ├── AssemblyError             the mechanism cannot close at the asked input: exit 3
    └── SingularityError          the position is singular: construction lines parallel, exit 3

    ParallelLinesError            (geom.lines; an ArithmeticError, not a KinepolyError) the
                                  geometry kernel's own: two lines that should cross are parallel.
                                  The kernel knows nothing of mechanisms; the construction turns
                                  it into a SingularityError that names the joint.

Each error carries the full, user-facing message; ``SceneError`` carries a list of problems,
each already formatted as ``FILE:LINE: key.path: what is wrong; what is expected``. An error
not in this tree reaching the command line is an internal error (exit 70).
"""

from __future__ import annotations

__all__ = [
    "EXIT_CANNOT_ASSEMBLE",
    "EXIT_INTERNAL",
    "EXIT_OK",
    "EXIT_SCENE",
    "EXIT_WRONG_ANSWERS",
    "AssemblyError",
    "CatalogueError",
    "HandoutError",
    "KinepolyError",
    "MobilityError",
    "OutputError",
    "SceneError",
    "SingularityError",
    "error_text",
    "internal_error_text",
]

EXIT_OK = 0
EXIT_WRONG_ANSWERS = 1
EXIT_SCENE = 2
EXIT_CANNOT_ASSEMBLE = 3
EXIT_INTERNAL = 70


class KinepolyError(Exception):
    """Base of every error kinepoly reports to a user."""

    exit_code = EXIT_SCENE


class SceneError(KinepolyError):
    """Raised when the scene file is wrong (by the loader, after it collected every problem), and likewise for
    an answers file, a ``[vary]`` table or a command-line value (``--from``, ``--n``, ``--sweep``, ...).
    """

    exit_code = EXIT_SCENE

    def __init__(self, problems: list[str] | str) -> None:
        self.problems = [problems] if isinstance(problems, str) else list(problems)
        super().__init__("\n".join(self.problems))


class MobilityError(SceneError):
    """Raised when Gruebler's count does not give one degree of freedom."""


class OutputError(KinepolyError):
    """Raised by the command line for an output it cannot make: no such folder, no permission, an unknown
    extension, nothing asked to write, a --dpi or --paper out of range (``kinepoly draw``, ``kinepoly handout``).
    """

    exit_code = EXIT_SCENE


class CatalogueError(KinepolyError):
    """Raised when a message catalogue cannot be used: an unknown language, a file that cannot be read or is
    not TOML, a missing or unknown key, a placeholder English does not have, a brace out of place.
    """

    exit_code = EXIT_SCENE


class HandoutError(KinepolyError):
    """Raised when a handout cannot be made as asked: an unknown paper, its text does not fit the paper, or its
    layout does not settle on it.
    """

    exit_code = EXIT_SCENE


class AssemblyError(KinepolyError):
    """Raised when a group of links cannot close at the asked input (names group, joint, inequality)."""

    exit_code = EXIT_CANNOT_ASSEMBLE


class SingularityError(KinepolyError):
    """Raised at a singular position: two construction lines parallel or a zero determinant."""

    exit_code = EXIT_CANNOT_ASSEMBLE


def error_text(error: KinepolyError) -> str:
    """A user's error as the command line prints it (``kinepoly edit`` shows it the same)."""
    return f"kinepoly: error: {error}"


def internal_error_text(error: Exception) -> str:
    """An error that is not the user's, as the command line prints it: never a traceback."""
    return f"kinepoly: internal error: {type(error).__name__}: {error}; please report it with the scene"
