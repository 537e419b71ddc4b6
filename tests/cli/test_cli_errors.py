"""The command line's errors: one line on stderr, a documented exit code, no traceback.

Includes a seeded fuzz test: a few hundred generated bad invocations, each of which
must end with a documented exit code and a one-line message (or, for ``--help`` and
``--version``, exit 0), without running the FE solver.
"""

from __future__ import annotations

import errno
import os
import random
import re

import pytest

from validation import cases as vc
from validation.store import case_files
from validation.cli import EXIT_CODES, build_parser, main
from validation.fe import pardiso_installed
from validation.store import FolderLock


def tiny_case(name="nh-d-e"):
    """One real FE ramp on the one-element equi-biaxial plate (well under a second)."""
    runs = (vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 1.0, (0.0, 1.0, 2.0)),)
    return vc.Case(name, name, "test", "equibiaxial", quick=runs, full=runs)


def run_cli(argv, capsys):
    """``(exit code, stdout, stderr)`` of ``main(argv)``; argparse's exits count too."""
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def assert_one_line_error(code, err, expect):
    assert code == expect, (code, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("skfem-dielectric"), err
    assert "Traceback" not in err


@pytest.fixture
def tiny(monkeypatch):
    monkeypatch.setitem(vc.CASES, "nh-d-e", tiny_case())
    return ["validate", "--case", "nh-d-e", "--no-progress"]


def test_out_is_a_file(tmp_path, capsys, tiny):
    f = tmp_path / "file"
    f.write_text("x")
    code, _, err = run_cli(tiny + ["--out", str(f)], capsys)
    assert_one_line_error(code, err, 3)
    assert str(f) in err
    code, _, err = run_cli(tiny + ["--out", str(f / "below")], capsys)
    assert_one_line_error(code, err, 3)
    assert str(f) in err
    assert f.read_text() == "x"


def test_state_is_a_file_and_csv_is_a_folder(tmp_path, capsys, tiny):
    a = tmp_path / "a"
    a.mkdir()
    (a / ".state").write_text("")
    code, _, err = run_cli(tiny + ["--out", str(a)], capsys)
    assert_one_line_error(code, err, 3)
    assert str(a / ".state") in err
    b = tmp_path / "b"
    (b / "nh-d-e.csv").mkdir(parents=True)
    code, _, err = run_cli(tiny + ["--out", str(b)], capsys)
    assert_one_line_error(code, err, 3)
    assert str(b / "nh-d-e.csv") in err and "Is a directory" in err


def test_unwritable_folder(tmp_path, capsys, tiny, monkeypatch):
    out = tmp_path / "ro"
    out.mkdir()
    if os.geteuid() != 0:
        out.chmod(0o500)
    else:                         # root writes anywhere: the OS's answer, simulated
        real = FolderLock.__enter__

        def denied(self):
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(self.path))
        monkeypatch.setattr(FolderLock, "__enter__", denied)
    try:
        code, _, err = run_cli(tiny + ["--out", str(out)], capsys)
    finally:
        out.chmod(0o700)
    assert_one_line_error(code, err, 3)
    assert str(out) in err and "Permission denied" in err
    if os.geteuid() == 0:
        monkeypatch.setattr(FolderLock, "__enter__", real)


def test_full_disk(tmp_path, capsys, tiny, monkeypatch):
    def full(path, header, rows):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    monkeypatch.setattr(case_files, "append_csv_rows", full)
    code, _, err = run_cli(tiny + ["--out", str(tmp_path)], capsys)
    assert_one_line_error(code, err, 3)
    assert str(tmp_path / "nh-d-e.csv") in err and "No space left on device" in err


