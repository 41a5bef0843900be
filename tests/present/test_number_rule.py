"""Issue 25: one rule for every number meant for people, and driven values exactly as given.

The rule (``present.clean``): a value within its error estimate of 0 is 0, a value within its
estimate of a short decimal is that decimal; a driven value is given, not recomputed. The scan
runs every command that writes for people over every example and two variants of each: the solve
table and steps, check's report, the variants' scenes and answer keys, the handout's web page
(its text), the animation page's table and the sweep plot's tick labels. The sweep's CSV is data
(as the JSON): it keeps the computed values at 15 significant digits, and is not scanned.
"""

from __future__ import annotations

import html
import json
import math
import re
from pathlib import Path

import pytest
from tests.cli_support import run
from tests.present.test_rounding_noise import noisy_lines
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.homework.toml_out import answers_toml
from kinepoly.present.clean import given_angle, tidy

EXAMPLE_FILES = sorted(EXAMPLES.glob("*.toml"))
_RUN = re.compile(r"\d\.\d*(?:0{6,}|9{6,})\d")
"""A decimal with a long run of 0s or 9s before its last digit: 49.99999999999999, 210.00000000000003."""
_LONG = re.compile(r"(?<![\w.])-?(?:[1-9]\d*\.\d{9,}|0\.0*[1-9]\d{9,})")
"""A decimal of more than nine significant digits, nine places or more: [56.3815572472, 20.5212085995] (a
computed value, not a written one)."""
_CHECK_ERROR = re.compile(r"\s(?:-|[-\d.e+]+ %)(?:, [-\d.e+]+ deg)?$")
"""The error column of check's report (an error is reported as such, however small)."""
_ZERO_EXPONENT = re.compile(r"\b0\.0+e[+-]?0+\b")
"""An exact zero in exponent form: 0.0e+00."""


def noise_in(text: str, given: str = "") -> list[str]:
    """The lines of ``text`` that show noise: the detector of issue 13 (tiny exponents, values below 1e-9 of
    their line's largest), runs of 0s or 9s, long decimals, a zero in exponent form. A number that
    ``given`` (the scene the text came from) spells out itself is the user's and is not noise."""
    bad = set(noisy_lines(text))
    for line in text.splitlines():
        found = [m.group(0) for pattern in (_RUN, _LONG, _ZERO_EXPONENT) for m in pattern.finditer(line)]
        if any(number not in given for number in found):
            bad.add(line)
    return sorted(bad)


def test_the_detector_finds_the_reported_noise() -> None:
    assert noise_in("s_dot: 49.99999999999999")
    assert noise_in("angle = 210.00000000000003")
    assert noise_in("angle = 24.000000000000004")
    assert noise_in("C = [56.3815572472, 20.5212085995]")
    assert noise_in("s_ddot_56 = 9.97136e-14")
    assert noise_in("the largest relative error is 0.0e+00, so they agree")
    assert noise_in("expected 1.616e-14")
    assert not noise_in("angle = 210\nC = { polar = [60, 20] }\ns_dot = 50\nerror 1.3e-15")
    assert not noise_in("line = { through = [300, -300], angle = 63.43494882292201 }", "angle = 63.43494882292201")


def test_tidy_is_the_short_decimal_within_the_estimate() -> None:
    assert tidy(49.99999999999999, 1e-12) == 50.0
    assert tidy(1.6e-14, 1e-12) == 0.0
    assert tidy(-9.53087e-14, 1e-10) == 0.0
    assert tidy(20.13934, 1e-4) == 20.1393
    assert tidy(20.13934, 1e-3) == 20.14
    assert tidy(20.13934, 0.0) == 20.13934
    assert tidy(0.1 + 0.2, 1e-15) == 0.3
    assert math.copysign(1.0, tidy(-1e-20, 1e-15)) == 1.0
    assert math.isnan(tidy(math.nan, 1.0)) and tidy(math.inf, 1.0) == math.inf
    # never further than the estimate, and never longer than the value itself
    for value, error in ((math.pi, 1e-6), (-123.456789, 0.01), (1e-7 / 3, 1e-12), (2.0 / 3.0, 0.0)):
        shown = tidy(value, error)
        assert abs(shown - value) <= error
        assert len(repr(shown)) <= len(repr(value))


