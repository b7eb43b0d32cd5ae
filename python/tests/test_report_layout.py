# SPDX-License-Identifier: MIT
"""The batch report as a reader sees it: the index and a material page parsed
(balanced elements, the tables' structure: a header row per model naming its
parameters, a published row under each, the Models table's median ratio, the
Error matrix sortable with data-v numbers), and laid out by headless Chromium
at 1200 and 1400 px wide: no table cell wraps (the text of each line of a
cell lies on one line box), the star stays with its number, and no page is
wider than the window. Skipped, saying so, without the chromium binary."""

import html
import html.parser
import json
import os
import re
import shutil
import subprocess

import pytest

# every model: the glTF ones have four parameters, the widest parameter table
MODELS = ["ward", "ward-duer", "blinn-phong", "lafortune", "cook-torrance",
          "ashikhmin-shirley", "he", "ggx", "gltf", "gltf-ext", "openpbr"]
DEMO = "synthetic-alum-bronze-ct"
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta",
        "source", "track", "wbr"}

# Injected into a copy of a page: after load, every td/th (but prose cells,
# class wrap or failed) is measured: its text nodes grouped by the block box
# they sit in; a group whose text spans more than 1.5 line heights wrapped.
MEASURE = r"""
<script>
window.addEventListener('load', function () {
  var bad = [], n = 0;
  document.querySelectorAll('td, th').forEach(function (c) {
    n++;
    if (/\b(wrap|failed)\b/.test(c.className)) return;
    var groups = new Map(), tw = document.createTreeWalker(c, NodeFilter.SHOW_TEXT), t;
    while ((t = tw.nextNode())) {
      if (!t.data.trim()) continue;
      var b = t.parentElement;
      while (b !== c && getComputedStyle(b).display.indexOf('inline') === 0) b = b.parentElement;
      var r = document.createRange(); r.selectNodeContents(t);
      var g = groups.get(b) || [];
      Array.prototype.forEach.call(r.getClientRects(), function (x) { if (x.width > 0) g.push(x); });
      groups.set(b, g);
    }
    groups.forEach(function (g, b) {
      if (!g.length) return;
      var cs = getComputedStyle(b), lh = parseFloat(cs.lineHeight);
      if (!(lh > 0)) lh = 1.2 * parseFloat(cs.fontSize);
      var top = Math.min.apply(null, g.map(function (x) { return x.top; }));
      var bot = Math.max.apply(null, g.map(function (x) { return x.bottom; }));
      if (bot - top > 1.5 * lh) bad.push(c.textContent.trim() + ' (' + Math.round(bot - top) + ' px, line ' + Math.round(lh) + ')');
    });
  });
  var pre = document.createElement('pre');
  pre.id = 'layout-report';
  pre.textContent = JSON.stringify({cells: n, wrapped: bad,
      overflow: document.documentElement.scrollWidth - document.documentElement.clientWidth});
  document.body.appendChild(pre);
});
</script>
"""


