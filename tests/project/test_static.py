"""Every name the three packages, the tests and the benchmarks use is defined: pyflakes'
undefined-name and undefined-export reports are zero (a name used only on a rarely taken
branch, a readout of the explore page say, fails here rather than in a user's hands)."""

from __future__ import annotations

from pathlib import Path

from pyflakes import api, messages
from pyflakes.reporter import Reporter

ROOT = Path(__file__).resolve().parents[2]
FATAL = (messages.UndefinedName, messages.UndefinedExport, messages.UndefinedLocal)


class _Collect(Reporter):
    def __init__(self):
        self.found: list[str] = []

    def flake(self, message):
        if isinstance(message, FATAL):
            self.found.append(str(message))

    def unexpectedError(self, filename, msg):
        self.found.append(f"{filename}: {msg}")

    def syntaxError(self, filename, msg, lineno, offset, text):
        self.found.append(f"{filename}:{lineno}: {msg}")


def test_no_undefined_name():
    rep = _Collect()
    files = [p for d in ("analytic", "skfem_dielectric", "validation", "tests", "benchmarks")
             for p in sorted((ROOT / d).rglob("*.py"))]
    assert len(files) > 100
    for path in files:
        api.checkPath(str(path), rep)
    assert not rep.found, "\n".join(rep.found)


def test_the_check_sees_an_undefined_name(tmp_path):
    """The rule can fail: a module using a name it never imports is reported."""
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    return BUCKLING_NAME\n")
    rep = _Collect()
    api.checkPath(str(bad), rep)
    assert len(rep.found) == 1 and "BUCKLING_NAME" in rep.found[0]


def test_ruff_finds_nothing():
    """``ruff check`` with the rules of pyproject.toml (pyflakes': unused imports and
    variables, undefined names, f-strings without placeholders; the import rules E401 and
    E402) over the packages, the tests, the benchmarks and the examples: no finding."""
    import shutil
    import subprocess
    import sys

    ruff = shutil.which("ruff") or str(Path(sys.executable).parent / "ruff")
    if not Path(ruff).exists():
        import pytest

        pytest.skip("ruff is not installed (the test extra installs it)")
    out = subprocess.run([ruff, "check", "--no-cache", "analytic", "skfem_dielectric",
                          "validation", "tests", "benchmarks", "docs/examples"],
                         cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


def test_ruff_applies_the_import_rules(tmp_path):
    """The project's ruff rules flag an import after code (E402), two modules in one
    import (E401) and an unused import (F401) in a file that has each once."""
    import shutil
    import subprocess
    import sys

    import pytest

    ruff = shutil.which("ruff") or str(Path(sys.executable).parent / "ruff")
    if not Path(ruff).exists():
        pytest.skip("ruff is not installed (the test extra installs it)")
    bad = tmp_path / "bad.py"
    bad.write_text("import os, sys\nprint(os.sep, sys.argv)\nimport json\n")
    out = subprocess.run([ruff, "check", "--no-cache", "--config",
                          str(ROOT / "pyproject.toml"), "--output-format", "concise",
                          str(bad)], capture_output=True, text=True)
    codes = sorted(ln.split()[1] for ln in out.stdout.splitlines() if "bad.py:" in ln)
    assert codes == ["E401", "E402", "F401"], out.stdout
