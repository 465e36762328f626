"""The workbench (`propbet serve`) driven in a real browser: Debian's chromium through
Playwright (from PyPI, `executable_path`; Playwright's own browser download is not used).

Each test starts the server on the shipped default case, drives the page as a user does, and
checks what it shows against the command line: `propbet run` on the folder the page saved, the
case's compare command with the same `--effect`, and the diagnosis' ladder."""

import json
import os
import shlex
import shutil
import subprocess
from pathlib import Path

import pytest
from playwright.sync_api import sync_playwright

REPO = Path(__file__).resolve().parents[2]
BINARY = Path(os.environ.get("PROPBET_BIN", REPO / "target" / "release" / "propbet"))
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """`propbet serve` on the default case, saving into a temporary folder: (URL, save folder)."""
    saves = tmp_path_factory.mktemp("saves")
    proc = subprocess.Popen(
        [str(BINARY), "serve", "props/apcsp_10x7", "--save-to", str(saves)],
        cwd=REPO,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    url = proc.stdout.readline().strip()
    assert url.startswith("http://127.0.0.1:"), f"no URL printed: {url!r} {proc.stderr.read() if proc.poll() is not None else ''}"
    yield url, saves
    proc.terminate()
    proc.wait(timeout=10)


@pytest.fixture(scope="module")
def browser():
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        yield b
        b.close()


def open_page(browser, url, errors):
    page = browser.new_page(viewport={"width": 1400, "height": 900})
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url)
    page.wait_for_selector("#numbers b")
    return page


def shown(page, name):
    """A number the page shows, as a fraction (\"5.5 %\" -> 0.055)."""
    text = page.locator(f'#numbers b[data-name^="{name}"]').inner_text()
    return float(text.replace("%", "").replace("+", "").strip()) / 100


def move(page, effect, param, value):
    """Moves a slider as a user drags it: its value set, its input event fired."""
    page.eval_on_selector(
        f'.effect[data-id="{effect}"] input[data-param="{param}"]',
        "(el, v) => { el.value = v; el.dispatchEvent(new Event('input', { bubbles: true })); }",
        value,
    )


def settled(page, text):
    page.wait_for_function("t => document.getElementById('message').textContent.includes(t)", arg=text)


def propbet(*argv):
    done = subprocess.run([str(BINARY), *map(str, argv)], cwd=REPO, capture_output=True, text=True)
    assert done.returncode in (0, 1), f"propbet {' '.join(map(str, argv))}: exit {done.returncode}\n{done.stderr}"
    return done


def test_the_page_loads_with_no_console_error_and_draws_four_figures(server, browser):
    errors = []
    page = open_page(browser, server[0], errors)
    settled(page, "baseline")
    assert page.locator("canvas").count() >= 4
    assert page.locator(".effect").count() >= 15
    # The first screen holds the numbers, the four figures and the effects.
    for sel in ["#numbers", "#fig-a", "#fig-d", "#effects"]:
        box = page.locator(sel).bounding_box()
        assert box and box["y"] < 900, sel
    # Each figure downloads as SVG, drawn from the figure's own data.
    with page.expect_download() as d:
        page.click("#cap-a a:text('SVG')")
    svg = Path(d.value.path()).read_text()
    assert svg.startswith("<svg") and svg.count("<polyline") >= 4 and svg.count("<circle") > 50, svg[:300]
    with page.expect_download() as d:
        page.click("#cap-d a:text('PNG')")
    assert Path(d.value.path()).read_bytes()[:4] == b"\x89PNG"
    assert errors == []


def test_a_slider_gives_what_compare_and_run_give_for_the_same_state(server, browser, tmp_path):
    url, saves = server
    errors = []
    page = open_page(browser, url, errors)
    settled(page, "baseline")
    move(page, "pitch-offset", "deg", -1.2)
    settled(page, "pitch-offset:deg=-1.2")
    state = page.evaluate("() => currentState()")
    assert state == {"effects": ["pitch-offset:deg=-1.2"]}
    api = page.evaluate("() => last.accuracy")
    assert abs(shown(page, "CT median") - api["ct_median_error"]) < 0.0006
    # Saved, the state is a case folder `propbet run` gives the same numbers for.
    page.fill("#save-name", "slider_case")
    page.click("#save")
    settled(page, "saved")
    saved = saves / "slider_case"
    assert "pitch-offset:deg=-1.2" in (saved / "case.toml").read_text()
    propbet("run", saved, "-o", tmp_path / "run")
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    for k in ["ct_median_error", "cp_median_error", "points"]:
        assert summary["accuracy"][k] == pytest.approx(api[k], rel=1e-9), k
    # The run's compare command (the saved case's effects as its --effect) run on its own.
    compare = next(s["command"] for s in summary["stages"] if s["command"].startswith("propbet compare"))
    assert "--effect pitch-offset:deg=-1.2" in compare
    argv = shlex.split(compare)[1:]
    argv[argv.index("--out") + 1] = str(tmp_path / "cmp")
    propbet(*argv)
    cmp = json.loads((tmp_path / "cmp" / "summary.json").read_text())
    assert cmp["accuracy"]["ct_median_error"] == pytest.approx(api["ct_median_error"], rel=1e-9)
    assert cmp["accuracy"]["cp_median_error"] == pytest.approx(api["cp_median_error"], rel=1e-9)
    assert errors == []