class Page(html.parser.HTMLParser):
    """Balanced elements (a stray or missing end tag fails), and the tables."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack, self.problems = [], []
        self.tables = []          # each: list of rows; row: (tr attrs, [(tag, attrs, text)])
        self.cell = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "table":
            self.tables.append([])
        elif tag == "tr" and self.tables:
            self.tables[-1].append((a, []))
        elif tag in ("td", "th") and self.tables and self.tables[-1]:
            self.cell = [tag, a, ""]
            self.tables[-1][-1][1].append(self.cell)
        if tag not in VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        if tag in VOID:
            return
        if not self.stack or self.stack[-1] != tag:
            self.problems.append(f"</{tag}> closes {self.stack[-1] if self.stack else 'nothing'}")
            return
        self.stack.pop()
        if tag in ("td", "th"):
            self.cell = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell[2] += data


def parse(path):
    p = Page()
    with open(path, encoding="utf-8") as f:
        p.feed(f.read())
    p.close()
    assert not p.problems, f"{path}: {p.problems}"
    assert p.stack == [], f"{path}: left open: {p.stack}"
    return p


# two tables of models with noise (no model fits them exactly): rows to sort
NOISY = {"noisy-blinn": ("blinn-phong", [0.05, 0.1, 0.2, 0.3, 0.3, 0.3, 300.0]),
         "noisy-ward": ("ward", [0.3, 0.2, 0.1, 0.05, 0.05, 0.05, 0.2])}


@pytest.fixture(scope="module")
def report(cli, brdffit, tmp_path_factory):
    """The batch of the demo material and two noisy tables with every model,
    and a published-fits file of the demo material (no scale stated): a row
    under each model, and a second line in its cells of the Error matrix."""
    import numpy as np
    d = tmp_path_factory.mktemp("report")
    rng = np.random.default_rng(7)
    tables = []
    for name, (model, params) in NOISY.items():
        t = brdffit.Table.from_model(model, params)
        v = t.values
        covered = v >= 0
        v[covered] *= rng.uniform(0.6, 1.4, int(covered.sum()))
        tables.append(str(d / f"{name}.binary"))
        t.write(tables[-1])
    pub = d / "published.tsv"
    rows = {"ward": "0.1\t0.07\t0.03\t0.05\t0.03\t0.02\t0.04\t\t",
            "ward-duer": "0.1\t0.07\t0.03\t0.05\t0.03\t0.02\t0.04\t\t",
            "blinn-phong": "0.1\t0.07\t0.03\t0.02\t0.01\t0.005\t1500\t\t",
            "lafortune": "0.1\t0.07\t0.03\t0.2\t0.1\t0.06\t-0.58\t0.58\t1000",
            "cook-torrance": "0.09\t0.06\t0.03\t0.12\t0.07\t0.04\t0.2\t0.037\t",
            "ashikhmin-shirley": "0.09\t0.06\t0.03\t0.13\t0.08\t0.04\t0.19\t1400\t",
            "he": "0.09\t0.06\t0.03\t0.14\t0.08\t0.04\t20\t0.5\t2.4"}
    pub.write_text("material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\n" +
                   "".join(f"{DEMO}\t{m}\t{v}\n" for m, v in rows.items()))
    out = d / "demo"
    r = subprocess.run([cli, "batch", *tables, "--demo", "--out", str(out), "--model", ",".join(MODELS),
                        "--starts", "1", "--no-render", "--no-plot", "--quiet",
                        "--published", str(pub)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    return out


def cells(row):
    return [c[2].strip() for c in row[1]]


def test_index_tables(report):
    p = parse(report / "index.html")
    models = next(t for t in p.tables if t and cells(t[0])[:2] == ["model", "median Error"])
    assert cells(models[0])[2] == "median ratio to published"
    assert len(models) == 1 + len(MODELS)
    ggx = next(r for r in models if cells(r)[0] == "GGX")
    assert cells(ggx)[2] == "-"  # no published GGX row: no ratio
    ward = next(r for r in models if cells(r)[0] == "Ward")
    assert re.fullmatch(r"[0-9.e-]+ \(of 1\)", cells(ward)[2]), cells(ward)
    matrix = next(t for t in p.tables if t and cells(t[0])[0] == "material")
    assert len(cells(matrix[0])) == 1 + len(MODELS)
    assert [cells(r)[0] for r in matrix[1:]] == sorted(NOISY) + [DEMO]  # by name
    row = matrix[3]
    values = [c for c in row[1] if "data-v" in c[1]]
    assert len(values) == len(MODELS)
    best = [c for c in values if c[1].get("class") == "best"]
    assert len(best) == 1 and re.match(r"[0-9.e-]+\u00a0\u2605", best[0][2]), best
    for c in values:
        assert float(c[1]["data-v"]) >= 0
    # the published Error and the ratio under the Error, in full on hover
    # every model but GGX and the renderers' (glTF, OpenPBR) has published parameters: their
    # Error and the ratio
    assert sum("\u00d7" in c[2] for c in values) == len(MODELS) - 4
    src = (report / "index.html").read_text()
    assert "<script>" in src and "aria-sort" in src and 'id="matrix"' in src
    assert 'data="headline.svg"' in src  # an object: the SVG's titles show on hover


def test_material_page_tables(report):
    p = parse(report / DEMO / "index.html")
    (t,) = [t for t in p.tables if t and t[0][0].get("class") == "mhead"]
    heads = [r for r in t if r[0].get("class") == "mhead"]
    assert [cells(h)[0] for h in heads] == ["Ward", "Ward-Duer", "Blinn-Phong", "Lafortune",
                                           "Cook-Torrance", "Ashikhmin-Shirley", "He", "GGX",
                                           "glTF 2.0", "glTF 2.0 extended", "OpenPBR Surface"]
    assert cells(heads[8])[7:11] == ["metallic", "roughness", "ior", "specular"]
    assert cells(heads[3])[7:10] == ["Cxy", "Cz", "n"]  # names in the header, not in cells
    assert cells(heads[0])[7] == "alpha"
    pubs = [r for r in t if r[0].get("class") == "pub"]
    assert len(pubs) == len(MODELS)
    ward_pub = cells(pubs[0])
    assert ward_pub[0] == "published" and ward_pub[1:8] == ["0.1", "0.07", "0.03", "0.05",
                                                           "0.03", "0.02", "0.04"]
    assert "no published parameters" in cells(pubs[7])[1]  # GGX
    for r in t:
        if r[0].get("class") == "mhead":
            continue
        for c in cells(r)[1:]:
            assert not re.search(r"[A-Za-z] [0-9]", c), c  # a number without its name
            assert "e+" not in c and "e-0" not in c, c  # the compact exponent: 2.8e4, 1.2e-5


def test_headline_figure(report):
    """Every point names its material, model and Error on hover; the axis is
    that of the bulk: the generating model's Error of about 1e-13 on its own
    data is a triangle below the axis, not a decade of the axis."""
    import xml.etree.ElementTree as ET
    ns = "{http://www.w3.org/2000/svg}"
    root = ET.parse(report / "headline.svg").getroot()
    titles = [c.find(ns + "title") for c in root.iter(ns + "circle")]
    points = [t.text for t in titles if t is not None]
    # Cook-Torrance's on the demo is below the axis
    assert len(points) == 3 * len(MODELS) - 1, points
    names = tuple(n + " \u2014 " for n in [DEMO, *NOISY])
    assert all(t.startswith(names) for t in points), points
    below = [p.find(ns + "title").text for p in root.iter(ns + "path")]
    assert len(below) == 1 and "Cook-Torrance" in below[0] and "below the axis" in below[0], below
    ticks = [t.text for t in root.iter(ns + "text") if re.fullmatch(r"1e-\d+|0\.0*1|1", t.text or "")]
    lowest = min(float(t) for t in ticks)
    assert 1e-8 <= lowest <= 1e-3, ticks  # not stretched down to 1e-14
    assert any("1 below the axis" in (t.text or "") for t in root.iter(ns + "text"))


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


@pytest.mark.parametrize("width", [1200, 1400])
@pytest.mark.parametrize("page", ["index.html", f"{DEMO}/index.html"])
def test_no_cell_wraps(report, page, width, tmp_path):
    exe = chromium()
    if not exe:
        pytest.skip("no chromium on PATH (Debian: apt-get install chromium; .ci/install-deps "
                    "installs it): the layout at 1200 and 1400 px is not checked")
    src = report / page
    probe = src.parent / f"layout-probe-{width}.html"  # beside the page: its links resolve
    text = src.read_text(encoding="utf-8")
    probe.write_text(text.replace("</body>", MEASURE + "</body>"), encoding="utf-8")
    r = subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                        f"--window-size={width},900", "--virtual-time-budget=2000",
                        f"--user-data-dir={tmp_path / 'profile'}", "--dump-dom",
                        probe.as_uri()], capture_output=True, text=True, timeout=120)
    probe.unlink()
    m = re.search(r'<pre id="layout-report">(.*?)</pre>', r.stdout, re.S)
    assert m, f"chromium gave no measurement (exit {r.returncode}): {r.stderr[-2000:]}"
    got = json.loads(html.unescape(m.group(1)))
    assert got["cells"] > 20, got
    assert got["wrapped"] == [], f"{page} at {width} px: cells that wrap: {got['wrapped']}"
    assert got["overflow"] <= 0, f"{page} at {width} px is {got['overflow']} px too wide"


SORT = r"""
<script>
window.addEventListener('load', function () {
  var t = document.getElementById('matrix'), hs = t.tHead.rows[0].cells, got = {};
  function order() {
    return Array.prototype.map.call(t.tBodies[0].rows, function (r) {
      return [r.cells[0].textContent.trim(), r.cells[1].getAttribute('data-v')];
    });
  }
  hs[1].click(); got.up = order(); got.aria = hs[1].getAttribute('aria-sort');
  hs[1].click(); got.down = order();
  hs[0].click(); hs[0].click(); got.names_down = order();
  var pre = document.createElement('pre');
  pre.id = 'sort-report';
  pre.textContent = JSON.stringify(got);
  document.body.appendChild(pre);
});
</script>
"""


def test_matrix_sorts_by_a_column(report, tmp_path):
    """The matrix's script: a click on a model's header sorts the rows by its
    Error, a second click the other way; the material column by name."""
    exe = chromium()
    if not exe:
        pytest.skip("no chromium on PATH: the sorting script is not run")
    probe = report / "sort-probe.html"
    probe.write_text((report / "index.html").read_text(encoding="utf-8").replace(
        "</body>", SORT + "</body>"), encoding="utf-8")
    r = subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu",
                        "--window-size=1200,900", "--virtual-time-budget=2000",
                        f"--user-data-dir={tmp_path / 'profile'}", "--dump-dom",
                        probe.as_uri()], capture_output=True, text=True, timeout=120)
    probe.unlink()
    m = re.search(r'<pre id="sort-report">(.*?)</pre>', r.stdout, re.S)
    assert m, r.stderr[-2000:]
    got = json.loads(html.unescape(m.group(1)))
    up = [float(v) for _, v in got["up"]]
    assert up == sorted(up) and len(up) == 3, got
    assert [float(v) for _, v in got["down"]] == sorted(up, reverse=True), got
    assert got["aria"] == "ascending"
    assert [n for n, _ in got["names_down"]] == sorted([DEMO, *NOISY], reverse=True), got


def test_measure_finds_a_wrapped_cell(report, tmp_path):
    """The measurement itself: a page whose cells are made to wrap is caught."""
    exe = chromium()
    if not exe:
        pytest.skip("no chromium on PATH: the layout check cannot be checked either")
    text = (report / "index.html").read_text(encoding="utf-8")
    squeezed = text.replace("white-space:nowrap", "white-space:normal").replace(
        "</style>", "td{max-width:3em}</style>")
    probe = report / "layout-probe-squeezed.html"
    probe.write_text(squeezed.replace("</body>", MEASURE + "</body>"), encoding="utf-8")
    r = subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu",
                        "--window-size=1200,900", "--virtual-time-budget=2000",
                        f"--user-data-dir={tmp_path / 'profile'}", "--dump-dom",
                        probe.as_uri()], capture_output=True, text=True, timeout=120)
    probe.unlink()
    m = re.search(r'<pre id="layout-report">(.*?)</pre>', r.stdout, re.S)
    assert m, r.stderr[-2000:]
    assert json.loads(html.unescape(m.group(1)))["wrapped"], "a squeezed table was not caught"
