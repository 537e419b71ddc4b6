"""``skfem-dielectric explore --results DIR`` on a folder of the main job: the export and
the live page both draw it, and its readout quotes the folder's own buckling load and P33
breakdown.  The folder is written by ``validate --quick`` itself (equi-biaxial, Keplinger
with the run analysed for buckling in its three variants, FE wrinkling), with the Keplinger
case cut to its ``alpha = 1`` runs to keep the suite short; bokeh is in the test extra, so
nothing here skips under the README's test command."""

from __future__ import annotations

import csv
import http.client
import os
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import bokeh  # noqa: F401  (the test extra has it: these tests never skip)
import numpy as np
import pytest

from validation import cases as vc
from validation.cli import main
from validation.explore import free_port

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    out = tmp_path_factory.mktemp("explore") / "results"
    small = vc._keplinger((1.0,), 6.0, 12, vc.QUICK_PLATE, buckling=vc.BUCKLING_ALPHAS)
    with pytest.MonkeyPatch.context() as mp:
        mp.setitem(vc.CASES, "uni-axial-ideal", replace(vc.CASES["uni-axial-ideal"],
                                                        quick=small))
        assert main(["validate", "--quick", "--case", "nh-d-e", "uni-axial-ideal",
                     "wrinkling-fe", "--out", str(out), "--no-progress"]) == 0
    return out


def _column(path: Path, name: str) -> list[str]:
    with open(path, newline="") as fh:
        return [r[name] for r in csv.DictReader(fh)]


def test_export_quotes_the_folders_buckling_load_and_breakdown(results, tmp_path, capsys):
    html = tmp_path / "page.html"
    assert main(["explore", "--results", str(results), "--export", str(html)]) == 0
    text = html.read_text()
    table = results / "uni-axial-ideal.csv"
    D0_b = [float(v) for v in _column(table, "D0_b") if v]
    assert D0_b, "the buckling run wrote no D0_b"
    # the readout of the uni-axial panel (alpha = 1, the page's default) quotes the run's
    # own D0_b to four decimals and the charges of its P33 breakdown markers
    assert f"buckling load of this run D0_b = {D0_b[0]:.4f}" in text
    brk = [float(d) for d, b in zip(_column(table, "D0"), _column(table, "breakdown"))
           if b == "True"]
    assert brk and f"P33 breakdown at D0 = {brk[0]:g}" in text
    # and the equi-biaxial FE dots of nh-d-e at the page's s = 1
    s = np.array([float(v) for v in _column(results / "nh-d-e.csv", "s")])
    assert np.isclose(s, 1.0).any() and "FE dots:" in text


def _env():
    return {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}


def test_the_live_page_with_results_answers_200(results):
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-m", "validation.cli", "explore", "--no-browser",
                             "--port", str(port), "--results", str(results)], cwd=ROOT,
                            env=_env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True)
    try:
        line = proc.stdout.readline()
        assert f"http://127.0.0.1:{port}/" in line, line
        c = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
        c.request("GET", "/", headers={"Host": f"127.0.0.1:{port}"})
        r = c.getresponse()
        body = r.read().decode()
        # the page's document is built for this session: a failure there is an HTTP 500
        assert r.status == 200 and "/static/js/bokeh.min.js" in body
    finally:
        proc.terminate()
        proc.wait(timeout=20)


def test_an_empty_export_name_is_refused(results, capsys):
    assert main(["explore", "--results", str(results), "--export", ""]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--export must name an HTML file" in err


def test_a_table_without_the_variant_column_is_one_line(results, tmp_path, capsys):
    bad = tmp_path / "bad"
    bad.mkdir()
    with open(results / "uni-axial-ideal.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    cols = [c for c in rows[0] if c != "variant"]
    with open(bad / "uni-axial-ideal.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, cols, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    assert main(["explore", "--results", str(bad), "--export", str(tmp_path / "x.html")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "lacks the column variant" in err, err
