"""``kinepoly.sweep`` is the sweep's public face (docs/python.md): the function, its result type and the plan
made once; the face lists its names sorted, each the one object of the module that defines it."""

from __future__ import annotations

from tests.scenes import EXAMPLES

import kinepoly.sweep as face
from kinepoly.scene.loader import load_scene
from kinepoly.sweep import family, result, run


def _isort_order(name: str) -> tuple[int, str]:
    """Constants, then classes, then functions (ruff's RUF022 order of an __all__)."""
    return (0 if name.isupper() else 1 if name[0].isupper() else 2, name)


def test_the_face_exports_the_sweep_and_its_result_type_sorted() -> None:
    assert face.__all__ == sorted(face.__all__, key=_isort_order)
    assert {"sweep", "SweepResult", "Column", "STATUS", "prepare_sweep", "run_sweep", "sweep_family",
            "FamilyResult"} <= set(face.__all__)
    for name in face.__all__:
        home = next(m for m in (result, family, run) if name in m.__all__)
        assert getattr(face, name) is getattr(home, name), name


def test_a_sweep_from_the_face_returns_the_result_type_with_its_columns() -> None:
    turn = face.sweep(load_scene(str(EXAMPLES / "four-bar.toml")), steps=12)
    assert isinstance(turn, face.SweepResult) and turn.rows == 12
    assert turn.column("theta_2") is turn.input and all(face.STATUS[int(s)] == "ok" for s in turn.status)
    assert isinstance(turn.column("omega_4"), face.Column) and bool(turn.column("omega_4").valid.all())
