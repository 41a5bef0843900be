"""The pages' scripts and styles are package files (``static/`` of kinepoly.handout and kinepoly.motion), shipped
by pyproject.toml's package-data and read through importlib.resources, so that an installed package reads them:
checked on a zip laid out as a wheel is (the modules and the package-data files), imported by zipimport, where
no file of the package has a path on disk."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOURCE = ROOT / "src"
PAGES = {"kinepoly.handout": ("handout.css", "handout.js"), "kinepoly.motion": ("animation.css", "animation.js")}


def _package_data() -> dict[str, list[str]]:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    data: dict[str, list[str]] = project["tool"]["setuptools"]["package-data"]
    return data


def _wheel_like(target: Path) -> Path:
    """The package as a wheel holds it: every module, and the files package-data names."""
    out = target / "kinepoly-installed.zip"
    with zipfile.ZipFile(out, "w") as archive:
        for module in sorted((SOURCE / "kinepoly").rglob("*.py")):
            archive.write(module, module.relative_to(SOURCE).as_posix())
        for package, globs in _package_data().items():
            folder = SOURCE.joinpath(*package.split("."))
            for pattern in globs:
                for path in sorted(folder.glob(pattern)):
                    archive.write(path, path.relative_to(SOURCE).as_posix())
    return out


def test_every_file_of_the_pages_static_folders_is_package_data() -> None:
    data = _package_data()
    for package, names in PAGES.items():
        folder = SOURCE.joinpath(*package.split("."))
        shipped = {path for pattern in data[package] for path in folder.glob(pattern)}
        assert shipped == set((folder / "static").iterdir())
        assert {path.name for path in shipped} == set(names)


def test_an_installed_package_reads_the_pages_files_through_importlib_resources(tmp_path: Path) -> None:
    archive = _wheel_like(tmp_path)
    probe = (
        "import sys, kinepoly, kinepoly.assets as a\n"
        f"assert kinepoly.__file__.startswith({str(archive)!r}), kinepoly.__file__\n"
        f"for package, names in {PAGES!r}.items():\n"
        "    for name in names:\n"
        "        sys.stdout.write(f'{package} {name} {len(a.static_text(package, name))}\\n')\n"
    )
    env = {**os.environ, "PYTHONPATH": str(archive)}
    done = subprocess.run([sys.executable, "-c", probe], check=False, env=env, capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    read = {tuple(line.split()[:2]): int(line.split()[2]) for line in done.stdout.splitlines()}
    expected = {(package, name): len((SOURCE.joinpath(*package.split("."), "static", name)).read_text("utf-8"))
                for package, names in PAGES.items() for name in names}
    assert read == expected and all(size > 100 for size in read.values())


def test_the_handout_page_carries_its_files_whole_and_no_file_ends_its_element_early() -> None:
    from kinepoly.handout.html import handout_html
    from kinepoly.present.catalogue import load_catalogue
    from kinepoly.scene.loader import load_scene
    from kinepoly.solution import solve

    files = {(package, name): SOURCE.joinpath(*package.split("."), "static", name).read_text("utf-8")
             for package, names in PAGES.items() for name in names}
    for (_package, name), text in files.items():
        assert ("</script" if name.endswith(".js") else "</style") not in text.lower()
    _handout, page = handout_html(solve(load_scene(str(ROOT / "examples" / "four-bar.toml"))), load_catalogue("en"))
    assert f"<style>\n{files['kinepoly.handout', 'handout.css']}</style>" in page
    assert f"<script>\n{files['kinepoly.handout', 'handout.js']}</script>" in page
