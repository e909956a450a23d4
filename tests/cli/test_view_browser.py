"""The 3D view in a real browser (Debian's Chromium, headless, WebGL on SwiftShader): the page
opens offline with no console error, its 3D canvas is drawn, and moving the slider to another
state changes the picture without reloading the page."""

import io

import numpy as np
import pytest
from helpers import EXAMPLES
from PIL import Image
from support.browser import Browser, chromium

from liftplan.model.lift import load_curve
from liftplan.model.scene.file import load_scene
from liftplan.planner.output.view.page import page
from liftplan.planner.output.view.states import lift_view

pytestmark = pytest.mark.skipif(
    chromium() is None, reason="Debian chromium not installed (.ci/run installs it)"
)

#: A drawn 3D scene has many colours (shaded body, rope colours, grid); an empty canvas one.
MIN_COLOURS = 50


def pixels(png):
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def colours(png):
    return len(np.unique(pixels(png).reshape(-1, 3), axis=0))


@pytest.fixture(scope="module")
def lift_page(tmp_path_factory):
    scene = load_scene(EXAMPLES / "sunken_block_lift.toml")
    view = lift_view(scene, load_curve(scene, step=2.0))
    path = tmp_path_factory.mktemp("view") / "lift.html"
    path.write_text(page(view), encoding="utf-8")
    return path, view


def _canvas_box(browser):
    """(x, y, width, height) of the 3D plot's area (the WebGL canvas), CSS pixels."""
    box = browser.evaluate(
        "(() => { const r = document.querySelector('#liftplan-view canvas').getBoundingClientRect();"
        " return [r.x, r.y, r.width, r.height]; })()"
    )
    assert box[2] > 100 and box[3] > 100, box
    return box


def _wait_drawn(browser, box):
    """Let plotly draw (it draws in animation frames); the canvas's screenshot."""
    for _ in range(50):
        browser.settle(5)
        shot = browser.screenshot(box)
        if colours(shot) >= MIN_COLOURS:
            return shot
    return shot


def test_lift_page_draws_and_its_slider_switches_states(lift_page, tmp_path):
    path, view = lift_page
    with Browser(tmp_path / "profile", height=1400) as browser:  # the slider within the window
        browser.open(path.as_uri())
        browser.evaluate(
            "new Promise(done => { const p = () => window.Plotly ? done(true) : setTimeout(p, 50); p(); })"
        )
        box = _canvas_box(browser)
        first = _wait_drawn(browser, box)
        assert colours(first) >= MIN_COLOURS, "the 3D canvas is blank"
        # the slider's rail: a click near its right end picks the last state
        rail = browser.evaluate(
            "(() => { const r = document.querySelector('#liftplan-view .slider-rail-rect')"
            ".getBoundingClientRect(); return [r.x, r.y, r.width, r.height]; })()"
        )
        marker = browser.evaluate("performance.getEntriesByType('navigation').length")
        assert rail[1] + rail[3] < 1400, rail
        browser.click(rail[0] + rail[2] - 2, rail[1] + rail[3] / 2)
        browser.settle(10)
        active = browser.evaluate("document.getElementById('liftplan-view').layout.sliders[0].active")
        assert active == len(view.states) - 1
        second = _wait_drawn(browser, box)
        assert np.any(pixels(first) != pixels(second)), "the slider did not change the picture"
        assert browser.evaluate("performance.getEntriesByType('navigation').length") == marker  # no reload
        title = browser.evaluate("document.getElementById('liftplan-view').layout.title.text")
        assert view.states[-1].name in title
        errors = browser.errors()
        fetched = [u for u in browser.requested() if u.startswith(("http://", "https://"))]
    (tmp_path / "first.png").write_bytes(first)
    (tmp_path / "second.png").write_bytes(second)
    assert errors == []
    assert fetched == []
