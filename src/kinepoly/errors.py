"""The one exception tree of kinepoly.

::

    KinepolyError                 base; every error the CLI turns into a message and an exit code
    ├── SceneError                the scene (or an answers file) is wrong: exit 2
    │   └── MobilityError         the links and joints do not make a one-degree-of-freedom mechanism
    ├── AssemblyError             the mechanism cannot close at the asked input: exit 3
    └── SingularityError          the position is singular: construction lines parallel, exit 3

Each error carries the full, user-facing message; ``SceneError`` carries a list of problems,
each already formatted as ``FILE:LINE: key.path: what is wrong; what is expected``.
"""

from __future__ import annotations

__all__ = [
    "EXIT_CANNOT_ASSEMBLE",
    "EXIT_OK",
    "EXIT_SCENE",
    "EXIT_WRONG_ANSWERS",
    "AssemblyError",
    "KinepolyError",
    "MobilityError",
    "SceneError",
    "SingularityError",
]

EXIT_OK = 0
EXIT_WRONG_ANSWERS = 1
EXIT_SCENE = 2
EXIT_CANNOT_ASSEMBLE = 3


class KinepolyError(Exception):
    """Base of every error kinepoly reports to a user."""

    exit_code = EXIT_SCENE


class SceneError(KinepolyError):
    """The scene file is wrong; raised by the loader after it collected every problem."""

    exit_code = EXIT_SCENE

    def __init__(self, problems: list[str] | str) -> None:
        self.problems = [problems] if isinstance(problems, str) else list(problems)
        super().__init__("\n".join(self.problems))


class MobilityError(SceneError):
    """Raised when Gruebler's count does not give one degree of freedom."""


class AssemblyError(KinepolyError):
    """Raised when a group of links cannot close at the asked input (names group, joint, inequality)."""

    exit_code = EXIT_CANNOT_ASSEMBLE


class SingularityError(KinepolyError):
    """Raised at a singular position: two construction lines parallel or a zero determinant."""

    exit_code = EXIT_CANNOT_ASSEMBLE
