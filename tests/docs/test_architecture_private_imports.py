"""No module of fe_crank imports another module's private (``_name``) names.

A name with a leading underscore is its module's own; a helper another module needs is made
public in the module that owns the concept.  Read from the sources' syntax trees: every
``from fe_crank.x import _y`` (module level or inside a function, absolute or relative) and
every ``m._y`` on a module ``m`` imported from fe_crank.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "fe_crank"

#: (importing module, imported module, name) still to be made public; each entry is a debt
KNOWN: set[tuple[str, str, str]] = set()


def _module_name(path: Path, package: Path) -> str:
    parts = path.relative_to(package.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _absolute(node: ast.ImportFrom, module: str, is_package: bool) -> str | None:
    if node.level == 0:
        return node.module
    base = module.split(".")
    base = base if is_package else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def private_imports(path: Path, package: Path = PACKAGE) -> list[tuple[str, str, str, int]]:
    """(importing module, imported module, private name, line) of one source file of ``package``."""
    module = _module_name(path, package)
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = []
    aliases: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            source = _absolute(node, module, path.name == "__init__.py")
            if not source or not source.startswith("fe_crank"):
                continue
            for a in node.names:
                if _private(a.name) and source != module:
                    found.append((module, source, a.name, node.lineno))
                aliases[a.asname or a.name] = f"{source}.{a.name}"
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("fe_crank"):
                    aliases[a.asname or a.name.split(".")[0]] = a.name if a.asname else a.name.split(".")[0]
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Name)
            and node.value.id in aliases
            and _private(node.attr)
            and aliases[node.value.id] != module
        ):
            found.append((module, aliases[node.value.id], node.attr, node.lineno))
    return found


def test_the_walker_finds_private_imports(tmp_path):
    pkg = tmp_path / "fe_crank" / "sub"
    pkg.mkdir(parents=True)
    src = pkg / "a.py"
    src.write_text(
        "from fe_crank.sub.b import _hidden, public\n"
        "from .c import _other\n"
        "from fe_crank.sub import d as dm\n"
        "def f():\n"
        "    from fe_crank.e import _late\n"
        "    return dm._inner + _hidden + _other + _late\n"
        "from fe_crank.sub.b import __version__\n"
    )
    names = {(imported, name) for _, imported, name, _ in private_imports(src, tmp_path / "fe_crank")}
    assert names == {
        ("fe_crank.sub.b", "_hidden"),
        ("fe_crank.sub.c", "_other"),
        ("fe_crank.e", "_late"),
        ("fe_crank.sub.d", "_inner"),
    }


def test_no_module_imports_another_modules_private_names():
    found = [hit for path in sorted(PACKAGE.rglob("*.py")) for hit in private_imports(path)]
    offending = [f"{m}:{line} uses {src}.{name}" for m, src, name, line in found if (m, src, name) not in KNOWN]
    assert not offending, "private names imported across modules:\n" + "\n".join(offending)
    stale = KNOWN - {(m, src, name) for m, src, name, _ in found}
    assert not stale, f"entries of KNOWN no longer needed: {sorted(stale)}"
