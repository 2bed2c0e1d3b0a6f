"""Write the docstrings of ``covmap/_native.pyi``, and its lists of the
sensor models' parameters, from the built module.

The stub's signatures are written by hand (the module knows no types), but
for the sensor models' parameters: the blocks between ``# generated: ...``
and ``# end generated`` are written from the classes' ``PARAMETERS`` (the
core's one declaration of them), a ``@property`` each
(``properties(Class)``, or ``properties(Class - Other)`` for those another
class lacks) or a keyword-only argument each (``keywords(Class)``). Its
docstrings are the native module's own, written once in Rust. This script
puts each runtime ``__doc__`` into the stub, so that no docstring is kept by
hand twice::

    python python/tools/gen_stubs.py          # rewrite the stub's docstrings
    python python/tools/gen_stubs.py --check  # exit 1 if they are stale

It needs ``covmap`` importable (built, e.g. ``maturin develop``); the stub is
the one beside the imported module. ``python/tests/test_stubs.py`` checks the
result independently of this script.

What gets a docstring: the module, each class, function, method and property
the module documents (the first of overloaded definitions). Slot methods
(``__eq__``, ``__hash__``, ...) and ``__new__`` carry Python's generic text,
not the module's, and get none. A ``@type_check_only`` base class of the stub
(members that several classes share) gets the members' docstrings, which
must then be the same in every class deriving from it; its own docstring
stays as written.
"""

from __future__ import annotations

import argparse
import ast
import inspect
import re
import sys
import types
from pathlib import Path
from typing import Any

GENERIC_MEMBERS = {"__new__", "__init__"}
"""Members whose runtime docstring is Python's, not the module's."""


def runtime_doc(owner: Any, name: str) -> str | None:
    """The module's own docstring of ``owner.name`` (cleaned), or ``None``."""
    if name in GENERIC_MEMBERS:
        return None
    static = inspect.getattr_static(owner, name)
    if isinstance(static, (types.WrapperDescriptorType, types.MethodWrapperType)):
        return None
    doc = getattr(owner, name).__doc__
    return inspect.cleandoc(doc) if doc else None


def _is_type_check_only(node: ast.ClassDef) -> bool:
    return any(isinstance(d, ast.Name) and d.id == "type_check_only" for d in node.decorator_list)


def _defs(body: list[ast.stmt], owner: Any) -> dict[ast.AST, str | None]:
    """The docstring of each definition in ``body``, whose names are
    attributes of ``owner`` at run time: the first definition of a name (of
    several overloads) gets the docstring, the others none."""
    docs: dict[ast.AST, str | None] = {}
    seen: set[str] = set()
    for node in body:
        if isinstance(node, ast.FunctionDef):
            docs[node] = runtime_doc(owner, node.name) if node.name not in seen else None
            seen.add(node.name)
    return docs


def expected_docs(tree: ast.Module, module: Any) -> dict[ast.AST, str | None]:
    """The docstring each documentable node of the stub should carry (the
    module, its functions, its classes and their members)."""
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    expected: dict[ast.AST, str | None] = {tree: inspect.cleandoc(module.__doc__)}
    expected.update(_defs(tree.body, module))
    shared: dict[ast.AST, dict[str, str | None]] = {}
    for node in tree.body:
        if not isinstance(node, ast.ClassDef) or _is_type_check_only(node):
            continue
        runtime = getattr(module, node.name)
        expected[node] = runtime_doc(module, node.name)
        expected.update(_defs(node.body, runtime))
        for base in node.bases:
            if isinstance(base, ast.Name) and base.id in classes:
                for member, doc in _defs(classes[base.id].body, runtime).items():
                    shared.setdefault(member, {})[node.name] = doc
    for member, docs in shared.items():
        if len(set(docs.values())) != 1:
            name = getattr(member, "name")
            raise SystemExit(f"the classes sharing {name} document it differently: {docs}")
        expected[member] = next(iter(docs.values()))
    return expected


def _docstring(node: ast.AST) -> ast.Expr | None:
    body = getattr(node, "body", [])
    first = body[0] if body else None
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
        return first
    return None


