"""Every code block of README.md and docs/*.md runs as written, or says why it does not.

Rules (checked here):

* every fenced block names its language; ``text`` (formulas, diagrams, synopses) and MyST
  directives (```` ```{toctree} ````) are not code;
* ``python`` blocks run top to bottom, one namespace per page (a page reads like one
  session), in a temporary folder with the Agg backend (no timing: speed is measured in
  ``benchmarks/``, never in the suite);
* ``bash`` blocks run line by line in a temporary folder with this interpreter's
  ``bin`` first on ``PATH``;
* a block right after ``<!-- not run: <reason> -->`` is skipped (the reason is required);
* indented code blocks are not allowed (except the README's two set-up commands, which
  ``.ci/run`` runs and ``tests/docs/test_readme.py`` checks).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
#: a hang guard for a bash block, not a speed check (speed is measured in benchmarks/)
HANG_TIMEOUT = 1800.0
NOT_CODE = ("text",)
RUN = ("python", "bash")
_FENCE = re.compile(r"^(?P<indent> {0,3})(?P<fence>`{3,})(?P<info>[^`\n]*)$")
_NOT_RUN = re.compile(r"<!--\s*not run:\s*(?P<reason>\S.*?)\s*-->")


def blocks(path: Path) -> list[dict]:
    """The fenced blocks of a page: language, body, first line, not-run reason."""
    lines = path.read_text().splitlines()
    out, i = [], 0
    while i < len(lines):
        m = _FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, fence, info = len(m["indent"]), m["fence"], m["info"].strip()
        j = i + 1
        while j < len(lines) and not lines[j].strip().startswith(fence):
            j += 1
        body = "\n".join(ln[indent:] if ln[:indent].strip() == "" else ln
                         for ln in lines[i + 1:j])
        k = i - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        note = _NOT_RUN.search(lines[k]) if k >= 0 else None
        out.append({"lang": info.split()[0] if info else "", "body": body, "line": i + 1,
                    "not_run": note["reason"] if note else None})
        i = j + 1
    return out


def indented_code(path: Path) -> list[int]:
    """First lines of indented code blocks outside fences, lists and tables."""
    lines = path.read_text().splitlines()
    if path.name == "README.md":                 # the two set-up commands on top
        first_rule = next(i for i, ln in enumerate(lines) if ln.strip() == "---")
        skip = set(range(first_rule))
    else:
        skip = set()
    found, fenced, context = [], False, ""
    for i, ln in enumerate(lines):
        if _FENCE.match(ln):
            fenced = not fenced
            continue
        if fenced or i in skip:
            continue
        if ln.strip():
            if not ln.startswith("    "):
                context = ln
            elif (i > 0 and not lines[i - 1].strip()
                  and not re.match(r"\s*([-*+]|\d+\.)\s", context)):
                found.append(i + 1)
    return found


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_blocks_are_declared(page):
    for b in blocks(page):
        assert b["lang"], f"{page.name}:{b['line']}: fenced block without a language"
        assert b["lang"] in NOT_CODE + RUN or b["lang"].startswith("{"), \
            f"{page.name}:{b['line']}: unknown block language {b['lang']!r}"
    assert not indented_code(page), \
        f"{page.name}: indented code at lines {indented_code(page)} (use a fenced block)"


def _pages_with(lang):
    return [p for p in PAGES if any(b["lang"] == lang and not b["not_run"] for b in blocks(p))]


@pytest.mark.parametrize("page", _pages_with("python"), ids=lambda p: p.name)
def test_python_blocks_run(page, tmp_path, monkeypatch):
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    ns: dict = {"__name__": "__docs__"}
    for b in blocks(page):
        if b["lang"] != "python" or b["not_run"]:
            continue
        try:
            exec(compile(b["body"], f"{page.name}:{b['line']}", "exec"), ns)
        except Exception as exc:                    # name the block in the failure
            raise AssertionError(f"{page.name}:{b['line']}: {type(exc).__name__}: "
                                 f"{str(exc)[:300]}") from exc
    plt.close("all")


@pytest.mark.parametrize("page", _pages_with("bash"), ids=lambda p: p.name)
def test_bash_blocks_run(page, tmp_path):
    env = dict(os.environ, PATH=str(Path(sys.executable).parent) + os.pathsep
               + os.environ.get("PATH", ""), MPLBACKEND="Agg")
    for b in blocks(page):
        if b["lang"] != "bash" or b["not_run"]:
            continue
        r = subprocess.run(["bash", "-euo", "pipefail", "-c", b["body"]], cwd=tmp_path,
                           env=env, capture_output=True, text=True, timeout=HANG_TIMEOUT)
        assert r.returncode == 0, f"{page.name}:{b['line']}: {r.stderr[-500:]}"


def test_not_run_markers_give_a_reason():
    for page in PAGES:
        for m in re.finditer(r"<!--\s*not run\b(?P<rest>[^>]*)-->", page.read_text()):
            assert _NOT_RUN.search(m.group(0)), f"{page.name}: 'not run' without a reason"


#: a command of the pages and the path it is given (``--out``, ``--export``, ``--results``)
_PATH_OPTION = re.compile(r"skfem-dielectric\s+(?P<cmd>[\w-]+)[^\n`|]*?"
                          r"--(?P<opt>out|export|results)\s+(?P<path>[^\s`|)\]]+)")
_PLACEHOLDERS = {"DIR", "FILE.html", "''"}


def test_commands_write_into_ignored_folders():
    """Every path a command of the README or docs writes (``--out``, ``--export``) lies in a
    folder that ``.gitignore`` ignores, so that running the pages leaves the checkout
    clean; every ``--results`` folder is one that a ``validate`` of the pages writes."""
    ignored = {ln.strip().strip("/") for ln in ROOT.joinpath(".gitignore").read_text()
               .splitlines() if ln.strip().endswith("/") and ln[:1] not in "!#"}
    written, read, outside = set(), [], []
    for page in PAGES:
        text = page.read_text().replace("\\\n", " ")         # continued command lines
        for m in _PATH_OPTION.finditer(text):
            path = m["path"]
            if path in _PLACEHOLDERS:
                continue
            if m["opt"] == "results":
                read.append((page.name, path))
                continue
            if Path(path).parts[0] not in ignored:
                outside.append(f"{page.name}: {m.group(0)}")
            if m["cmd"] == "validate":
                written.add(path)
    assert not outside, "writes into the checkout: " + "; ".join(outside)
    assert read and all(path in written for _, path in read), (read, written)
