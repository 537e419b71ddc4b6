"""The README's two set-up commands: the test command is what CI runs, the main job parses."""

import shlex
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


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
