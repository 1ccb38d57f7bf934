"""The API reference: every public name is on the API pages, the main entry points with their
signature and a parameter table that matches the code, and no Sphinx role left as raw text."""
from __future__ import annotations

import ast
import html
import importlib
import inspect
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ["vbikit", "vbikit.solve", "vbikit.scenario", "vbikit.analysis", "vbikit.bridge", "vbikit.contact"]
ROLES = re.compile(r":(func|class|meth|data|mod|attr|obj|exc|const):`")
RAW_ROLES = re.compile(r"(?<!\w):(?:func|class|meth|data|mod|attr|obj|exc|const):")  # as rendered: the backticks became <code>
HEADING = re.compile(r'<h[1-6] id="(vbikit(?:\.\w+)*)" class="doc doc-heading"')
TABLE = re.compile(r'<span class="doc-section-title">(?:Parameters|Attributes):</span>.*?<tbody>(.*?)</tbody>', re.S)
ROW = re.compile(r'<tr class="doc-section-item">\s*<td>(.*?)</td>\s*<td>(.*?)</td>', re.S)


@pytest.fixture(scope="module")
def api_pages(strict_site) -> dict[str, str]:
    """The built API pages (the run's strict build, ``strict_site``): page name → HTML."""
    assert strict_site["returncode"] == 0, strict_site["output"]
    site = Path(strict_site["site"])
    return {p.parent.name: p.read_text(encoding="utf-8") for p in sorted((site / "api").glob("*/index.html"))}


def _objects(pages: dict[str, str]) -> dict[str, str]:
    """Every documented object on the API pages: heading id → its heading and own contents."""
    out = {}
    for text in pages.values():
        parts = HEADING.split(text)
        for ident, body in zip(parts[1::2], parts[2::2]):
            out[ident] = body
    return out


def _text(fragment: str, sep: str = " ") -> str:
    return html.unescape(" ".join(re.sub(r"<[^>]+>", sep, fragment).split()))


def _parameter_table(body: str) -> dict[str, str]:
    """The object's parameter table (a record's attribute table): name → type as rendered."""
    match = TABLE.search(body)
    return {} if match is None else {_text(name): _text(kind) for name, kind in ROW.findall(match.group(1))}


def test_no_sphinx_role_on_the_api_pages(api_pages):
    raw = {page: sorted(set(RAW_ROLES.findall(_text(text, sep="")))) for page, text in api_pages.items()}
    assert not {page: roles for page, roles in raw.items() if roles}, raw


def test_no_sphinx_role_in_docstrings():
    # mkdocstrings does not read Sphinx roles: cross-references are [`name`][vbikit.path]
    hits = []
    for path in sorted((ROOT / "src" / "vbikit").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            body = getattr(node, "body", None)
            if not isinstance(body, list):
                continue
            for stmt in body:
                if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant) \
                        and isinstance(stmt.value.value, str) and ROLES.search(stmt.value.value):
                    hits.append(f"{path.relative_to(ROOT)}:{stmt.lineno}")
    assert not hits, "Sphinx roles in docstrings: " + ", ".join(hits)


@pytest.mark.parametrize("package", PACKAGES)
def test_every_public_name_is_on_the_api_pages(api_pages, package):
    documented = {ident.rsplit(".", 1)[-1] for ident in _objects(api_pages)}
    names = [n for n in importlib.import_module(package).__all__ if not n.startswith("__")]
    missing = [n for n in names if n not in documented]
    assert not missing, f"{package}.__all__ names without an entry on the API pages: {missing}"


