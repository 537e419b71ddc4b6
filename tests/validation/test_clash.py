"""The clash guard: a foreign ``analytic`` first on ``sys.path`` stops ``import validation``."""

import os
import subprocess
import sys
import textwrap


def _run(code: str, cwd, env_path: str | None = None):
    """``python -c code`` in ``cwd`` (not the repository: ``-c`` puts the cwd first)."""
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    if env_path is not None:
        env["PYTHONPATH"] = env_path
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, cwd=cwd, timeout=120)


def _fake_distribution(root, name="analytic", version="1.0"):
    """A package ``name`` with a dist-info that claims it, like ``pip install analytic``."""
    pkg = root / name
    pkg.mkdir()
    (pkg / "__init__.py").write_text('"""Someone else\'s package."""\n')
    info = root / f"{name}-{version}.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n")
    (info / "top_level.txt").write_text(f"{name}\n")
    (info / "RECORD").write_text(textwrap.dedent(f"""\
        {name}/__init__.py,,
        {name}-{version}.dist-info/METADATA,,
        {name}-{version}.dist-info/RECORD,,
        """))


def test_shadowing_analytic_stops_import_with_the_fix(tmp_path):
    _fake_distribution(tmp_path)
    r = _run("import validation", tmp_path, env_path=str(tmp_path))
    assert r.returncode != 0
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("validation.clash.PackageClash"), r.stderr
    assert "'analytic 1.0'" in last and "virtual environment" in last, last
    assert str(tmp_path / "analytic") in last


def test_our_packages_pass(tmp_path):
    r = _run("import validation; from validation.clash import find_clashes; "
             "print(find_clashes())", tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[]"
