"""kinepoly variants --quiz: the exports read back by independent readers (xml.etree, zipfile, tomllib, text2qti).

Every right number is the variant's answer key as written (NAME.answers.toml, read with tomllib);
every mistake's number is what ``kinepoly check`` makes of that mistake, through check's own API:
a scalar answered with it is diagnosed as that mistake, a vector's part is that of check's candidate.
"""

from __future__ import annotations

import base64
import contextlib
import html as html_module
import io
import math
import re
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.cli_support import run
from tests.scenes import EXAMPLES

from kinepoly import load_scene
from kinepoly.cli import main
from kinepoly.homework import check, loads_answers, make_checker
from kinepoly.homework.answers import AnswerKey
from kinepoly.homework.diagnose import candidates
from kinepoly.present.catalogue import load_catalogue

SLOTTED = str(EXAMPLES / "slotted-lever.toml")
COUNT = 3
CODES = ("sign-reversed", "coriolis-left-out", "coriolis-reversed", "normal-reversed", "kv-not-divided",
         "ka-not-divided", "degrees-for-radians", "rpm-for-rad/s", "other-point", "other-link")
PNG = b"\x89PNG\r\n\x1a\n"
SAY = load_catalogue("en")


def _make(folder: Path, *options: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["variants", SLOTTED, "--n", str(COUNT), "--seed", "7", "-o", str(folder), *options])
    assert code == 0, out.getvalue()
    return out.getvalue()