def test_fit_gives_the_diagnosis_value(server, browser, tmp_path):
    errors = []
    page = open_page(browser, server[0], errors)
    settled(page, "baseline")
    page.click('.effect[data-id="pitch-offset"] button.fit')
    settled(page, "fitted:")
    fitted = page.evaluate("() => currentState()")["effects"]
    assert len(fitted) == 1 and fitted[0].startswith("pitch-offset:deg=")
    deg = float(fitted[0].split("=")[1])
    # The diagnosis' first rung fits the same effect alone on the same points.
    propbet("run", "props/apcsp_10x7", "-o", tmp_path / "run")
    d = json.loads((tmp_path / "run" / "diagnose" / "diagnosis.json").read_text())["diagnosis"]
    first = d["ladder"][1]
    assert first["added"] == "pitch-offset", first
    assert deg == pytest.approx(first["params"][0]["value"], abs=2e-3)
    assert errors == []


def test_a_refused_request_leaves_the_page_working(server, browser):
    errors = []
    page = open_page(browser, server[0], errors)
    settled(page, "baseline")
    status = page.evaluate(
        """async () => {
            const r = await fetch('/api/evaluate', { method: 'POST', headers: { 'X-Propbet-Token': token },
                                                     body: '{"effects": ["nope:x=1"]}' });
            return [r.status, (await r.json()).error];
        }"""
    )
    assert status[0] == 400 and "unknown effect `nope`" in status[1]
    move(page, "drag-scale", "factor", 1.3)
    settled(page, "drag-scale:factor=1.3")
    assert page.evaluate("() => last.state.effects") == ["drag-scale:factor=1.3"]
    # The only console error is the refused request's own.
    assert all("400" in e for e in errors), errors


def test_two_tabs_at_once_each_get_their_own_state(server, browser):
    errors = []
    a = open_page(browser, server[0], errors)
    b = open_page(browser, server[0], errors)
    settled(a, "baseline")
    settled(b, "baseline")
    move(a, "pitch-offset", "deg", 0.6)
    move(b, "chord-scale", "factor", 1.05)
    settled(a, "pitch-offset:deg=0.6")
    settled(b, "chord-scale:factor=1.05")
    assert a.evaluate("() => last.state.effects") == ["pitch-offset:deg=0.6"]
    assert b.evaluate("() => last.state.effects") == ["chord-scale:factor=1.05"]
    assert shown(a, "CT median") != shown(b, "CT median")
    assert errors == []


def test_a_workbench_of_compares_flags_loads_and_says_it_cannot_save(browser, tmp_path):
    """Started from `compare`'s flags (the PhotoFoil prop and log, no XFOIL): the page loads
    with no console error, shows compare's numbers for the same flags, and Save is off."""
    case = REPO / "props" / "photofoil_8x4.5"
    flags = ["--prop", case / "QProp_8x4_5.txt", "--measured", case / "StepsTestV2_2022-01-18_153833.csv",
             "--rho", "1.1648"]
    proc = subprocess.Popen([str(BINARY), "serve", *map(str, flags), "--save-to", str(tmp_path)], cwd=REPO,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        url = proc.stdout.readline().strip()
        assert url.startswith("http://127.0.0.1:"), url
        errors = []
        page = open_page(browser, url, errors)
        propbet("compare", *flags, "-o", tmp_path / "cmp")
        cli = json.loads((tmp_path / "cmp" / "summary.json").read_text())
        assert abs(shown(page, "CT") - cli["accuracy"]["ct_median_error"]) < 0.0006
        assert page.locator("#save").is_disabled()
        # Export writes the simulator files of the state, even where Save cannot write a case.
        page.fill("#save-name", "flags")
        page.click("#export")
        settled(page, "exported to")
        assert (tmp_path / "flags_export" / "map.csv").exists()
        assert errors == []
        page.close()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
