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
