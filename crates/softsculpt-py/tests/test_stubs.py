"""The type stubs describe the module as built: every public name, method and property of the
native module appears in _core.pyi, and every one there exists."""

import ast
from pathlib import Path

import softsculpt._core as core

STUBS = Path(__file__).parents[1] / "python" / "softsculpt" / "_core.pyi"


def stubbed():
    tree = ast.parse(STUBS.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
    return names


def test_the_stubs_name_exactly_what_the_module_has():
    stubs = stubbed()
    public = {n for n in dir(core) if not n.startswith("__")}
    assert set(stubs) == public  # both ways: nothing public unstubbed, no stub of nothing
    for cls in ("World", "Body"):
        members = {n for n in vars(getattr(core, cls)) if not n.startswith("__") or n == "__reduce__"}
        assert stubs[cls] == members, cls
    assert {"World", "Body", "SimulationError", "parameters", "scene_files"} <= set(stubs)
