#!/usr/bin/python3
"""The include graph of base/ shaders/ scenes/ harness/ algorithms/ keeps its
layers (docs/ARCHITECTURE.md, "Layers").

Every `#include "..."` of a C++ or GLSL file there is read. It fails, naming
the file and line, on
  1. an include cycle between modules (a module is x.h with x.cpp; module A
     depends on B when A's header or source includes B's header), anywhere;
  2. an include of a higher layer: each layer may include its own and lower
     layers, in the order of LAYERS; algorithms/ may include only ALGORITHM_USES;
  3. an include written relative to the including file instead of from the
     repository root, and a file in a folder no layer names.
Includes that name no file of the repository (generated headers such as
oit_revision.h) are not judged. Before the repository, the checker runs on
a small tree holding each fault and must report each one by file and line.
argv[1]: the repository root (default: this file's parent's parent)."""
import os
import re
import sys
import tempfile

# Lowest first; a file may include files of its own layer and the layers
# before it. shaders/ is the GLSL library with bindings.h, shared by C++ and
# GLSL: any layer may include it, and it includes only itself.
LAYERS = [
    ("base", ["base/", "shaders/"]),
    ("scenes", ["scenes/"]),
    ("harness/gl", ["harness/gl/"]),
    ("harness/toolkit", ["harness/toolkit/"]),
    ("harness/output", ["harness/output/"]),
    ("harness/run", ["harness/run/"]),
    ("harness/app", ["harness/app/"]),
    ("algorithms", ["algorithms/"]),
]
# A technique sees the harness only through the toolkit (and GL): it knows
# nothing of how runs are driven, measured or written. Techniques may share
# each other's code (linearized_fragment_buffer draws with linked_list's
# length classes).
ALGORITHM_USES = {"base", "scenes", "harness/gl", "harness/toolkit", "algorithms"}

SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".c")
SHADER_SUFFIXES = (".glsl", ".vert", ".frag", ".comp", ".geom")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def layer_of(path):
    for index, (name, prefixes) in enumerate(LAYERS):
        if any(path.startswith(prefix) for prefix in prefixes):
            return index, name
    return None, None


def module_of(path):
    """x.h and x.cpp are one module; a GLSL file is a module of its own."""
    stem, suffix = os.path.splitext(path)
    return stem if suffix in SOURCE_SUFFIXES else path


def read_includes(root):
    """[(file, line, included path)] of every quoted include under the
    layers' folders, and the problems found while reading them."""
    includes, problems = [], []
    folders = sorted({prefix.split("/")[0] for _, prefixes in LAYERS for prefix in prefixes})
    for folder in folders:
        for directory, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if not name.endswith(SOURCE_SUFFIXES + SHADER_SUFFIXES):
                    continue
                path = os.path.relpath(os.path.join(directory, name), root)
                if layer_of(path)[0] is None:
                    problems.append(f"{path}: in no layer; move it into one or name its folder in "
                                    f"LAYERS of tests/include_layers_test.py and docs/ARCHITECTURE.md")
                with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
                    for number, text in enumerate(f, 1):
                        match = INCLUDE.match(text)
                        if not match:
                            continue
                        target = match.group(1)
                        if os.path.isfile(os.path.join(root, target)):
                            includes.append((path, number, target))
                        elif os.path.isfile(os.path.join(root, os.path.dirname(path), target)):
                            whole = os.path.normpath(os.path.join(os.path.dirname(path), target))
                            problems.append(f'{path}:{number}: #include "{target}" is relative to the file; '
                                            f'write it from the repository root: #include "{whole}"')
    return includes, problems


def layer_problems(includes):
    problems = []
    for path, number, target in includes:
        rank, layer = layer_of(path)
        target_rank, target_layer = layer_of(target)
        if rank is None or target_rank is None:
            continue
        if layer == "algorithms":
            allowed = target_layer in ALGORITHM_USES
            rule = "a technique includes only " + ", ".join(sorted(ALGORITHM_USES))
        else:
            allowed = target_rank <= rank
            rule = f"{layer} may include only its own and lower layers ({' < '.join(n for n, _ in LAYERS)})"
        if not allowed:
            problems.append(f'{path}:{number}: #include "{target}" reaches up from {layer} into {target_layer}: '
                            f"{rule}; move what it needs down, or the code up (docs/ARCHITECTURE.md, Layers)")
    return problems


def module_graph(includes):
    """{module: {module it depends on: (file, line, included path) of the first such include}}"""
    graph = {}
    for path, number, target in includes:
        source, dependency = module_of(path), module_of(target)
        graph.setdefault(source, {})
        graph.setdefault(dependency, {})
        if dependency != source:
            graph[source].setdefault(dependency, (path, number, target))
    return graph


