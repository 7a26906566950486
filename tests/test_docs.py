"""The documentation states the present: the README is short enough to read, no commit hash is left
in the README, docs/ or a study's README (history lives in git), every relative link resolves, each
study's README names the command that re-measures its numbers, and the README's Python example
does what its comments say."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
STUDIES = sorted(p.parent for p in ROOT.glob("*/*/README.md") if p.parts[-3] in ("verification", "validation"))


#: a commit hash as the repository's before-stop hook finds one: a word of 7-12 hex digits, not part
#: of a path, a number or an identifier, with at least one digit and one letter
HASH = re.compile(r"(?:^|[^0-9a-zA-Z_/.-])([0-9a-f]{7,12})(?=[^0-9a-zA-Z_]|$)", re.M)


def documents():
    """README.md, docs/*.md and the studies' READMEs, as paths relative to the repository."""
    paths = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")), *(s / "README.md" for s in STUDIES)]
    return [str(p.relative_to(ROOT)) for p in paths]


def test_readme_is_at_most_300_lines():
    assert len((ROOT / "README.md").read_text().splitlines()) <= 300


def test_the_architecture_is_at_most_350_lines():
    assert len((ROOT / "docs" / "architecture.md").read_text().splitlines()) <= 350


@pytest.mark.parametrize("name", documents())
def test_no_commit_hash_in_the_docs(name):
    text = (ROOT / name).read_text()
    hashes = [w for w in HASH.findall(text) if re.search("[0-9]", w) and re.search("[a-f]", w)]
    assert hashes == [], f"{name}: {hashes}"


def test_the_hash_pattern_finds_a_hash_and_spares_numbers_and_paths():
    """The check above could pass by matching nothing: it finds a short hash in prose and leaves
    alone decimal numbers, hex colours in paths and identifiers."""
    found = [w for w in HASH.findall("measured on 1e16960 and (ae66515); see a/b3c4d5e6f/x 1234567 ab_c1d2e3f4")
             if re.search("[0-9]", w) and re.search("[a-f]", w)]
    assert found == ["1e16960", "ae66515"]


@pytest.mark.parametrize("name", documents())
def test_relative_links_resolve(name):
    """Every Markdown link to a file of the repository (not a web address, not an anchor alone)
    points at a file that exists."""
    path = ROOT / name
    missing = []
    for target in re.findall(r"\]\(([^)\s]+)\)", path.read_text()):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        if not (path.parent / target.split("#")[0]).exists():
            missing.append(target)
    assert missing == [], f"{name}: {missing}"


@pytest.mark.parametrize("study", STUDIES, ids=[f"{s.parent.name}/{s.name}" for s in STUDIES])
def test_each_study_readme_names_the_command_that_remeasures_it(study):
    text = (study / "README.md").read_text()
    assert f"python -m {study.parent.name}.{study.name}." in text


def test_readme_python_example_does_what_its_comments_say(tmp_path):
    """The README's first Python block, run as written from a folder holding the examples: the
    tension it prints is the static one the run starts from (the first row of tensions.csv), and the
    picture it names is written."""
    readme = (ROOT / "README.md").read_text()
    block = next(b for b in re.findall(r"```python\n(.*?)```", readme, re.S) if "run_scene(" in b)
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    script = tmp_path / "example.py"
    script.write_text(block)
    out = subprocess.run([sys.executable, str(script)], cwd=tmp_path, check=True, capture_output=True,
                         text=True, timeout=600).stdout
    printed = float(out.split()[0])
    picture = re.search(r"# (out-flat/\S+\.png)", block).group(1)
    assert (tmp_path / picture).is_file()
    rows = (tmp_path / "out-flat" / "tensions.csv").read_text().splitlines()
    header, first = rows[0].split(","), rows[1].split(",")
    assert float(first[header.index("fairlead_tension")]) == pytest.approx(printed, rel=1e-9)
