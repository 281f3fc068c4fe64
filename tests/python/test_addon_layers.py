"""The add-on's package order (docs/architecture.md, "The add-on"): its sub-packages import one way only.

Read from the sources with Python's ast (no Blender needed). Every relative import counts, those inside
functions too: a module may import from its own sub-package and from the layers before its own, never
from a later layer nor from another unit of its own layer. A top-level module is a unit of its own.
"""
import ast
import pathlib

from conftest import REPO

ADDON = REPO / "python_addon" / "gauss_stylization"

# Bottom first. The package's own __init__.py loads and registers everything and is left out.
LAYERS = (
    ("errors", "app_handlers"),
    ("native",),
    ("settings",),
    ("mesh",),
    ("view",),
    ("run",),
    ("handles", "sphere", "bake"),
    ("operators", "slot_operators", "crossing_operators", "reach_operators"),
    ("ui",),
)


def _unit_of(parts):
    """The unit a module belongs to: its sub-package, or the top-level module itself."""
    return parts[0] if parts else "__init__"


def imports_between_units(package):
    """[(importing file, importing unit, imported unit)] of every relative import in ``package``."""
    found = []
    for path in sorted(pathlib.Path(package).rglob("*.py")):
        parts = list(path.relative_to(package).with_suffix("").parts)
        if parts == ["__init__"]:
            continue
        folder = parts[:-1]  # the package that holds this module: relative imports start there
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.ImportFrom) or node.level == 0:
                continue
            base = folder[:len(folder) - (node.level - 1)]
            if node.module:
                targets = [base + node.module.split(".")]
            else:
                targets = [base + [alias.name] for alias in node.names]
            for target in targets:
                found.append((path.relative_to(package).as_posix(), _unit_of(folder or parts), _unit_of(target)))
    return found


def layer_violations(package, layers):
    """Imports that go up the layers or sideways within one; units not in ``layers`` are named too."""
    rank = {unit: number for number, layer in enumerate(layers) for unit in layer}
    problems = []
    for path, importer, imported in imports_between_units(package):
        if imported == "gauss_core":  # native.py's compiled module, not a unit of the sources
            continue
        if importer not in rank or imported not in rank:
            problems.append("%s: %s -> %s: not in the layers" % (path, importer, imported))
        elif importer != imported and rank[imported] >= rank[importer]:
            problems.append("%s: %s imports %s, which is not below it" % (path, importer, imported))
    return problems


def test_the_add_on_imports_down_the_layers_only():
    assert layer_violations(ADDON, LAYERS) == []


def test_every_unit_of_the_add_on_has_a_layer():
    units = {path.stem if path.is_file() else path.name for path in ADDON.iterdir()
             if (path.suffix == ".py" and path.stem != "__init__") or (path / "__init__.py").is_file()}
    assert units == {unit for layer in LAYERS for unit in layer}


def _write(root, name, text):
    path = root / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")


def test_the_check_finds_an_import_up_or_sideways(tmp_path):
    package = tmp_path / "addon"
    _write(package, "__init__.py", "from . import low, high\n")
    _write(package, "errors.py", "")
    _write(package, "low/__init__.py", "")
    _write(package, "low/a.py", "from .. import errors\n\ndef later():\n    from ..high import b\n")
    _write(package, "high/__init__.py", "")
    _write(package, "high/b.py", "from ..low.a import later\nfrom . import c\n")
    _write(package, "high/c.py", "from ..side import d\n")
    _write(package, "side/__init__.py", "")
    _write(package, "side/d.py", "")
    layers = (("errors",), ("low",), ("high", "side"))
    assert layer_violations(package, layers) == [
        "high/c.py: high imports side, which is not below it",
        "low/a.py: low imports high, which is not below it",
    ]
    assert layer_violations(package, (("errors",), ("low",), ("side",), ("high",))) == [
        "low/a.py: low imports high, which is not below it"]
