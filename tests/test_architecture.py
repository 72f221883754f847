"""The package's shape (issue 26 point 4): the layers and the vendors'
independence that pyproject.toml's [tool.importlinter] contracts state hold,
and no module imports itself through others (no import circle), counting
imports inside functions and under TYPE_CHECKING too."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

grimp = pytest.importorskip("grimp")

ROOT = Path(__file__).resolve().parent.parent


def lint_imports(cwd: Path, src: Path) -> subprocess.CompletedProcess:
    """lint-imports over the package found in ``src``, with the contracts of
    ``cwd``'s pyproject.toml (no cache: nothing is written to the checkout)."""
    env = dict(os.environ, PYTHONPATH=str(src))
    code = "import sys; from importlinter.cli import lint_imports; " \
           "sys.exit(lint_imports(no_cache=True))"
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, env=env,
                          capture_output=True, text=True)


def test_import_contracts_hold():
    res = lint_imports(ROOT, ROOT / "src")
    assert res.returncode == 0, res.stdout + res.stderr
    assert "0 broken" in res.stdout


def copy_of_package(tmp_path: Path) -> Path:
    shutil.copytree(ROOT / "src" / "ucsio", tmp_path / "src" / "ucsio",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    return tmp_path / "src"


@pytest.mark.parametrize("module, line, contract", [
    # geometry reaching up into the method breaks the layers
    ("geometry/rotations.py", "from ..method import horn", "Layers"),
    # one vendor's folder using another's
    ("vendors/abb/rapid.py", "from ..kuka import krl", "imports no other vendor's"),
    ("vendors/fanuc/va.py", "from ..abb.rapid import parse", "imports no other vendor's"),
    # what the vendors share leaning on one of them
    ("vendors/common/taught.py", "from ..fanuc import tp", "share imports no vendor"),
])
def test_a_broken_contract_is_caught(tmp_path, module, line, contract):
    """The contracts are not vacuous: one wrong import in a copy of the
    package fails lint-imports, naming the contract it breaks."""
    src = copy_of_package(tmp_path)
    with open(src / "ucsio" / module, "a") as f:
        f.write(f"\n\ndef _wrong():\n    {line}\n")
    res = lint_imports(tmp_path, src)
    assert res.returncode != 0
    broken = [ln for ln in res.stdout.splitlines() if " BROKEN" in ln]
    assert len(broken) >= 1 and any(contract in ln for ln in broken), res.stdout


def circles(graph) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's
    algorithm, iterative): each is a set of modules that import each other."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for root in sorted(graph.modules):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.find_modules_directly_imported_by(root))))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.find_modules_directly_imported_by(child)))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    m = stack.pop()
                    on_stack.discard(m)
                    component.append(m)
                    if m == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def test_no_import_circle_in_the_package():
    graph = grimp.build_graph("ucsio", include_external_packages=False)
    assert circles(graph) == []


def test_an_import_circle_is_found(tmp_path):
    """The finder sees a circle closed by an import inside a function (the
    kind the parsers had: controller -> fanuc -> va -> controller)."""
    pkg = tmp_path / "circled"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from . import b\n")
    (pkg / "b.py").write_text("def f():\n    from . import c\n")
    (pkg / "c.py").write_text("from .a import b\n")
    (pkg / "d.py").write_text("from . import a\n")
    sys.path.insert(0, str(tmp_path))
    try:
        graph = grimp.build_graph("circled", include_external_packages=False, cache_dir=None)
    finally:
        sys.path.remove(str(tmp_path))
    assert circles(graph) == [["circled.a", "circled.b", "circled.c"]]
