"""The type stubs cover the module: every public name and every public member of its classes."""

import ast
import pathlib

import mpr

STUB = pathlib.Path(mpr.__file__).with_name("__init__.pyi")


def stub_names():
    tree = ast.parse(STUB.read_text())
    top, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            top.add(node.target.id)
        if isinstance(node, ast.ClassDef):
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    return top, members


def test_every_public_name_has_a_stub():
    top, members = stub_names()
    assert set(mpr.__all__) <= top, set(mpr.__all__) - top
    for cls in ("Camera", "View", "FrameSet"):
        public = {n for n in dir(getattr(mpr, cls)) if not n.startswith("_")}
        assert public <= members[cls], (cls, public - members[cls])


def test_every_call_has_a_docstring():
    for name in mpr.__all__:
        obj = getattr(mpr, name)
        if callable(obj) and name not in ("Scene",):
            assert obj.__doc__ and len(obj.__doc__) > 20, name


def binding_signatures(name, doc):
    """Each `name(arg: type = default, ...) -> ...` line of a pybind11 docstring (one per
    overload) as a list of (argument, default or None)."""
    out = []
    for line in doc.splitlines():
        if not line.startswith(name + "(") or ") ->" not in line:
            continue
        depth, current, parts = 0, "", []
        for ch in line[len(name) + 1:line.rindex(") ->")]:
            depth += (ch in "([{") - (ch in ")]}")
            if ch == "," and depth == 0:
                parts.append(current)
                current = ""
            else:
                current += ch
        if current.strip():
            parts.append(current)
        out.append([(p.split(":")[0].strip(), p.split("=", 1)[1].strip() if "=" in p else None) for p in parts])
    return out


def test_stub_signatures_match_the_bindings():
    """Every function the stub declares takes the binding's arguments, in its order, with its
    defaults (a stub default of `...` stands for any)."""
    tree = ast.parse(STUB.read_text())
    checked = 0
    for node in tree.body:
        if not isinstance(node, ast.FunctionDef) or node.name.startswith("_") or not hasattr(mpr, node.name):
            continue
        args = node.args.args
        defaults = [None] * (len(args) - len(node.args.defaults)) + [ast.unparse(d) for d in node.args.defaults]
        stub = [(a.arg, d) for a, d in zip(args, defaults)]
        bound = binding_signatures(node.name, getattr(mpr, node.name).__doc__ or "")
        assert bound, node.name
        assert any(len(b) == len(stub) and all(s[0] == n and s[1] in ("...", d) for s, (n, d) in zip(stub, b))
                   for b in bound), (node.name, stub, bound)
        checked += 1
    assert checked >= 15