def render(doc: str, indent: str) -> list[str]:
    """``doc`` as the lines of a docstring at ``indent``."""
    if '"""' in doc:
        raise SystemExit(f"a docstring holds triple quotes: {doc!r}")
    prefix = "r" if "\\" in doc else ""
    lines = doc.split("\n")
    if len(lines) == 1 and not doc.endswith('"'):
        return [f'{indent}{prefix}"""{doc}"""']
    return [
        f'{indent}{prefix}"""{lines[0]}',
        *(f"{indent}{line}" if line else "" for line in lines[1:]),
        f'{indent}"""',
    ]


GENERATED = re.compile(
    r"^(?P<indent> *)# generated: (?P<kind>properties|keywords)\((?P<cls>\w+)(?: - (?P<minus>\w+))?\)\n"
    r"(?:.*\n)*?(?P=indent)# end generated$",
    re.MULTILINE,
)
"""A generated block of the stub: its indent, what it lists, of which class."""


def parameters(module: Any, cls: str, minus: str | None) -> list[str]:
    """The names of ``cls``'s parameters (``PARAMETERS``), less ``minus``'s."""
    names: list[str] = list(getattr(module, cls).PARAMETERS)
    if minus is not None:
        names = [n for n in names if n not in getattr(module, minus).PARAMETERS]
    return names


def rewrite_parameters(text: str, module: Any) -> str:
    """``text`` (the stub) with every generated block listing the parameters
    the module's classes have now (docstrings left for :func:`rewrite`)."""

    def block(m: re.Match[str]) -> str:
        indent = m["indent"]
        names = parameters(module, m["cls"], m["minus"])
        if m["kind"] == "properties":
            lines = [f"{indent}@property\n{indent}def {n}(self) -> float: ..." for n in names]
        else:
            lines = [f"{indent}{n}: float | None = None," for n in names]
        head = f"{indent}# generated: {m['kind']}({m['cls']}{' - ' + m['minus'] if m['minus'] else ''})"
        return "\n".join([head, *lines, f"{indent}# end generated"])

    return GENERATED.sub(block, text)


def rewrite(text: str, module: Any) -> str:
    """``text`` (the stub) with every docstring the module's."""
    text = rewrite_parameters(text, module)
    tree = ast.parse(text)
    lines = text.split("\n")
    edits: list[tuple[int, int, list[str]]] = []  # lines [first, end) become the new ones
    for node, doc in expected_docs(tree, module).items():
        body: list[ast.stmt] = getattr(node, "body")
        indent = "" if isinstance(node, ast.Module) else " " * (getattr(node, "col_offset") + 4)
        existing = _docstring(node)
        first = body[0]
        if existing is not None:
            kept = render(doc, indent) if doc else [] if len(body) > 1 else [f"{indent}..."]
            edits.append((existing.lineno - 1, existing.end_lineno or existing.lineno, kept))
        elif doc is None:
            continue
        elif isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and first.value.value is Ellipsis:
            # The body is `...`: on the header's line (`def f() -> T: ...`) or its own.
            header = lines[first.lineno - 1][: first.col_offset].rstrip()
            kept = [header] if header.strip() else []
            edits.append((first.lineno - 1, first.lineno, [*kept, *render(doc, indent)]))
        else:
            blank = [""] if isinstance(node, ast.ClassDef) else []
            edits.append((first.lineno - 1, first.lineno - 1, [*render(doc, indent), *blank]))
    for first_line, end, new in sorted(edits, key=lambda e: e[0], reverse=True):
        lines[first_line:end] = new
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="only check; exit 1 if the stub is stale")
    args = parser.parse_args()
    import covmap._native as module

    stub = Path(module.__file__).with_name("_native.pyi")
    text = stub.read_text()
    new = rewrite(text, module)
    if new == text:
        print(f"{stub}: docstrings up to date")
        return 0
    if args.check:
        print(f"{stub}: docstrings are stale; run python/tools/gen_stubs.py", file=sys.stderr)
        return 1
    stub.write_text(new)
    print(f"{stub}: docstrings written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
