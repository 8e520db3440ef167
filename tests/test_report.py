"""``report.html``: the self-contained page ``moorline run`` writes (:mod:`moorline.report`).

The page of the OC3 single-line run is parsed with :mod:`html.parser` (balanced tags, every
section, every plot embedded as a PNG data URI, nothing external, no script, the numbers of
``summary.json``), a case named like markup is escaped, a failed and an interrupted run say
so at the top, and headless Chromium (Debian's ``chromium``, skipped when absent) loads the
page, shows every section in its DOM and takes a screenshot.
"""

from __future__ import annotations

import base64
import json
import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from moorline.cli import cli
from moorline.io import load_case
from moorline.report import REPORT_FILE, SECTIONS, write_report

ROOT = Path(__file__).resolve().parents[1]
OC3 = ROOT / "cases" / "oc3_line.yaml"
PNG = b"\x89PNG\r\n\x1a\n"
VOID = {"meta", "img", "br", "hr", "link", "input", "col", "wbr", "source", "area", "base"}
MARKUP = '<script>alert("x")</script> & <b>bold</b>'

needs_oc3 = pytest.mark.skipif(not OC3.is_file(), reason="cases/oc3_line.yaml not present")


class _Page(HTMLParser):
    """Tags, headings, images, links and text of a page; unbalanced tags are recorded."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.stack: list[str] = []
        self.errors: list[str] = []
        self.tags: list[str] = []
        self.h2: list[str] = []
        self.section_ids: list[str] = []
        self.images: list[str] = []
        self.captions: list[str] = []
        self.urls: list[str] = []
        self.text: list[str] = []
        self._h2 = self._caption = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        self.tags.append(tag)
        if tag not in VOID:
            self.stack.append(tag)
        if tag == "section":
            self.section_ids.append(values.get("id") or "")
        if tag == "img":
            self.images.append(values.get("src") or "")
        for key in ("href", "src", "action", "srcset", "poster"):
            if key in values and tag != "img":
                self.urls.append(values[key] or "")
        self._h2 = self._h2 or tag == "h2"
        self._caption = self._caption or tag == "figcaption"

    def handle_endtag(self, tag: str) -> None:
        if tag in VOID:
            return
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes <{self.stack[-1] if self.stack else ''}>")
            return
        self.stack.pop()
        self._h2 = self._h2 and tag != "h2"
        self._caption = self._caption and tag != "figcaption"

    def handle_data(self, data: str) -> None:
        self.text.append(data)
        if self._h2:
            self.h2.append(data)
        if self._caption:
            self.captions.append(data)


def _parse(path: Path) -> _Page:
    page = _Page()
    page.feed(path.read_text(encoding="utf-8"))
    page.close()
    return page


def _invoke(*args: object) -> Result:
    return CliRunner().invoke(cli, [str(a) for a in args])


def _case(tmp_path: Path, name: str, analyses: str | None = None) -> Path:
    """cases/oc3_line.yaml renamed (and with other analyses)."""
    text = OC3.read_text(encoding="utf-8").replace("name: oc3-line", f"name: {name}")
    if analyses is not None:
        text = re.sub(r"analyses:\n(  - .*\n)+", f"analyses:\n{analyses}", text)
    path = tmp_path / "case.yaml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def oc3_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Result, Path]:
    """``moorline run cases/oc3_line.yaml`` (plots drawn) once for the module."""
    if not OC3.is_file():
        pytest.skip("cases/oc3_line.yaml not present")
    out = tmp_path_factory.mktemp("out")
    return _invoke("run", OC3, "--out", out), out / "oc3-line"


@needs_oc3
def test_report_parses_and_embeds_every_plot(oc3_run: tuple[Result, Path]) -> None:
    result, directory = oc3_run
    assert result.exit_code == 0, result.stderr
    report = directory / REPORT_FILE
    assert str(report) in result.stderr  # listed among the files written
    page = _parse(report)
    assert not page.errors and not page.stack, (page.errors, page.stack)
    assert page.tags[0] == "html" and "head" in page.tags and "body" in page.tags
    # every section, with its heading, in order
    assert [h.strip() for h in page.h2] == list(SECTIONS.values())
    assert page.section_ids == list(SECTIONS)
    # every PNG the run wrote, embedded as a data URI that decodes to a PNG
    pngs = sorted(p.name for p in directory.glob("*.png"))
    assert pngs == ["configuration_3d.png", "configuration_plan.png", "configuration_xz.png"]
    assert sorted(page.captions) == pngs
    assert len(page.images) == len(pngs)
    for src in page.images:
        prefix = "data:image/png;base64,"
        assert src.startswith(prefix), src[:40]
        data = base64.b64decode(src[len(prefix):], validate=True)
        assert data.startswith(PNG) and data in {(directory / n).read_bytes() for n in pngs}
    # self-contained: no script, no stylesheet link, only in-page links
    assert "script" not in page.tags and "link" not in page.tags
    assert page.urls and all(u.startswith("#") for u in page.urls), page.urls


@needs_oc3
def test_report_shows_the_summary_numbers(oc3_run: tuple[Result, Path]) -> None:
    """The statics table, the stiffness and the design block are those of summary.json."""
    _, directory = oc3_run
    summary = json.loads((directory / "summary.json").read_text())["analyses"][0]
    text = " ".join(_parse(directory / REPORT_FILE).text)
    line = summary["lines"]["line1"]
    assert summary["converged"] and "converged" in text
    # forces in kN (the fairlead tension is about 910 kN)
    for value in (line["max_tension"], line["end_a"]["tension"], line["end_b"]["force"][2]):
        assert f"{value / 1e3:.6g}" in text, value
    assert f"{line['seabed_length']:.6g}" in text
    for row in summary["points"]["fairlead"]["stiffness"]:
        for value in row:
            assert f"{value:.6g}" in text, value
    assert "3x3 stiffness [N/m]" in text
    assert summary["design"]["standard"] in text and "no MBL" in text and "not checked" in text
    for key in ("chain", "anchor", "fairlead", "902.2", "384.243", "newton", "depth 320 m"):
        assert key in text, key


@needs_oc3
def test_names_and_text_are_escaped(oc3_run: tuple[Result, Path], tmp_path: Path) -> None:
    """A case, a line and a message named like markup appear as text, never as tags."""
    _, directory = oc3_run
    summary = json.loads((directory / "summary.json").read_text())
    analysis = summary["analyses"][0]
    analysis["lines"] = {MARKUP: analysis["lines"]["line1"]}
    analysis["message"] = MARKUP
    summary["case"] = MARKUP
    system = load_case(_case(tmp_path, json.dumps(MARKUP)))
    assert system.name == MARKUP
    path = write_report(summary, list(directory.glob("*.png")), tmp_path / "page", system)
    raw = path.read_text(encoding="utf-8")
    assert "<script" not in raw and "<b>" not in raw
    page = _parse(path)
    assert not page.errors and "script" not in page.tags and "b" not in page.tags
    text = "".join(page.text)
    assert text.count(MARKUP) >= 3  # the title and heading, the line, the message


@needs_oc3
def test_a_failed_run_writes_a_report_that_says_so(tmp_path: Path) -> None:
    case = _case(tmp_path, "oc3-failed",
                 "  - {kind: statics, method: relaxation, max_iterations: 1, "
                 "tolerance: 1.0e-12}\n")
    result = _invoke("run", case, "--out", tmp_path, "--no-plots")
    assert result.exit_code == 1, result.stderr
    page = _parse(tmp_path / "oc3-failed" / REPORT_FILE)
    assert not page.errors
    text = " ".join(page.text)
    assert "statics failed" in text and "1 iteration" in text
    assert [h.strip() for h in page.h2] == list(SECTIONS.values())
    assert not page.images and "No other plots" in text


@needs_oc3
def test_an_interrupted_run_writes_a_report_that_says_so(tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    """Ctrl-C in the dynamics (raised by a stand-in runner): the report shows the statics
    done before and the status ``interrupted``."""
    def interrupted(*_args: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr("moorline.runners.run_dynamics", interrupted)
    case = _case(tmp_path, "oc3-interrupted", "  - {kind: statics, method: newton}\n"
                 "  - {kind: dynamics, duration: 1, dt: 0.05}\n")
    result = _invoke("run", case, "--out", tmp_path, "--no-plots")
    assert result.exit_code == 130, result.stderr
    page = _parse(tmp_path / "oc3-interrupted" / REPORT_FILE)
    text = " ".join(page.text)
    assert "interrupted in dynamics" in text and "results so far in" in text
    assert "converged in" in text  # the statics that ran before


def _chromium() -> str | None:
    return next((p for p in map(shutil.which, ("chromium", "chromium-browser",
                                               "google-chrome")) if p), None)


def _run_chromium(binary: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([binary, "--headless", "--disable-gpu", "--no-sandbox", *args],
                          capture_output=True, text=True, timeout=120, check=False)


@needs_oc3
def test_report_renders_in_headless_chromium(oc3_run: tuple[Result, Path],
                                             tmp_path: Path) -> None:
    binary = _chromium()
    if binary is None:
        pytest.skip("no chromium binary (Debian: apt-get install -y chromium)")
    _, directory = oc3_run
    url = (directory / REPORT_FILE).resolve().as_uri()
    dom = _run_chromium(binary, "--enable-logging=stderr", "--dump-dom", url)
    assert dom.returncode == 0, dom.stderr
    # a page that does not load logs "Page load failed: net::ERR_..."
    assert "Page load failed" not in dom.stderr and "net::ERR" not in dom.stderr, dom.stderr
    page = _Page()
    page.feed(dom.stdout)
    assert [h.strip() for h in page.h2] == list(SECTIONS.values())
    assert page.section_ids == list(SECTIONS)
    assert len(page.images) == 3 and all(s.startswith("data:image/png;base64,")
                                         for s in page.images)
    shot = tmp_path / "report.png"
    done = _run_chromium(binary, f"--screenshot={shot}", "--window-size=1200,4000", url)
    assert done.returncode == 0, done.stderr
    assert shot.read_bytes().startswith(PNG) and shot.stat().st_size > 10_000
    from PIL import Image

    with Image.open(shot) as image:
        assert image.size == (1200, 4000)
        rgb = image.convert("RGB")
        # the styled header (background #14305a) is drawn, and the page is not blank
        assert rgb.getpixel((5, 5)) == (0x14, 0x30, 0x5A)
        assert len(rgb.getcolors(maxcolors=1 << 20) or []) > 100


OFFSET = ROOT / "cases" / "oc3_offset.yaml"


@pytest.mark.skipif(not OFFSET.is_file(), reason="cases/oc3_offset.yaml not present")
def test_offset_run_report_has_the_group_stiffness_and_the_offset_curves(
        tmp_path: Path) -> None:
    """The OC3 offset case, shortened (one heading, 5 offsets): the Offset section, the
    point group's 6x6 in the Stiffness section (the summary's values) and offset.png."""
    text = OFFSET.read_text(encoding="utf-8")
    text = re.sub(r"headings: \[[^]]*\]", "headings: [0]", text)
    text = re.sub(r"steps: *\d+", "steps: 5", text).replace("yaw: true", "yaw: false")
    case = tmp_path / "offset.yaml"
    case.write_text(text, encoding="utf-8")
    result = _invoke("run", case, "--out", tmp_path)
    assert result.exit_code == 0, result.stderr
    directory = tmp_path / "oc3-offset"
    offset = json.loads((directory / "summary.json").read_text())["analyses"][1]
    assert offset["kind"] == "offset" and len(offset["headings"]) == 1
    page = _parse(directory / REPORT_FILE)
    assert not page.errors
    assert [h.strip() for h in page.h2] == [*list(SECTIONS.values())[:-1], "Offset", "Plots"]
    assert "offset.png" in page.captions and len(page.images) == len(page.captions)
    text = " ".join(page.text)
    assert "6x6 stiffness at zero offset" in text
    for row in offset["stiffness"]:
        for value in row:
            assert f"{value:.6g}" in text, value
    for value in offset["headings"][0]["offsets"]:
        assert f"{value:.6g}" in text
