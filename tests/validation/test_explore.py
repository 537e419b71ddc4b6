"""``skfem-dielectric explore``: the page draws analytic's numbers, follows a slider in a real
headless browser, refuses foreign hosts, and says how to install Bokeh when it is missing."""

from __future__ import annotations

import http.client
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import analytic as an
from validation.explore import ExploreParameters, dispersion_panel, equibiaxial_panel, free_port

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def test_panels_carry_analytic_numbers():
    d = equibiaxial_panel(ExploreParameters(s=1.0))
    lam, E0 = an.max_E0(1.0)
    # the same function: equal to the last bit
    assert (d["max_lam"], d["max_E0"]) == (lam, E0)
    # neo-Hookean, s = 1: the root of 2 lam^6 - 3 lam^5 - 8 = 0 (paper Sec. 3.1); rtsafe
    # converges to a few ulp
    assert abs(2 * lam**6 - 3 * lam**5 - 8) < 1e-12
    # under voltage control the state past the maximum of E0 is unstable, before it stable
    v = equibiaxial_panel(ExploreParameters(s=1.0, control="voltage"))
    past = v["lam"] > lam * 1.01
    assert np.isnan(v["D0_stable"][past]).all() and np.isfinite(v["D0_unstable"][past]).all()
    disp = dispersion_panel(ExploreParameters(lam=2.0))
    # flexural D0_c(kh) runs from the thin-plate limit sqrt(lam^6 - 1) (Eq. antisym_thin,
    # within 1 % at kh = 0.02) toward the thick-plate limit (within 1 % at kh = 50)
    assert abs(disp["antisymmetric"][0] / np.sqrt(2.0**6 - 1) - 1) < 1e-2
    assert abs(disp["antisymmetric"][-1] / disp["thick"] - 1) < 1e-2


def test_bad_input_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="Jm"):
        equibiaxial_panel(ExploreParameters(model="Gent", Jm=0.0))
    with pytest.raises(ValueError, match="lam must be below the locking"):
        dispersion_panel(ExploreParameters(model="Gent", lam=8.0))


def _env():
    return {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}


def test_without_bokeh_one_line_and_exit_2():
    code = ("import sys; sys.modules['bokeh'] = None\n"
            "from validation.cli import main\n"
            "sys.exit(main(['explore', '--no-browser']))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       cwd=ROOT, env=_env())
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "pip install -e '.[explore]'" in r.stderr


@pytest.fixture
def server():
    pytest.importorskip("bokeh", reason="the 'explore' extra (bokeh) is not installed")
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-m", "validation.cli", "explore", "--no-browser",
                             "--port", str(port)], cwd=ROOT, env=_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    line = proc.stdout.readline()
    assert f"http://127.0.0.1:{port}/" in line, line
    yield port
    proc.terminate()
    proc.wait(timeout=20)


def _get(port, host):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    c.request("GET", "/", headers={"Host": host})
    r = c.getresponse()
    return r.status, r.read().decode()


def test_a_foreign_host_is_refused_and_the_page_needs_no_cdn(server):
    status, _ = _get(server, f"attacker.example:{server}")
    assert status == 403
    status, html = _get(server, f"127.0.0.1:{server}")
    assert status == 200
    assert "/static/js/bokeh.min.js" in html and "cdn.bokeh.org" not in html


def test_moving_s_in_a_browser_redraws_the_E0_maximum(server):
    if CHROMIUM is None:
        pytest.skip("no chromium (apt-get install chromium)")
    sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed")
    with sync_api.sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=[
            "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
            "--disable-component-update", "--disable-sync", "--no-first-run"])
        page = browser.new_page(viewport={"width": 1180, "height": 1250})
        page.goto(f"http://127.0.0.1:{server}/")
        page.wait_for_selector("#E0max", timeout=60000)
        first = float(page.inner_text("#E0max"))
        # the paper's s = 1: the page prints max_E0 to 6 decimals
        assert abs(first - an.max_E0(1.0)[1]) <= 5e-7
        handle = page.locator(".noUi-handle").first
        handle.focus()
        for _ in range(10):                    # ten steps of 0.05: s = 1.5
            page.keyboard.press("ArrowRight")
        page.wait_for_function(
            "() => Bokeh.documents[0].get_model_by_name('readout_equibiaxial')"
            ".text.startsWith('s = 1.5:')", timeout=30000)
        text = page.evaluate("() => Bokeh.documents[0].get_model_by_name('readout_equibiaxial')"
                             ".text")
        s = float(re.search(r"s = ([-0-9.]+):", text).group(1))
        drawn = page.evaluate("() => Bokeh.documents[0].get_model_by_name('eq_max_E0')"
                              ".data.y[0]")
        # the drawn triangle is analytic.max_E0 at the new s, sent as a double
        assert s == pytest.approx(1.5, abs=1e-12)
        assert drawn == an.max_E0(s)[1] and drawn != first
        shot = ROOT / "docs" / "explore.png"
        if not shot.exists():
            page.screenshot(path=str(shot))
        browser.close()
