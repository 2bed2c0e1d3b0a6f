"""The stub ``covmap/_native.pyi`` carries the native module's own docstrings.

stubtest (in CI) checks the stub's names and signatures against the module;
this checks its docstrings, which python/tools/gen_stubs.py writes from the
module. A docstring changed in Rust and not written into the stub fails here.
"""

from __future__ import annotations

import ast
import inspect
import types
from pathlib import Path
from typing import Any

import covmap._native as native

STUB = Path(native.__file__).with_name("_native.pyi")
HINT = "the stub's docstrings are stale: run python python/tools/gen_stubs.py"


def own_doc(owner: Any, name: str) -> str | None:
    """The docstring the module gives ``owner.name``: ``None`` for ``__new__``
    and slot methods, whose docstrings are Python's generic ones."""
    static = inspect.getattr_static(owner, name)
    if name == "__new__" or isinstance(static, (types.WrapperDescriptorType, types.MethodWrapperType)):
        return None
    doc = getattr(owner, name).__doc__
    return inspect.cleandoc(doc) if doc else None


def stub_defs(body: list[ast.stmt]) -> dict[str, list[ast.FunctionDef]]:
    defs: dict[str, list[ast.FunctionDef]] = {}
    for node in body:
        if isinstance(node, ast.FunctionDef):
            defs.setdefault(node.name, []).append(node)
    return defs


def compare(where: str, runtime: str | None, defs: list[ast.FunctionDef], wrong: list[str]) -> None:
    """The first definition (of overloads) carries the runtime docstring, the others none."""
    docs = [ast.get_docstring(d) for d in defs]
    if docs != [runtime] + [None] * (len(defs) - 1):
        wrong.append(f"{where}: stub {docs[0]!r}, module {runtime!r}")


def test_stub_docstrings_are_the_modules() -> None:
    tree = ast.parse(STUB.read_text())
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    wrong: list[str] = []
    checked = 0
    if ast.get_docstring(tree) != inspect.cleandoc(native.__doc__ or ""):
        wrong.append("the module docstring")
    for name, defs in stub_defs(tree.body).items():
        compare(name, own_doc(native, name), defs, wrong)
        checked += 1
    for name in native.__all__:
        runtime = getattr(native, name)
        if not isinstance(runtime, type):
            continue
        node = classes[name]
        if ast.get_docstring(node) != own_doc(native, name):
            wrong.append(f"class {name}")
        # Members of the class and of its stub-only bases.
        members = stub_defs(node.body)
        for base in node.bases:
            if isinstance(base, ast.Name) and base.id in classes:
                for member, defs in stub_defs(classes[base.id].body).items():
                    members.setdefault(member, defs)
        for member, defs in members.items():
            compare(f"{name}.{member}", own_doc(runtime, member), defs, wrong)
            checked += 1
        # Every member the module documents is in the stub.
        for member, value in vars(runtime).items():
            routine = callable(value) or isinstance(value, (staticmethod, classmethod))
            if not (routine or inspect.isdatadescriptor(value)):
                continue  # __doc__, __module__
            if own_doc(runtime, member) is not None and member not in members:
                wrong.append(f"{name}.{member}: documented by the module, absent from the stub")
    assert not wrong, HINT + ":\n" + "\n".join(wrong)
    assert checked > 100, f"only {checked} definitions checked: is the stub the right file?"