def strongly_connected(graph):
    """Tarjan's components, iteratively (no recursion limit on long chains)."""
    index, low, on_stack, stack, components = {}, {}, set(), [], []
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, successors = work[-1]
            advanced = False
            for successor in successors:
                if successor not in index:
                    index[successor] = low[successor] = len(index)
                    stack.append(successor)
                    on_stack.add(successor)
                    work.append((successor, iter(sorted(graph[successor]))))
                    advanced = True
                    break
                if successor in on_stack:
                    low[node] = min(low[node], index[successor])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                components.append(sorted(component))
    return components


def shortest_cycle_through(graph, start, members):
    """The modules of a shortest cycle from `start` back to it within `members`."""
    previous, frontier = {start: None}, [start]
    while frontier:
        following = []
        for node in frontier:
            for successor in sorted(graph[node]):
                if successor == start:
                    path = [node]
                    while previous[path[-1]] is not None:
                        path.append(previous[path[-1]])
                    return list(reversed(path)) + [start]
                if successor in members and successor not in previous:
                    previous[successor] = node
                    following.append(successor)
        frontier = following
    return [start]


def cycle_problems(includes):
    graph = module_graph(includes)
    problems = []
    for component in strongly_connected(graph):
        if len(component) < 2:
            continue
        cycle = shortest_cycle_through(graph, component[0], set(component))
        lines = [f"include cycle between modules: {' -> '.join(cycle)}"]
        for source, dependency in zip(cycle, cycle[1:]):
            path, number, target = graph[source][dependency]
            lines.append(f'  {path}:{number}: #include "{target}"')
        if len(component) > len(cycle) - 1:
            lines.append(f"  (the cycle's component also holds {', '.join(m for m in component if m not in cycle)})")
        lines.append("  move the declaration both need into the module where it belongs, so one includes the other")
        problems.append("\n".join(lines))
    return problems


def check(root):
    includes, problems = read_includes(root)
    return problems + layer_problems(includes) + cycle_problems(includes)


def write(root, path, text):
    os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
    with open(os.path.join(root, path), "w") as f:
        f.write(text)


def self_check():
    """The checker finds each kind of fault, by file and line, in a small tree."""
    with tempfile.TemporaryDirectory() as root:
        write(root, "base/params.h", "#pragma once\n")
        write(root, "harness/run/runner.h", '#pragma once\n#include "harness/toolkit/technique.h"\n')
        write(root, "harness/run/runner.cpp", '#include "harness/run/runner.h"\n#include "harness/run/prepared_run.h"\n')
        write(root, "harness/run/prepared_run.h", '#pragma once\n\n#include "harness/run/runner.h"\n')
        write(root, "harness/toolkit/technique.h", '#pragma once\n#include "base/params.h"\n')
        write(root, "harness/toolkit/technique.cpp", '#include "harness/toolkit/technique.h"\n#include "harness/output/image.h"\n')
        write(root, "harness/output/image.h", "#pragma once\n")
        write(root, "algorithms/x/x.cpp", '#include "harness/toolkit/technique.h"\n#include "harness/run/runner.h"\n'
                                          '#include "x.h"\n#include "oit_revision.h"\n')
        write(root, "algorithms/x/x.h", "#pragma once\n")
        write(root, "harness/core/old.h", "#pragma once\n")
        found = "\n".join(check(root))
    expected = [
        "harness/run/prepared_run -> harness/run/runner -> harness/run/prepared_run",
        'harness/run/runner.cpp:2: #include "harness/run/prepared_run.h"',
        'harness/run/prepared_run.h:3: #include "harness/run/runner.h"',
        'harness/toolkit/technique.cpp:2: #include "harness/output/image.h" reaches up from harness/toolkit '
        "into harness/output",
        'algorithms/x/x.cpp:2: #include "harness/run/runner.h" reaches up from algorithms into harness/run',
        'algorithms/x/x.cpp:3: #include "x.h" is relative to the file; write it from the repository root: '
        '#include "algorithms/x/x.h"',
        "harness/core/old.h: in no layer",
    ]
    missed = [text for text in expected if text not in found]
    assert not missed, "the checker missed:\n" + "\n".join(missed) + "\nit reported:\n" + found
    assert "oit_revision.h" not in found and "technique.h:2" not in found, "the checker reported a good include:\n" + found


def main():
    self_check()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    problems = check(root)
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        sys.exit(f"{len(problems)} include problem(s); the layers are in docs/ARCHITECTURE.md, Layers")
    print("includes keep the layers; no include cycle between modules")


if __name__ == "__main__":
    main()