@pytest.fixture(scope="module")
def moodle(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    folder = tmp_path_factory.mktemp("moodle")
    return folder, _make(folder, "--quiz", "moodle")


@pytest.fixture(scope="module")
def canvas(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    pytest.importorskip("text2qti")
    folder = tmp_path_factory.mktemp("qti")
    return folder, _make(folder, "--quiz", "qti")


# --------------------------------------------------------------------------------------------
# An independent reader of Moodle's embedded answers: {1:NUMERICAL:=V:T#F~%0%W:T#F}


def _unescape(text: str) -> str:
    return re.sub(r"\\(.)", r"\1", text)


def _blanks(html: str) -> list[tuple[str, list[tuple[float, float, float, str]]]]:
    """Each blank's label (the paragraph's text before it) and its answers: (grade %, number, tolerance, feedback)."""
    out = []
    for label, body in re.findall(r"<p>([^<]*(?:<sub>[^<]*</sub>[^<]*)*) \{1:NUMERICAL:((?:\\.|[^}\\])*)\}</p>", html):
        answers = []
        for alternative in re.split(r"(?<!\\)~", body):
            match = re.fullmatch(r"(=|%(\d+)%)([-+0-9.eE]+):([0-9.eE+-]+)(?:#(.*))?", alternative, re.DOTALL)
            assert match, alternative
            grade = 100.0 if match.group(1) == "=" else float(match.group(2))
            answers.append((grade, float(match.group(3)), float(match.group(4)), _unescape(match.group(5) or "")))
        out.append((label, answers))
    return out


def _key(folder: Path, name: str) -> dict[str, Any]:
    return tomllib.loads((folder / f"{name}.answers.toml").read_text())


def _asked(key: dict[str, Any]) -> dict[str, float]:
    """The numbers a quiz asks, by the label's notation, from an answer key as written."""
    out = {}
    for name, value in key.items():
        if name.startswith("theta_"):
            continue
        if name.startswith(("v_", "a_")):
            letter, _, point = name.partition("_")
            shown = f"{letter}<sub>{point}</sub>"
            out[f"|{shown}|"] = math.hypot(*value)
            out[f"direction of {shown}"] = math.degrees(math.atan2(value[1], value[0]))
        else:
            kind, _, link = name.partition("_")
            out[f"{'ω' if kind == 'omega' else 'α'}<sub>1{link}</sub>"] = value
    return out


def _code_of(feedback: str) -> str:
    """The mistake a feedback names, by the catalogue's words for each code."""
    found = [code for code in CODES
             if SAY.messages[f"quiz.{code.replace('-', '_').replace('/', '_')}"].split("{")[0] in feedback]
    assert len(found) == 1, feedback
    return found[0]


def _questions(folder: Path) -> tuple[ET.Element, list[ET.Element]]:
    root = ET.parse(folder / "slotted-lever.moodle.xml").getroot()
    return root, root.findall("question[@type='cloze']")


def _parts_of(label: str) -> tuple[AnswerKey, str]:
    match = re.search(r"(ω|α)<sub>1(\d+)</sub>", label)
    if match:
        return AnswerKey("omega" if match.group(1) == "ω" else "alpha", match.group(2)), "value"
    match = re.search(r"([va])<sub>([^<]+)</sub>", label)
    assert match, label
    kind = "velocity" if match.group(1) == "v" else "acceleration"
    return AnswerKey(kind, match.group(2)), "direction" if "direction" in label else "magnitude"


def _angle_apart(a: float, b: float) -> float:
    return abs(math.remainder(a - b, 360.0))


# --------------------------------------------------------------------------------------------
# Moodle


def test_moodle_one_question_per_variant_named_by_variant_and_seed_in_the_scenes_category(
        moodle: tuple[Path, str]) -> None:
    folder, printed = moodle
    root, questions = _questions(folder)
    category = root.find("question[@type='category']/category/text")
    assert category is not None and category.text == "$course$/top/kinepoly/slotted-lever"
    assert len(questions) == COUNT
    for k, question in enumerate(questions, 1):
        assert question.findtext("name/text") == f"slotted-lever-{k:02d}: variant {k} of {COUNT}, seed 7"
    assert f"quiz {folder / 'slotted-lever.moodle.xml'}: {COUNT} questions" in printed


def test_moodle_figures_are_embedded_valid_pngs_of_the_problem(moodle: tuple[Path, str]) -> None:
    import matplotlib.image

    folder, _ = moodle
    _, questions = _questions(folder)
    for k, question in enumerate(questions, 1):
        html = question.findtext("questiontext/text") or ""
        name = f"slotted-lever-{k:02d}.png"
        assert f'src="@@PLUGINFILE@@/{name}"' in html
        files = question.findall("questiontext/file")
        assert [f.get("name") for f in files] == [name] and files[0].get("encoding") == "base64"
        data = base64.b64decode(files[0].text or "")
        assert data.startswith(PNG)
        pixels = matplotlib.image.imread(io.BytesIO(data), format="png")
        assert pixels.shape[0] > 500 and pixels.shape[1] > 800 and pixels.min() < 0.5  # a drawing, not a blank
        variant = tomllib.loads((folder / f"slotted-lever-{k:02d}.toml").read_text())
        assert variant["title"] in html and "Find" in html and "kv = " in html  # the problem page's text


def test_moodle_right_answers_are_the_variants_keys(moodle: tuple[Path, str]) -> None:
    folder, _ = moodle
    _, questions = _questions(folder)
    for k, question in enumerate(questions, 1):
        blanks = _blanks(question.findtext("questiontext/text") or "")
        asked = _asked(_key(folder, f"slotted-lever-{k:02d}"))
        assert len(blanks) == len(asked) == 10
        seen = set()
        for label, answers in blanks:
            name = next(n for n in asked if n in label)
            seen.add(name)
            grade, value, tolerance, feedback = answers[0]
            assert grade == 100.0 and feedback == "Right."
            assert value == pytest.approx(asked[name], rel=1e-5, abs=1e-6)  # the key: six digits
            if "direction" in name:
                assert tolerance >= 2.0 * 0.999
            else:
                assert tolerance >= 0.02 * abs(asked[name]) * 0.999  # 2 %, of at least 1 % of the largest of the kind
            assert all(a[0] in (0.0, 100.0) for a in answers)
        assert seen == set(asked)


def test_moodle_mistakes_are_what_check_makes_of_them(moodle: tuple[Path, str]) -> None:
    folder, _ = moodle
    _, questions = _questions(folder)
    found: set[str] = set()
    for k, question in enumerate(questions, 1):
        name = f"slotted-lever-{k:02d}"
        scene = load_scene(str(folder / f"{name}.toml"))
        checker = make_checker(scene)
        for label, answers in _blanks(question.findtext("questiontext/text") or ""):
            key, part = _parts_of(label)
            right, tolerance = answers[0][1], answers[0][2]
            wrong = [a for a in answers if a[0] == 0.0]
            values = [right, *(a[1] for a in wrong)]
            angle = part == "direction"
            for i, first in enumerate(values):  # none within the tolerance of the right one or of another kept
                for second in values[i + 1:]:
                    assert (_angle_apart(first, second) if angle else abs(first - second)) > tolerance
            for _, value, _, feedback in wrong:
                code = _code_of(feedback)
                found.add(code)
                assert feedback.startswith("Not right: this is the number one gets with a typical mistake: ")
                if part == "value":  # the student's number, checked by kinepoly check: diagnosed as this mistake
                    answers_file = loads_answers(f"{key.text} = {value!r}\n", scene, source="quiz.toml")
                    verdict = next(v for v in check(answers_file, checker).verdicts if v.key == key)
                    assert not verdict.is_correct
                    assert verdict.diagnosis is not None and code in (verdict.diagnosis.code,
                                                                      *verdict.diagnosis.alternatives)
                else:  # a vector's part: that of check's own candidate for the mistake
                    parts = []
                    for candidate in candidates(checker.reference, checker.recomputed, key):
                        x, y = candidate.answer  # type: ignore[misc]
                        if candidate.code == code:
                            parts.append(math.degrees(math.atan2(y, x)) if angle else math.hypot(x, y))
                    assert any((_angle_apart(p, value) if angle else abs(p - value)) <= 1e-5 * max(1.0, abs(value))
                               for p in parts), (name, label, code, value, parts)
    assert {"coriolis-left-out", "coriolis-reversed", "sign-reversed", "kv-not-divided", "ka-not-divided",
            "degrees-for-radians", "other-point"} <= found


def test_the_coriolis_mistake_of_the_slotted_lever(moodle: tuple[Path, str]) -> None:
    """a_A@4: the Coriolis term left out is offered, its number the acceleration polygon constructed without it."""
    folder, _ = moodle
    _, questions = _questions(folder)
    html = questions[0].findtext("questiontext/text") or ""
    blank = next(answers for label, answers in _blanks(html) if label.startswith("|a<sub>A@4</sub>|"))
    coriolis = [a for a in blank if a[0] == 0.0 and _code_of(a[3]) == "coriolis-left-out"]
    assert len(coriolis) == 1
    key = _key(folder, "slotted-lever-01")
    scene = tomllib.loads((folder / "slotted-lever-01.toml").read_text())
    right = math.hypot(*key["a_A@4"])
    # By hand: A (of the block 3) and A@4 coincide; a_A = a_A@4 + a_rel + a_cor with a_cor = 2 omega_4 x v_rel,
    # v_rel = v_A - v_A@4 along the slot, a_A@4 = a^n + a^t with a^t square to B0A. Without a_cor the student's
    # a_A@4' = a_A@4 + a_cor + k * slot, k such that a_A@4' - a_A@4 stays square to B0A (the tangential line).
    omega = key["omega_4"]
    v_rel = (key["v_A"][0] - key["v_A@4"][0], key["v_A"][1] - key["v_A@4"][1])
    a_cor = (-2 * omega * v_rel[1], 2 * omega * v_rel[0])
    crank = scene["links"]["2"]["points"]["A"][0]
    angle = math.radians(scene["input"]["angle"])
    b0 = scene["links"]["1"]["points"]["B0"]
    a_point = (crank * math.cos(angle), crank * math.sin(angle))
    normal = (-(a_point[1] - b0[1]), a_point[0] - b0[0])  # the tangential term's direction

    def cross(u: tuple[float, float], v: tuple[float, float]) -> float:
        return u[0] * v[1] - u[1] * v[0]

    k = -cross(normal, a_cor) / cross(normal, v_rel)
    without = math.hypot(key["a_A@4"][0] + a_cor[0] + k * v_rel[0], key["a_A@4"][1] + a_cor[1] + k * v_rel[1])
    assert coriolis[0][1] == pytest.approx(without, rel=1e-4)
    assert abs(coriolis[0][1] - right) > blank[0][2]


def test_moodle_in_turkish_and_with_a_drawing_tolerance(tmp_path: Path) -> None:
    printed = _make(tmp_path, "--quiz", "moodle", "--lang", "tr", "--tolerance", "0.5mm")
    assert "tolerance 0.5 mm on the paper, language tr" in printed
    _, questions = _questions(tmp_path)
    say = load_catalogue("tr")
    for k, question in enumerate(questions, 1):
        html = question.findtext("questiontext/text") or ""
        assert say.say("problem.find") in html and say.say("quiz.answers") in html
        kv = float(re.search(r"kv = ([0-9,]+) mm", html).group(1).replace(",", "."))  # type: ignore[union-attr]
        scene = tomllib.loads((tmp_path / f"slotted-lever-{k:02d}.toml").read_text())
        lever = math.dist(*scene["links"]["4"]["points"].values())  # link 4's longest (only) dimension, B0F
        velocities = {f"v<sub>{p[2:]}</sub>": math.hypot(*v) for p, v in
                      (item for item in _key(tmp_path, f"slotted-lever-{k:02d}").items() if item[0].startswith("v_"))}
        checked = 0
        for label, answers in _blanks(html):
            assert answers[0][3] == say.say("quiz.right")
            tolerance = answers[0][2]
            if label.startswith("|v<sub>"):  # 0.5 mm of the velocity polygon
                assert tolerance == pytest.approx(0.5 / kv, rel=1e-5)
                checked += 1
            elif label.startswith("ω<sub>14</sub>"):  # omega = v / B0F: 0.5 mm of v over kv B0F
                assert tolerance == pytest.approx(0.5 / (kv * lever), rel=1e-5)
                checked += 1
            elif label.startswith("v<sub>"):  # a direction: the angle 0.5 mm subtends at the tip
                name = label.split(" ", 1)[0]
                assert tolerance == pytest.approx(math.degrees(math.atan2(0.5, velocities[name] * kv)), rel=1e-4)
                checked += 1
        assert checked == 5


# --------------------------------------------------------------------------------------------
# Canvas (QTI by text2qti)


def _package(folder: Path) -> zipfile.ZipFile:
    return zipfile.ZipFile(folder / "slotted-lever.qti.zip")


def test_qti_package_unpacks_into_what_canvas_reads(canvas: tuple[Path, str]) -> None:
    folder, _ = canvas
    with _package(folder) as package:
        names = package.namelist()
        manifest = ET.fromstring(package.read("imsmanifest.xml"))
        ns = {"m": "http://www.imsglobal.org/xsd/imsccv1p1/imscp_v1p1"}
        hrefs = [f.get("href") for f in manifest.iterfind(".//m:resource/m:file", ns)]
        assert hrefs and all(href in names for href in hrefs)
        assessment = next(h for h in hrefs if h and h.endswith(".xml") and "assessment_meta" not in h)
        root = ET.fromstring(package.read(assessment))
        for k in range(1, COUNT + 1):
            data = package.read(f"images/slotted-lever-{k:02d}.png")
            assert data.startswith(PNG)
    items = root.findall(".//{*}item")
    texts = [i for i in items if "text2qti_text_" in (i.get("ident") or "")]
    questions = [i for i in items if "text2qti_question_" in (i.get("ident") or "")]
    assert len(texts) == COUNT and len(questions) == COUNT * 10
    for k, text in enumerate(texts, 1):
        assert text.get("title") == f"slotted-lever-{k:02d}: variant {k} of {COUNT}, seed 7"
        assert f"images/slotted-lever-{k:02d}.png" in ET.tostring(text, encoding="unicode")
    for question in questions:
        title = question.get("title") or ""
        name = title.split(":")[0]
        key = _key(folder, name)
        asked = title.rsplit(": ", 1)[1]
        if asked.endswith((" magnitude", " direction")):
            vector = key[asked.split()[0]]
            right = math.hypot(*vector) if asked.endswith("magnitude") else math.degrees(math.atan2(vector[1],
                                                                                                   vector[0]))
        else:
            right = key[asked]
        low = float(question.findtext(".//{*}vargte") or "nan")
        high = float(question.findtext(".//{*}varlte") or "nan")
        assert low < right < high
        if not asked.endswith("direction"):  # 2 % of the value (of at least 1 % of the largest of its kind)
            assert (high - low) / 2 >= 0.02 * abs(right) - 1e-4


def test_qti_lists_the_typical_mistakes_in_the_incorrect_feedback(canvas: tuple[Path, str]) -> None:
    folder, _ = canvas
    with _package(folder) as package:
        assessment = next(n for n in package.namelist() if n.endswith(".xml") and "text2qti_assessment_" in n
                          and "assessment_meta" not in n)
        root = ET.fromstring(package.read(assessment))
    question = next(i for i in root.iterfind(".//{*}item") if i.get("title", "").endswith("a_A@4 magnitude"))
    feedback = " ".join(m.text or "" for m in question.iterfind(".//{*}itemfeedback//{*}mattext"))
    assert "Typical mistakes give these numbers" in feedback
    assert SAY.say("quiz.coriolis_left_out") in feedback


def test_qti_quiz_text_passes_text2qtis_own_command(tmp_path: Path) -> None:
    """The text kinepoly hands text2qti, run through text2qti's own command line: it makes the same package."""
    pytest.importorskip("text2qti")
    from kinepoly.homework.canvas import quiz_text
    from kinepoly.homework.quiz import QuizTolerance, make_quiz
    from kinepoly.homework.variants import make_variants
    from kinepoly.homework.vary import default_ranges

    scene = load_scene(SLOTTED)
    variants = make_variants(scene, default_ranges(scene), 1, 7)
    quiz = make_quiz(variants, "slotted-lever", 7, QuizTolerance(), SAY)
    figures = {}
    for question in quiz.questions:
        figures[question.figure_name] = tmp_path / question.figure_name
        figures[question.figure_name].write_bytes(question.figure)
    source = tmp_path / "slotted-lever.txt"
    source.write_text(quiz_text(quiz, SAY, figures))
    command = [sys.executable, "-c", "import sys; from text2qti.cmdline import main; sys.exit(main())", source.name]
    done = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    with zipfile.ZipFile(tmp_path / "slotted-lever.zip") as package:
        assert "imsmanifest.xml" in package.namelist()


# --------------------------------------------------------------------------------------------
# Bad input, and files whole or not at all


@pytest.mark.parametrize(("options", "says"), [
    (("--quiz", "kahoot"), "invalid choice: 'kahoot'"),
    (("--quiz", "moodle", "--tolerance", "2"), "--tolerance: '2' is not a tolerance"),
    (("--quiz", "moodle", "--tolerance", "0%"), "--tolerance: '0%'"),
    (("--quiz", "moodle", "--tolerance", "60%"), "expected a percentage"),
    (("--quiz", "moodle", "--lang", "xx"), "xx"),
])
def test_bad_quiz_options_exit_2_and_write_nothing(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                   options: tuple[str, ...], says: str) -> None:
    folder = tmp_path / "out"
    code, _, err = run(capsys, "variants", SLOTTED, "--n", "1", "-o", str(folder), *options)
    assert code == 2 and says in err and "Traceback" not in err
    assert not folder.exists()


def test_qti_without_text2qti_says_how_to_install_it(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "text2qti", None)  # import text2qti raises ImportError
    folder = tmp_path / "out"
    code, _, err = run(capsys, "variants", SLOTTED, "--n", "1", "-o", str(folder), "--quiz", "qti")
    assert code == 2 and "pip install 'kinepoly[quiz]'" in err and "--quiz moodle" in err
    assert not folder.exists()


def test_a_quiz_that_fails_leaves_no_file(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                          monkeypatch: pytest.MonkeyPatch) -> None:
    import kinepoly.homework.moodle

    def broken(*_: object) -> bytes:
        raise RuntimeError("broken")

    monkeypatch.setattr(kinepoly.homework.moodle, "moodle_xml", broken)
    folder = tmp_path / "out"
    code, _, err = run(capsys, "variants", SLOTTED, "--n", "1", "-o", str(folder), "--quiz", "moodle")
    assert code == 70 and "broken" in err
    assert not folder.exists()


def test_the_worked_example_in_the_docs_is_what_the_command_writes(moodle: tuple[Path, str]) -> None:
    folder, printed = moodle
    doc = (Path(__file__).resolve().parents[2] / "docs" / "quiz.md").read_text()
    block = doc[doc.index("<!-- quiz example: begin -->"):doc.index("<!-- quiz example: end -->")]
    blank = block.split("```text\n", 1)[1].split("\n```", 1)[0]
    _, questions = _questions(folder)
    assert f"|a<sub>A@4</sub>| in mm/s²: {blank}</p>" in (questions[0].findtext("questiontext/text") or "")
    shown = [line for line in doc.splitlines() if line.startswith("  slotted-lever-01 ")]
    assert len(shown) == 3 and all(line in printed.splitlines() for line in shown)


# --------------------------------------------------------------------------------------------
# The embedded-answers text, for any words and numbers


_WORDS = st.text(alphabet=st.sampled_from(list("ab }#~/\"\\{<&>%=:;ωα²−")), min_size=1, max_size=30)


@settings(max_examples=60, deadline=None)
@given(value=st.floats(-1e5, 1e5, allow_nan=False), tolerance=st.floats(1e-3, 50.0), angle=st.booleans(),
       wrong=st.lists(st.tuples(_WORDS, st.floats(-1e5, 1e5, allow_nan=False)), max_size=4), title=_WORDS)
def test_any_words_and_numbers_read_back_from_the_moodle_xml(value: float, tolerance: float, angle: bool,
                                                              wrong: list[tuple[str, float]], title: str) -> None:
    from kinepoly.homework.moodle import moodle_xml
    from kinepoly.homework.quiz import Quantity, Question, Quiz, Wrong

    if angle:
        value = math.remainder(value, 360.0)
    quantity = Quantity("v_A", "direction" if angle else "magnitude", "|v_A| in mm/s:", value, tolerance,
                        tuple(Wrong("other-point", words, number) for words, number in wrong), (), angle)
    question = Question("s-01", title, "<p>statement</p>", PNG, (quantity,))
    root = ET.fromstring(moodle_xml(Quiz("s", title, "en", (question,)), SAY))
    element = root.find("question[@type='cloze']")
    assert element is not None and element.findtext("name/text") == title
    html = element.findtext("questiontext/text") or ""
    [(_, answers)] = _blanks(html)
    right = [a for a in answers if a[0] == 100.0]
    assert right[0][1] == pytest.approx(value, rel=1e-7, abs=1e-9) and right[0][3] == "Right."
    assert all(a[2] == pytest.approx(tolerance, rel=1e-5) for a in answers)
    wraps = angle and abs(value) + tolerance > 180.0
    assert len(right) == (2 if wraps else 1)
    if wraps:  # the same direction written 360 degrees away is right too
        assert abs(right[1][1] - right[0][1]) == pytest.approx(360.0)
    offered = [a for a in answers if a[0] == 0.0]
    assert len(offered) == len(wrong)
    for (words, number), (_, read, _, feedback) in zip(wrong, offered, strict=True):
        assert read == pytest.approx(number, rel=1e-7, abs=1e-9)
        assert html_module.unescape(feedback) == SAY.say("quiz.mistake", mistake=words)


def test_a_scene_that_asks_only_instant_centers_has_no_quiz(capsys: pytest.CaptureFixture[str],
                                                             tmp_path: Path) -> None:
    text = (EXAMPLES / "four-bar.toml").read_text()
    scene = tmp_path / "centers.toml"
    scene.write_text(text[:text.index("[find]")] + '[find]\ninstant_centers = "all"\n')
    folder = tmp_path / "out"
    code, _, err = run(capsys, "variants", str(scene), "--n", "1", "-o", str(folder), "--quiz", "moodle")
    assert code == 2 and "the quiz has no number to ask" in err
    assert not folder.exists()


def test_a_mistake_the_catalogue_does_not_name_keeps_checks_words() -> None:
    """A mistake code check learns later is offered with check's own words until the catalogues name it."""
    from kinepoly.homework.diagnose import Candidate
    from kinepoly.homework.quiz import _words
    from kinepoly.homework.reference import prepare

    reference = prepare(load_scene(SLOTTED))
    key = AnswerKey("alpha", "4")
    new = Candidate("image-reversed", "the image triangle turned the wrong way", 1.0)
    assert _words(reference, key, new, SAY) == "the image triangle turned the wrong way"
    known = Candidate("coriolis-left-out", "check's words", 1.0)
    assert _words(reference, key, known, SAY) == SAY.say("quiz.coriolis_left_out")
