"""The README's two set-up commands: the test command is what CI runs, the main job parses,
and the package they install declares its licence as current build tools read it."""

import re
import shlex
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _readme_commands() -> list[str]:
    """Indented (code) lines at the top of README.md, before the first horizontal rule."""
    top = ROOT.joinpath("README.md").read_text().split("\n---", 1)[0]
    return [ln.strip() for ln in top.splitlines() if ln.startswith("    ") and ln.strip()]


def test_readme_test_command_is_the_ci_command():
    ci = [ln.strip() for ln in ROOT.joinpath(".ci", "run").read_text().splitlines()
          if ln.strip() and not ln.lstrip().startswith("#")
          and not ln.startswith(("set ", "cd "))]
    cmds = _readme_commands()
    assert len(cmds) == 2, cmds                       # exactly two set-up commands
    assert ci[-1] == cmds[1]


def test_readme_main_job_is_a_valid_validate_call():
    from validation.cli import build_parser

    main_job = _readme_commands()[0]
    last = main_job.split("&&")[-1].strip()
    argv = shlex.split(last)
    assert argv[0] == "skfem-dielectric"
    args = build_parser().parse_args(argv[1:])
    assert args.command == "validate" and args.quick and args.out == Path("results")


def test_pyproject_license_is_an_spdx_expression():
    """``project.license`` as a TOML table is deprecated by setuptools (a warning on every
    ``pip install``/``pip wheel``): an SPDX string with ``license-files``, which needs
    setuptools >= 77 in the build system."""
    tomllib = pytest.importorskip("tomllib")          # Python >= 3.11
    meta = tomllib.loads(ROOT.joinpath("pyproject.toml").read_text())
    project = meta["project"]
    assert project["license"] == "BSD-3-Clause"
    assert ROOT.joinpath("LICENSE").read_text().startswith("BSD 3-Clause License\n")
    assert project["license-files"] == ["LICENSE"]
    assert not any(c.startswith("License ::") for c in project.get("classifiers", []))
    (setuptools,) = [r for r in meta["build-system"]["requires"] if r.startswith("setuptools")]
    low = re.fullmatch(r"setuptools>=(\d+)(\.\d+)*", setuptools.replace(" ", ""))
    assert low and int(low.group(1)) >= 77, setuptools
    assert project["requires-python"] == ">=3.10"


def test_readme_fe_snippet_has_one_stretch_per_charge_target(tmp_path, monkeypatch):
    """The README's finite-element block run as written (after its theory block, one
    namespace as a reader's session): ``lam1`` has one entry per ``D0`` and equals the
    equi-biaxial loading curve ``lam^6 - s lam^5 - 1 = D0^2`` (Eq. (loading_gent),
    neo-Hookean) solved here with brentq, independently of ``analytic``."""
    from scipy.optimize import brentq
    from test_docs_snippets import blocks

    monkeypatch.chdir(tmp_path)
    python = [b for b in blocks(ROOT / "README.md") if b["lang"] == "python"]
    fe_block = next(b for b in python if "equibiaxial_plate" in b["body"])
    assert "targets_only=True" in fe_block["body"] and "assert" in fe_block["body"]
    ns: dict = {}
    for b in python[:python.index(fe_block) + 1]:
        exec(compile(b["body"], f"README.md:{b['line']}", "exec"), ns)
    s = 1.5
    ref = [brentq(lambda lam, d=d: lam**6 - s * lam**5 - 1 - d**2, 1.0, 10.0, xtol=1e-15)
           for d in ns["D0"]]
    assert len(ns["lam1"]) == len(ns["D0"]) == 4
    assert max(abs(a - b) for a, b in zip(ns["lam1"], ref)) < 1e-10
    assert len(ns["res"].column("lam1")) == 7