# (documented id, the object): each is on the pages with its signature and a parameter table
# that lists exactly the signature's parameters (a record built by the library: its attributes)
ENTRY_POINTS = [
    ("vbikit.scenario.pipeline.run", "vbikit.scenario.pipeline:run"),
    ("vbikit.scenario.report.Report", "vbikit.scenario.report:Report"),
    ("vbikit.scenario.build.build", "vbikit.scenario.build:build"),
    ("vbikit.solve.simulate.simulate", "vbikit.solve.simulate:simulate"),
    ("vbikit.solve.Crossing", "vbikit.solve.crossing:Crossing"),
    ("vbikit.solve.VehicleMotion", "vbikit.solve.crossing:VehicleMotion"),
    ("vbikit.solve.Integrator", "vbikit.solve.integrators:Integrator"),
    ("vbikit.solve.register_integrator", "vbikit.solve.integrators:register_integrator"),
    ("vbikit.solve.RunPlan", "vbikit.solve.plan:RunPlan"),
    ("vbikit.solve.plan_run", "vbikit.solve.plan:plan_run"),
    ("vbikit.contact.register_tire", "vbikit.contact.registry:register_tire"),
    ("vbikit.analysis.ResponsePlan", "vbikit.analysis.plan:ResponsePlan"),
    ("vbikit.analysis.ResponsePoint", "vbikit.analysis.plan:ResponsePoint"),
    ("vbikit.errors.VbikitError", "vbikit.errors:VbikitError"),
    ("vbikit.outputs.Output", "vbikit.outputs:Output"),
    ("vbikit.outputs.Quantity", "vbikit.outputs:Quantity"),
    ("vbikit.outputs.Reduction", "vbikit.outputs:Reduction"),
    ("vbikit.outputs.register_output", "vbikit.outputs:register_output"),
    ("vbikit.bridge.GirderSection", "vbikit.bridge.sections:GirderSection"),
    ("vbikit.bridge.ScaledBridge", "vbikit.bridge.scaled:ScaledBridge"),
    ("vbikit.vehicle.Vehicle", "vbikit.vehicle.model:Vehicle"),
    ("vbikit.vehicle.Wheel", "vbikit.vehicle.model:Wheel"),
    ("vbikit.road.RoadProfile", "vbikit.road.profile:RoadProfile"),
    ("vbikit.road.RoadPSD", "vbikit.road.psd:RoadPSD"),
    ("vbikit.road.Defect", "vbikit.road.defects:Defect"),
    ("vbikit.analysis.ImpactFactor", "vbikit.analysis.impact:ImpactFactor"),
    ("vbikit.scenario.BuiltScenario", "vbikit.scenario.build:BuiltScenario"),
    ("vbikit.traffic.VehicleRecord", "vbikit.traffic.records:VehicleRecord"),
    ("vbikit.traffic.LaneTraffic", "vbikit.traffic.stream:LaneTraffic"),
    ("vbikit.traffic.TruckClass", "vbikit.traffic.stream:TruckClass"),
    ("vbikit.traffic.Event", "vbikit.traffic.events:Event"),
    ("vbikit.solve.CrossingResult", "vbikit.solve.result:CrossingResult"),
    ("vbikit.analysis.PointResponse", "vbikit.analysis.response:PointResponse"),
    ("vbikit.contact.RigidDiskTire", "vbikit.contact.tires:RigidDiskTire"),
    ("vbikit.contact.DiskTire", "vbikit.contact.tires:DiskTire"),
    ("vbikit.vehicle.VehicleBuilder", "vbikit.vehicle.builder:VehicleBuilder"),
    ("vbikit.bridge.EulerBernoulliBeam", "vbikit.bridge.beam:EulerBernoulliBeam"),
]


@pytest.mark.parametrize("ident, target", ENTRY_POINTS, ids=[e[0] for e in ENTRY_POINTS])
def test_entry_point_has_its_signature_and_parameter_table(api_pages, ident, target):
    objects = _objects(api_pages)
    assert ident in objects, f"{ident} is not on the API pages"
    module, name = target.split(":")
    obj = getattr(importlib.import_module(module), name)
    params = [("*" + p.name if p.kind is p.VAR_POSITIONAL else "**" + p.name if p.kind is p.VAR_KEYWORD else p.name)
              for p in inspect.signature(obj).parameters.values()]
    heading = _text(objects[ident].split("</h", 1)[0], sep="")
    assert f"{name}(" in heading, f"{ident}: no signature in the heading {heading!r}"
    assert sorted(_parameter_table(objects[ident])) == sorted(params)


def test_crossing_parameters_have_their_own_types(api_pages):
    table = _parameter_table(_objects(api_pages)["vbikit.solve.Crossing"])
    assert {k: table[k] for k in ("bridge", "vehicle", "tire", "road", "vehicles")} == {
        "bridge": "ModalBridge", "vehicle": "Vehicle", "tire": "TireModel", "road": "RoadProfile",
        "vehicles": "tuple of VehicleMotion"}


def test_the_solve_page_documents_the_function_simulate(api_pages):
    # a function that shares its module's name: the function, not the module, is on the page
    assert 'id="vbikit.solve.simulate.simulate"' in api_pages["solve"]
    assert 'id="vbikit.scenario.build.build"' in api_pages["scenario"]
