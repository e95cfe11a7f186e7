"""The type stubs name exactly what the extension module has."""

import ast
from pathlib import Path

import rotorflow
from rotorflow import _rotorflow

STUB = Path(__file__).resolve().parents[1] / "rotorflow" / "_rotorflow.pyi"


def stub_names():
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    classes, functions = {}, set()
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            classes[node.name] = {
                n.name for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("__")
            }
        elif isinstance(node, ast.FunctionDef):
            functions.add(node.name)
    return classes, functions


def test_every_public_name_has_a_stub_and_every_stub_a_name():
    classes, functions = stub_names()
    runtime_classes = {n: getattr(_rotorflow, n) for n in dir(_rotorflow) if isinstance(getattr(_rotorflow, n), type)}
    assert set(classes) == set(runtime_classes)
    compared = 0
    for name, cls in runtime_classes.items():
        public = {m for m in vars(cls) if not m.startswith("__")}
        assert classes[name] == public, name
        compared += len(public)
    runtime_functions = {n for n in dir(_rotorflow) if callable(getattr(_rotorflow, n)) and not n.startswith("_") and n not in runtime_classes}
    assert functions == runtime_functions
    assert compared > 80
    # The geometry functions are exported by the modules rotorflow.pga, .cga and .sta.
    geometry = {f for f in runtime_functions if f.split("_")[0] in ("pga", "cga", "sta")}
    assert len(geometry) == 17
    for f in geometry:
        module, name = f.split("_", 1)
        assert getattr(getattr(rotorflow, module), name) is getattr(_rotorflow, f)
    assert set(rotorflow.__all__) >= set(runtime_classes) | (runtime_functions - geometry)


def test_every_public_method_has_a_docstring():
    missing = []
    for name in dir(_rotorflow):
        cls = getattr(_rotorflow, name)
        if isinstance(cls, type):
            assert cls.__doc__, name
            for m, v in vars(cls).items():
                if not m.startswith("_") and not (getattr(v, "__doc__", None) or "").strip():
                    missing.append(f"{name}.{m}")
    assert missing == []