#: a cost figure in prose: a number with a time unit ("74 s CPU", "3 minutes", "2 CPU minutes")
_COST = re.compile(r"\b\d+(?:\.\d+)?\s*(?:CPU\s+)?(?:s|sec|seconds?|min|minutes?|h|hours?)\b")


def readme_commands() -> list[str]:
    """The commands the README shows, as written: the last command of each set-up line
    (the main job, the test suite), the site build and every ``skfem-dielectric`` line of
    the command-line block (comments dropped)."""
    text = ROOT.joinpath("README.md").read_text()
    cmds = [c.split("&&")[-1].strip() for c in _readme_commands()]
    cmds += [ln.split("&&")[-1].strip() for ln in text.splitlines()
             if ln.startswith("pip install") and "sphinx-build" in ln]
    cmds += [ln.split("#")[0].strip() for ln in text.splitlines()
             if ln.startswith("skfem-dielectric ")]
    return cmds


def costs_table() -> dict[str, list[str]]:
    """The rows of docs/costs.md of the README's commands: command -> the other cells (the
    rows of the lecture's demos, "(lecture demo N)", are tests/docs/test_lecture.py's)."""
    rows = {}
    for ln in ROOT.joinpath("docs", "costs.md").read_text().splitlines():
        if ln.startswith("| `") and "(lecture demo " not in ln:
            cells = [c.strip() for c in ln.strip().strip("|").split("|")]
            rows[cells[0].split("`")[1]] = cells[1:]
    return rows


def test_readme_states_no_costs_and_the_table_has_every_command():
    """Costs are stated once, in the generated docs/costs.md: the README points to it and
    quotes no CPU or wall time; the table has a row (measured, or saying how to measure it)
    for every command the README shows, and counts the tests."""
    text = ROOT.joinpath("README.md").read_text()
    assert not _COST.findall(text), _COST.findall(text)
    assert "(docs/costs.md)" in text
    cmds = readme_commands()
    assert "skfem-dielectric validate --quick --out results" in cmds
    assert "python -m pytest" in cmds and len(cmds) == 10, cmds
    table = costs_table()
    assert sorted(table) == sorted(cmds)
    for cmd, cells in table.items():
        if cells[0] != "not measured":
            cpu, wall = float(cells[0]), float(cells[1])
            assert cpu > 0 and wall > 0 and cells[3].endswith(" MB"), (cmd, cells)
    count = re.search(r"runs (\d+) tests; `python -m pytest -m slow` runs the other (\d+)",
                      " ".join(ROOT.joinpath("docs", "costs.md").read_text().split()))
    assert count and int(count[1]) > 1000, "docs/costs.md: no test count"


def test_cost_pattern_catches_the_figures_it_should():
    for prose in ("(74 s CPU)", "about 3 minutes of CPU", "2 CPU minutes", "44 min CPU",
                  "170.4 s"):
        assert _COST.search(prose), prose
    for prose in ("100 x 50 x 1 mm", "150 g", "1e-12", "fourteen examples", "D0 = 5.1"):
        assert not _COST.search(prose), prose


def test_the_test_count_of_costs_md_is_this_suites(request):
    """docs/costs.md's test count (written by ``benchmarks/bench_costs.py`` from
    ``pytest --collect-only``) is the number of tests this run of the whole default suite
    runs; a run of part of the suite, or of another selection, cannot say."""
    cfg = request.config
    testpaths = [str(p) for p in cfg.getini("testpaths")]
    whole = (list(cfg.args) in ([], testpaths, [str(ROOT / p) for p in testpaths])
             and not cfg.getoption("keyword") and cfg.getoption("markexpr") == "not slow")
    if not whole:
        pytest.skip("not the whole default suite")
    m = re.search(r"`python -m pytest` runs (\d+) tests", (ROOT / "docs" / "costs.md")
                  .read_text())
    assert m, "no test count on docs/costs.md"
    assert int(m.group(1)) == len(request.session.items), (
        "rerun python benchmarks/bench_costs.py --only list (it counts the tests again)")