def test_empty_out_is_an_error(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for cmd in (["validate", "--quick"], ["curves"], ["simulate"]):
        code, _, err = run_cli(cmd + ["--out", ""], capsys)
        assert_one_line_error(code, err, 2)
        assert "--out" in err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command", ["buckling", "post-buckling", "wrinkling-fe"])
def test_a_study_is_locked_like_a_case(tmp_path, capsys, command):
    # the lock is taken before any FE work: the refused command writes no table
    (tmp_path / ".state").mkdir()
    with FolderLock(tmp_path / ".state" / f"{command}.lock", "test"):
        code, _, err = run_cli([command, "--quick", "--out", str(tmp_path)]
                               + (["--solver", "superlu"] if command != "wrinkling-fe" else []),
                               capsys)
    assert_one_line_error(code, err, 2)
    assert f"being written by another process (pid {os.getpid()}:" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == [".state"]


def test_another_writer_is_named(tmp_path, capsys, tiny):
    (tmp_path / ".state").mkdir()
    with FolderLock(tmp_path / ".state" / "nh-d-e.lock", "test"):
        code, _, err = run_cli(tiny + ["--out", str(tmp_path)], capsys)
    assert_one_line_error(code, err, 2)
    assert f"being written by another process (pid {os.getpid()}:" in err
    assert not (tmp_path / "nh-d-e.csv").exists()
    code, _, err = run_cli(tiny + ["--out", str(tmp_path)], capsys)    # lock released
    assert code == 0 and err == ""
    assert (tmp_path / "nh-d-e.csv").read_text().count("\n") == 4       # header + 3 steps


def test_simulate_rejects_options_of_the_other_geometry(tmp_path, capsys):
    code, _, err = run_cli(["simulate", "--geometry", "equibiaxial", "--alpha", "0.5",
                            "--out", str(tmp_path)], capsys)
    assert_one_line_error(code, err, 2)
    assert "--alpha" in err and "--geometry uniaxial only" in err
    code, _, err = run_cli(["simulate", "--s", "2", "--out", str(tmp_path)], capsys)
    assert_one_line_error(code, err, 2)
    assert "--s applies to --geometry equibiaxial only" in err
    assert list(tmp_path.iterdir()) == []


def test_simulate_pvd_and_stop_message(tmp_path, capsys):
    out = tmp_path / "sim"
    code, stdout, _ = run_cli(["simulate", "--geometry", "equibiaxial", "--s", "1.5",
                               "--variant", "membrane", "--mesh", "2", "1", "2", "--D0-max", "2",
                               "--steps", "2", "--out", str(out)], capsys)
    assert code == 0
    pvd = (out / "equibiaxial_nh_membrane_s1.5.pvd").read_text()
    found = re.findall(r'timestep="([^"]+)" group="" part="0" file="([^"]+)"', pvd)
    assert [(float(t), f) for t, f in found] == [
        (0.0, "equibiaxial_nh_membrane_s1.5_000.vtu"), (1.0, "equibiaxial_nh_membrane_s1.5_001.vtu"),
        (2.0, "equibiaxial_nh_membrane_s1.5_002.vtu")]
    assert all((out / f).exists() for _, f in found)
    assert "ramp reached D0 = 2 in 2 charge steps" in stdout


def test_help_shows_defaults_and_every_option_has_help():
    parser = build_parser()
    subs = next(a for a in parser._actions if a.dest == "command").choices
    nested = {f"clamp-zone {n}": p for n, p in next(
        a for a in subs["clamp-zone"]._actions if a.dest == "clamp_command").choices.items()}
    assert set(nested) >= {"clamp-zone units", "clamp-zone tables", "clamp-zone modes"}
    for name, sub in {**subs, **nested}.items():
        for action in sub._actions:
            assert action.help, (name, action.dest)
        text = sub.format_help()
        if name == "simulate":
            assert "(default: 4.0)" in text and "eighth" in text and "millimetres" in text
        if name == "validate":
            assert "(default: 1)" in text and "--scheduler" in text
        if name == "bench":
            assert "(default: auto)" in text
    assert "exit codes" in parser.format_help()


def test_bench_names_the_solver_auto_chose(capsys):
    code, out, _ = run_cli(["bench", "--mesh", "1", "1", "1", "--steps", "1", "--D0-max", "0.5"],
                           capsys)
    assert code == 0
    used = "pardiso" if pardiso_installed() else "superlu"
    assert out.splitlines()[0].startswith(f"linear solver: {used} (chosen by 'auto'")


# --------------------------------------------------------------------------- the fuzz test
#: Values an option may never take, per kind of option.
BAD = {
    "int": ["0", "-3", "1.5", "abc", "", "nan"],
    "float": ["nan", "inf", "-inf", "-1", "0", "abc", "", "1e999"],
    "alpha": ["nan", "inf", "-0.5", "0", "x"],
    "s": ["nan", "inf", "-1", "-1e-9", "s"],
    "mesh": [["0", "1", "1"], ["1", "-2", "1"], ["1", "1"], ["a", "b", "c"], ["1", "1", "1.5"]],
    "choice": ["nope", "", "NEO-HOOKEAN", "vtk", "mumps"],
}
GOOD = {
    "simulate": [["--model", "Gent"], ["--variant", "membrane"], ["--format", "xdmf"],
                 ["--D0-max", "2"], ["--steps", "3"], ["--mesh", "2", "1", "2"]],
    "bench": [["--variant", "membrane"], ["--D0-max", "2"], ["--steps", "2"],
              ["--mesh", "2", "1", "1"], ["--alpha", "0.5"], ["--solver", "superlu"]],
    "validate": [["--quick"], ["--force"], ["--no-progress"], ["--jobs", "2"],
                 ["--case", "nh-d-e"], ["--solver", "superlu"]],
    "curves": [["--case", "nh-d-e"], ["--case", "figde", "gent-d-e"]],
    "list": [[]],
}


def _fatal(rng, cmd, tmp):
    """One mistake that must stop ``cmd`` before any FE work, and its exit codes."""
    f = str(tmp / "a-file")
    kinds = {
        "simulate": [
            lambda: (["--steps", rng.choice(BAD["int"])], {2}),
            lambda: (["--D0-max", rng.choice(BAD["float"])], {2}),
            lambda: (["--geometry", "uniaxial", "--alpha", rng.choice(BAD["alpha"])], {2}),
            lambda: (["--geometry", "equibiaxial", "--s", rng.choice(BAD["s"])], {2}),
            lambda: (["--mesh"] + rng.choice(BAD["mesh"]), {2}),
            lambda: (["--geometry", "equibiaxial", "--alpha", "1"], {2}),
            lambda: (["--geometry", "uniaxial", "--s", "1"], {2}),
            lambda: (["--s", "1"], {2}),
            lambda: ([rng.choice(["--model", "--variant", "--format", "--geometry"]),
                      rng.choice(BAD["choice"])], {2}),
            lambda: (["--bogus"], {2}),
        ],
        "bench": [
            lambda: (["--steps", rng.choice(BAD["int"])], {2}),
            lambda: (["--D0-max", rng.choice(BAD["float"])], {2}),
            lambda: (["--alpha", rng.choice(BAD["alpha"])], {2}),
            lambda: (["--mesh"] + rng.choice(BAD["mesh"]), {2}),
            lambda: (["--solver", rng.choice(BAD["choice"])], {2}),
            lambda: (["--out", "x"], {2}),
        ] + ([lambda: (["--solver", "pardiso"], {2})] if not pardiso_installed() else []),
        "validate": [
            lambda: (["--jobs", rng.choice(["0", "-1", "x", "1.5", ""])], {2}),
            lambda: (["--case", rng.choice(["nope", "", "NH-D-E"])], {2}),
            lambda: (["--solver", rng.choice(["mumps", "", "PARDISO"])], {2}),
            lambda: (["--out", ""], {2}),
            lambda: (["--out", f], {3}),
            lambda: (["--out", f + "/below"], {3}),
            lambda: (["--scheduler", ""], {2}),
            lambda: (["--quick=yes"], {2}),
            lambda: (["--case"], {2}),
        ] + ([lambda: (["--solver", "pardiso"], {2})] if not pardiso_installed() else []),
        "curves": [
            lambda: (["--out", ""], {2}),
            lambda: (["--out", f], {3}),
            lambda: (["--out", f + "/below"], {3}),
            lambda: (["--case", rng.choice(["nope", "", "zs"])], {2}),
            lambda: (["--jobs", "2"], {2}),
        ],
        "list": [lambda: ([rng.choice(["--out", "--quick", "extra", "-x"])], {2})],
    }
    return rng.choice(kinds[cmd])()


def generate(rng, tmp):
    """One bad invocation and the exit codes it may end with."""
    roll = rng.random()
    if roll < 0.04:
        return [rng.choice(["", "run", "valdate", "--quick", "-h5"])], {2}
    if roll < 0.07:
        return [rng.choice(["--help", "--version"])] if rng.random() < 0.5 else \
            [rng.choice(list(GOOD)), "--help"], {0}
    cmd = rng.choice(list(GOOD))
    fatal, codes = _fatal(rng, cmd, tmp)
    good = [g for g in GOOD[cmd] if not g or g[0] not in fatal]     # no fix of the mistake
    noise = [tok for part in rng.sample(good, k=rng.randint(0, min(3, len(good))))
             for tok in part]
    needs_out = cmd in ("simulate", "validate", "curves") and "--out" not in fatal
    parts = [fatal, noise] + ([["--out", str(tmp / f"out{rng.randint(0, 9)}")]]
                              if needs_out and rng.random() < 0.9 else [])
    rng.shuffle(parts)
    if needs_out and not any("--out" in p for p in parts):
        codes = codes | {2}                           # --out missing: argparse's error
    return [cmd] + [tok for p in parts for tok in p], codes


def test_fuzz_bad_invocations(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(vc.CASES, "nh-d-e", tiny_case())
    (tmp_path / "a-file").write_text("keep")
    rng = random.Random(20201101)
    seen = {}
    for _ in range(220):
        argv, codes = generate(rng, tmp_path)
        code, out, err = run_cli(argv, capsys)
        assert code in codes and code in EXIT_CODES, (argv, code, err)
        assert "Traceback" not in err, (argv, err)
        if code == 0:
            assert out and err == "", argv                 # help or version on stdout
        else:
            lines = err.strip().splitlines()
            assert len(lines) == 1 and lines[0].startswith("skfem-dielectric"), (argv, err)
        seen[code] = seen.get(code, 0) + 1
    assert {0, 2, 3} <= set(seen) and sum(seen.values()) == 220, seen
    assert (tmp_path / "a-file").read_text() == "keep"
    # nothing was computed: no case CSV anywhere (every invocation failed before FE work)
    assert not list(tmp_path.rglob("*.csv"))


def test_simulate_says_why_its_ramp_stopped(tmp_path, capsys, monkeypatch):
    # a ramp the solver could not finish: simulate's steps CSV ends with the reason
    import validation.cli as cli

    def stopped(**kw):
        out = kw["out"]
        out.mkdir(parents=True)
        files = [out / f"run_{i:03d}.vtu" for i in range(2)]
        for f in files:
            f.write_text("")
        table = out / "run_steps.csv"
        table.write_text("step,D0,lam1,lam3,min_P33,min_P33_clamp,iterations\n"
                         "0,0.0,1.2,0.7,0.1,0.1,3\n1,0.5,1.3,0.6,0.1,0.1,4\n"
                         "2,,,,,,stopped: Newton diverged after 6 cut-backs\n")
        return files + [table]

    monkeypatch.setattr(cli, "simulate", stopped)
    code, out, _ = run_cli(["simulate", "--D0-max", "2", "--steps", "4", "--out",
                            str(tmp_path / "sim")], capsys)
    assert code == 0
    assert out.splitlines()[-1] == ("ramp stopped after step 1 (D0 = 0.5): the next target "
                                    "D0 = 1 was not reached: Newton diverged after 6 cut-backs")
    assert 'timestep="0.5" group="" part="0" file="run_001.vtu"' in \
        (tmp_path / "sim" / "run.pvd").read_text()


def test_bad_scheduler_address(tmp_path, capsys):
    pytest.importorskip("distributed", reason="dask.distributed is not installed")
    code, _, err = run_cli(["validate", "--quick", "--case", "nh-d-e", "--out", str(tmp_path),
                            "--scheduler", "http://nowhere:1"], capsys)
    assert_one_line_error(code, err, 2)
    assert "--scheduler must be a dask scheduler address" in err


@pytest.mark.parametrize("cmd", ["buckling", "post-buckling"])
@pytest.mark.parametrize("bad, expect", [
    (["--D0-step", "-0.5"], 2),
    (["--D0-step", "x"], 2),
    (["--D0-max", "0"], 2),
    (["--alpha", "0"], 2),
    (["--meshes", "10x1"], 2),
    (["--solver", "mumps"], 2),
    (["--out", "a-file"], 3),
] + ([(["--solver", "pardiso"], 2)] if not pardiso_installed() else []))
def test_study_commands_bad_input(cmd, bad, expect, tmp_path, capsys, monkeypatch):
    # each mistake stops the study before any FE work: one line, its exit code, no file
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a-file").write_text("keep")
    argv = [cmd, "--quick"] + bad + ([] if "--out" in bad else ["--out", "res"])
    code, out, err = run_cli(argv, capsys)
    assert_one_line_error(code, err, expect)
    assert not (tmp_path / "res").exists() and (tmp_path / "a-file").read_text() == "keep"


def test_post_buckling_odd_thickness_count(tmp_path, capsys):
    code, _, err = run_cli(["post-buckling", "--meshes", "10x1x5", "--out",
                            str(tmp_path / "res")], capsys)
    assert_one_line_error(code, err, 2)
    assert "N2 must be even" in err and "10x1x5" in err
