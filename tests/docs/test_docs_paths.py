"""Every module, file and Python name the documentation names exists.

Read from README.md and docs/*.md:

* file and folder paths under the repository's own folders (``fe_crank/...``, ``tests/...``,
  ``docs/...``, ``benchmarks/...``, ``tools/...``, ``loadcases/...``, ``geometry/...``,
  ``engines/...``) and paths inside the package written from a subpackage
  (``assess/fatigue.py``); paths with a placeholder (``<key>``, ``*``) are patterns, not files;
* a bare module file name in code quotes (```fatigue.py```): some file of that name in the
  repository;
* dotted names ``fe_crank.x.y``: the module, then each attribute;
* dotted names in code quotes that start with a subpackage and one of its modules
  (```assess.fatigue.goodman```): the same, inside ``fe_crank``.  Dotted input keys
  (```cad.faces.axis```, ``[mesh] symmetric``) name no module and are left alone.
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "fe_crank"
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
TOP = ("fe_crank", "tests", "docs", "benchmarks", "tools", "loadcases", "geometry", "engines")
SUBPACKAGES = tuple(sorted(p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists()))
MUTANT = re.compile(r"^x_(\w+?)__mutmut_\d+$")  # mutmut's name of a mutant of a function

_PATH = re.compile(r"(?<![\w/.~$-])((?:[\w.-]+/)+[\w.-]*)")
_DOTTED = re.compile(r"(?<![\w.])fe_crank(?:\.\w+)+")
_CODE = re.compile(r"`([^`\n]+)`")
_SHORT = re.compile(r"^(\w+)\.(\w+)(?:\.(\w+))*(?:\(\))?$")


def _paths(text: str) -> set[str]:
    out = set()
    for m in _PATH.finditer(text):
        p = m.group(1).rstrip(".,:;")
        if any(c in text[m.end() : m.end() + 1] for c in "<*{"):
            continue
        head = p.split("/", 1)[0]
        if head in TOP or head in SUBPACKAGES:
            out.add(p)
    return out


def _exists(path: str) -> bool:
    head = path.split("/", 1)[0]
    if head in TOP and (ROOT / path).exists():
        return True
    return head in SUBPACKAGES and (PACKAGE / path).exists()


def _resolve(dotted: str) -> str | None:
    """None when ``dotted`` names a module of fe_crank and attributes of it, else why not."""
    parts = dotted.split(".")
    for n in range(len(parts), 0, -1):
        name = ".".join(parts[:n])
        try:
            obj = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name is not None and not name.startswith(exc.name) and not exc.name.startswith(name):
                return f"importing {name}: {exc}"
            continue
        break
    else:
        return "no such module"
    for k, attr in enumerate(parts[n:]):
        mutant = MUTANT.match(attr)
        if mutant and k == len(parts) - n - 1:
            attr = mutant.group(1)
        if not hasattr(obj, attr):
            return f"{'.'.join(parts[: n + k])} has no {attr!r}"
        obj = getattr(obj, attr)
    return None


def _short_names(text: str) -> set[str]:
    """Dotted names in code quotes that start with a subpackage and one of its modules."""
    out = set()
    for span in _CODE.findall(text):
        m = _SHORT.match(span.strip())
        if not m:
            continue
        sub, mod = m.group(1), m.group(2)
        if sub in SUBPACKAGES and ((PACKAGE / sub / f"{mod}.py").exists() or (PACKAGE / sub / mod).is_dir()):
            out.add(span.strip().removesuffix("()"))
    return out


def _file_names(text: str) -> set[str]:
    return {s for s in _CODE.findall(text) if re.fullmatch(r"[\w]+\.py", s)}


_FILES = None


def _repository_file_names() -> set[str]:
    global _FILES
    if _FILES is None:
        _FILES = {p.name for top in TOP for p in (ROOT / top).rglob("*.py")}
    return _FILES


@pytest.mark.parametrize("doc", DOCS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_path_and_name_a_doc_names_exists(doc: Path):
    text = doc.read_text(encoding="utf-8")
    missing = [f"path {p}" for p in sorted(_paths(text)) if not _exists(p)]
    missing += [f"file {f}" for f in sorted(_file_names(text)) if f not in _repository_file_names()]
    for name in sorted(_DOTTED.findall(text)):
        why = _resolve(name)
        if why:
            missing.append(f"name {name}: {why}")
    for name in sorted(_short_names(text)):
        why = _resolve(f"fe_crank.{name}")
        if why:
            missing.append(f"name {name}: {why}")
    assert not missing, f"{doc.relative_to(ROOT)} names what does not exist:\n" + "\n".join(missing)


def test_the_reader_finds_paths_and_names():
    text = (
        "see `assess/fatigue.py`, fe_crank/fe/linalg/factorise.py and tests/test_none_such.py; "
        "`fe_crank.fe.linalg.factorise`, fe_crank.nothing.here, `assess.fatigue.no_such`, "
        "`cad.faces.axis` (a key), `.cache/meshes/<key>/`, `gone.py`"
    )
    assert _paths(text) == {"assess/fatigue.py", "fe_crank/fe/linalg/factorise.py", "tests/test_none_such.py"}
    assert not _exists("tests/test_none_such.py") and _exists("assess/fatigue.py")
    assert _resolve("fe_crank.fe.linalg.factorise") is None
    assert _resolve("fe_crank.nothing.here") is not None
    assert _short_names(text) == {"assess.fatigue.no_such"}
    assert _resolve("fe_crank.assess.fatigue.no_such") is not None
    assert _file_names(text) == {"gone.py"} and "gone.py" not in _repository_file_names()
