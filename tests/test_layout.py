"""The package's layout is its architecture (docs/architecture.md): stages as folders, few modules at
the top, no import circle among cablefem's modules (function-level imports counted), and no module
``__getattr__`` standing in for a moved name (a package's lazy ``__init__`` is allowed)."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "cablefem"

#: the stages, in the order data flows through them (docs/architecture.md draws them)
FOLDERS = {"model", "fem", "loads", "compiled", "statics", "dynamics", "runs", "io", "geometry", "waves", "sweeps"}


def module_name(path):
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def modules():
    return {module_name(path): path for path in PACKAGE.rglob("*.py")}


def imports(name, path, known):
    """The cablefem modules that module ``name`` imports anywhere in its source."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1] + ([base] if base else []))
            targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in known else base for alias in node.names]
        elif isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        else:
            continue
        for target in targets:
            while target and target not in known:
                target = target.rpartition(".")[0]
            if target and target != name:
                found.add(target)
    return found


def cycles(graph):
    """The strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return found


def test_no_import_circle_among_the_package_modules_counting_function_level_imports():
    known = modules()
    graph = {name: imports(name, path, known) for name, path in known.items()}
    assert cycles(graph) == []


def test_the_detector_finds_a_circle_made_by_a_function_level_import(tmp_path):
    # the test above could pass by finding nothing: a circle through a function-level import is seen
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert cycles(graph) == [["a", "b", "c"]]


def test_at_most_twelve_modules_at_the_top_and_the_stages_are_folders():
    top = [path.name for path in PACKAGE.glob("*.py")]
    assert len(top) <= 12, top
    folders = {path.name for path in PACKAGE.iterdir() if (path / "__init__.py").exists()}
    assert folders == FOLDERS


def test_no_module_getattr_outside_a_package_init():
    shims = [module_name(path) for path in PACKAGE.rglob("*.py") if path.name != "__init__.py"
             and any(isinstance(node, ast.FunctionDef) and node.name == "__getattr__"
                     for node in ast.parse(path.read_text()).body)]
    assert shims == []


def test_statics_and_dynamics_do_not_know_which_face_they_run_on():
    """One evaluator interface (cablefem.fem.evaluator): statics and dynamics import neither face's
    evaluator class and test no object for being one; ``LineSystem.evaluator`` picks it."""
    faces = {"NumpyEvaluator", "FusedEvaluator"}
    named = []
    for stage in ("statics", "dynamics"):
        for path in (PACKAGE / stage).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text())):
                if isinstance(node, ast.Name) and node.id in faces or (
                        isinstance(node, ast.alias) and node.name in faces) or (
                        isinstance(node, ast.Attribute) and node.attr in faces):
                    named.append((module_name(path), getattr(node, "id", None) or getattr(node, "name", None)
                                  or node.attr))
    assert named == []