def test_an_angle_comes_back_as_written() -> None:
    for written in (210.0, 24.0, 60.0, -37.5, 0.1, 359.99, 63.434948822922):
        assert given_angle(math.radians(written), "deg") == written
    # a number of more digits than the stored radians tell apart: one that stores the same radians, as short
    assert math.radians(given_angle(math.radians(63.43494882292201), "deg")) == math.radians(63.43494882292201)
    assert given_angle(1.2345, "rad") == 1.2345


def _json(capsys: pytest.CaptureFixture[str], path: Path) -> dict[str, object]:
    code, out, _ = run(capsys, "solve", str(path), "--json")
    assert code == 0
    return json.loads(out)  # type: ignore[no-any-return]


def test_driven_sliders_echo_the_given_values(capsys: pytest.CaptureFixture[str]) -> None:
    """The excavator's cylinders: s = 680, s_dot = 50, s_ddot = 0 (was 679.9999999999998, 49.99999999999999) and
    s = 1070, s_dot = -30, s_ddot = 5; the dump body's s = 520, s_dot = 40 (was 39.99999999999998)."""
    sliders = _json(capsys, EXAMPLES / "excavator.toml")["sliders"]
    assert sliders["34"]["s"] == 680 and sliders["34"]["s_dot"] == 50 and sliders["34"]["s_ddot"] == 0  # type: ignore[index]
    assert sliders["67"]["s"] == 1070 and sliders["67"]["s_dot"] == -30 and sliders["67"]["s_ddot"] == 5  # type: ignore[index]
    dump = _json(capsys, EXAMPLES / "dump-body.toml")["sliders"]["34"]  # type: ignore[index]
    assert (dump["s"], dump["s_dot"], dump["s_ddot"]) == (520, 40, 0)


def test_a_driven_link_echoes_its_angle(capsys: pytest.CaptureFixture[str]) -> None:
    """The triad's crank is driven at 60 degrees (was 59.99999999999999); the other links keep their floats."""
    links = _json(capsys, EXAMPLES / "triad.toml")["links"]
    assert links["2"] == {"angle": 60, "omega": 5, "alpha": 2}  # type: ignore[index]


def test_the_cross_check_still_checks_the_construction() -> None:
    """The echo is for what is shown: the cross-check compares the slider values the construction laid."""
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "excavator.toml"))
    constructed = solution.sliders["34"]
    assert constructed.s_dot is not None and constructed.s_dot != 50.0, "the construction's own float"
    assert abs(constructed.s_dot - 50.0) <= 1e-12 * 50.0
    assert solution.slider("34").s_dot == 50.0
    assert solution.check.max_rel_error < 1e-12


# --------------------------------------------------------------------------------------------
# The scan: every command's human output over every example, variants included


def _text_of_html(page: str) -> str:
    """The words a reader sees: scripts and styles out, tags out, entities resolved."""
    page = re.sub(r"<(script|style)\b.*?</\1>", "", page, flags=re.DOTALL)
    return html.unescape(re.sub(r"<[^>]+>", "\n", page))


