"""The documentation speaks of the project only: no files outside the repository, no
references to how the team works."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
_GENERATED = ("_build", "auto_examples", "generated")
FILES = [ROOT / "README.md"] + sorted(
    p for p in (ROOT / "docs").rglob("*")
    if p.is_file() and p.suffix in (".md", ".py", ".rst", ".txt")
    and not any(part in _GENERATED for part in p.relative_to(ROOT / "docs").parts))

FORBIDDEN = {
    "design notes outside the repository": re.compile(r"DESIGN(\.md|\s*§)"),
    "a shared folder outside the repository": re.compile(r"\.\./shared"),
    "a LaTeX source": re.compile(r"\.tex\b"),
    "an issue number": re.compile(r"\bissues?\s*#?\s*\d+", re.I),
    "a team member": re.compile(r"\bhelpers?\s+[A-Z0-9]\b"),
    "the team's process": re.compile(r"\b(work\s+)?sessions?\b", re.I),
}


@pytest.mark.parametrize("path", FILES, ids=[str(p.relative_to(ROOT)) for p in FILES])
def test_no_outside_references(path):
    text = path.read_text()
    for what, pattern in FORBIDDEN.items():
        m = pattern.search(text)
        assert m is None, f"{path.relative_to(ROOT)} mentions {what}: {m.group(0)!r}"


def test_the_patterns_catch_what_they_should():
    samples = {"see DESIGN.md": "design", "in ../shared/x": "shared", "paper.tex": "LaTeX",
               "fixes issue 12": "issue", "Issue #3": "issue", "helper B wrote": "team",
               "in this session": "process"}
    for text in samples:
        assert any(p.search(text) for p in FORBIDDEN.values()), text
    assert not any(p.search("the tests and the text of the paper") for p in FORBIDDEN.values())