def _animation_table(path: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> str:
    """The animation page's table as its script prints it: each value to six significant digits."""
    target = tmp_path / "motion.html"
    code, _, err = run(capsys, "animate", str(path), "-o", str(target), "--positions", "12")
    assert code == 0, err
    found = re.search(r'id="frames">(.*?)</script>', target.read_text(encoding="utf-8"), re.DOTALL)
    assert found is not None
    data = json.loads(found[1].replace("<\\/", "</"))
    return "\n".join(repr(float(f"{x:.6g}")).removesuffix(".0") for value in data["values"] for x in value["values"]
                     if x is not None)


def _plot_ticks(path: Path) -> str:
    """Every tick label and offset text of the sweep's plots."""
    import matplotlib.pyplot as plt

    from kinepoly.sweep.plots import plot_figure
    from kinepoly.sweep.run import sweep

    fig = plot_figure(sweep(kinepoly.load_scene(path), steps=90))
    try:
        fig.canvas.draw()
        lines = []
        for ax in fig.axes:
            for axis in (ax.xaxis, ax.yaxis):
                labels = [t.get_text().replace("−", "-") for t in axis.get_ticklabels()]
                lines.append(" ".join(labels) + " " + axis.get_offset_text().get_text().replace("−", "-"))
        return "\n".join(lines)
    finally:
        plt.close(fig)


def _offsets(ticks: str) -> list[str]:
    """Axis offsets that add noise to a constant: 1e-10+5e1."""
    return re.findall(r"1e-1\d\+\S+", ticks)


@pytest.mark.slow
@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=lambda p: p.stem)
def test_no_command_prints_noise(capsys: pytest.CaptureFixture[str], tmp_path: Path, path: Path) -> None:
    given = path.read_text(encoding="utf-8")
    found: dict[str, list[str]] = {}
    code, out, _ = run(capsys, "solve", str(path))
    assert code == 0
    found["solve"] = noise_in(out, given)
    code, out, _ = run(capsys, "solve", str(path), "--steps")
    found["steps"] = noise_in(out, given)
    # check: the scene against its own key (every expected value is printed)
    key = tmp_path / "key.toml"
    code, _, err = run(capsys, "variants", str(path), "--n", "2", "--seed", "3", "-o", str(tmp_path / "v"))
    variants = sorted((tmp_path / "v").glob("*[0-9].toml")) if code == 0 else []
    if code == 0:
        assert len(variants) == 2
    else:
        assert "[given]" in err, err  # a [given] scene has no variants
    for scene in variants:
        answers = scene.with_suffix(".answers.toml")
        found[f"variant {scene.name}"] = noise_in(scene.read_text(encoding="utf-8"), given)
        found[f"key {answers.name}"] = noise_in(answers.read_text(encoding="utf-8"), given)
        code, out, _ = run(capsys, "check", str(scene), str(answers))
        assert code == 0
        found[f"check {scene.name}"] = noise_in("\n".join(_CHECK_ERROR.sub("", line) for line in out.splitlines()),
                                                given)
    if variants:
        from kinepoly.homework.reference import asked_keys, values_of

        solution = kinepoly.solve(kinepoly.load_scene(path))
        values = values_of(solution)
        key.write_text(answers_toml([(k, values[k]) for k in asked_keys(values)], solution.scene.units),
                       encoding="utf-8")
        code, out, _ = run(capsys, "check", str(path), str(key))
        assert code == 0, out
        found["check"] = noise_in("\n".join(_CHECK_ERROR.sub("", line) for line in out.splitlines()), given)
    page = tmp_path / "handout.html"
    code, _, err = run(capsys, "handout", str(path), "--html", str(page))
    assert code == 0, err
    found["handout"] = noise_in(_text_of_html(page.read_text(encoding="utf-8")), given)
    if "[given" not in given:
        found["animate"] = noise_in(_animation_table(path, tmp_path, capsys), given)
        ticks = _plot_ticks(path)
        found["sweep plot"] = noise_in(ticks, given) + _offsets(ticks)
    noisy = {where: lines for where, lines in found.items() if lines}
    assert noisy == {}, json.dumps(noisy, indent=1)


def test_variants_write_polar_points_and_angles_as_written(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    """A gear scene's lengths are scaled exactly (so radii still sum to centre distances): its polar point was
    written [56.3815572472, 20.5212085995]; now { polar = [r, 20] }, r the scaled radius, the angle as given."""
    text = (EXAMPLES / "gear-pair.toml").read_text(encoding="utf-8")
    text = text.replace('E = [45, 0]', 'E = { polar = [45, 20] }').replace("angle = 20", "angle = 210")
    scene = tmp_path / "polar-gears.toml"
    scene.write_text(text, encoding="utf-8")
    code, _, err = run(capsys, "variants", str(scene), "--n", "3", "--seed", "5", "--angle", "210,210",
                       "-o", str(tmp_path / "v"))
    assert code == 0, err
    for written in sorted((tmp_path / "v").glob("*[0-9].toml")):
        variant = written.read_text(encoding="utf-8")
        assert noise_in(variant) == []
        polar = re.search(r"E = \{ polar = \[([-\d.]+), ([-\d.]+)\] \}", variant)
        assert polar is not None, variant
        assert polar[2] == "20" and len(polar[1]) <= 6, polar[0]
        assert "angle = 210\n" in variant
        loaded = kinepoly.load_scene(written)
        point = next(p for link in loaded.links for p in link.points if p.name == "E")
        assert point.polar is not None and math.isclose(point.polar[1], math.radians(20.0))
