#!/usr/bin/env python3
"""Checks the library's layer order on its include graph.

The library's layers, bottom up, are the folders of include/coshell/ and
source/: a file may include headers of its own layer and of the layers
below it, never of a layer above (an upward edge), and the files may not
include each other in a cycle. The executable (source/app) sits on top.
The solvers know no physics: they include nothing of element, mesh, model
or contact.

    check_layers.py --root <source tree> [--graph FILE.dot]

Prints the layer-to-layer edges with their counts; exits 1 naming every
upward edge (with the file and the header), every file not in a known
layer, and every include cycle.
"""
import argparse
import collections
import pathlib
import re
import sys

LAYERS = ["base", "element", "mesh", "model", "contact", "solvers", "io",
          "driver", "app"]
# Edges the order allows but the design does not: the solvers (Newton, time
# integration, path following, linear solvers) know no physics, so they see
# the problem only through base's interfaces.
NEVER = {"solvers": {"element", "mesh", "model", "contact"}}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"](?:coshell/)?([^>"]+)[>"]')


def layer_of(path, root):
    """The layer of a file under include/coshell/<layer>/ or
    source/<layer>/, or None."""
    parts = path.relative_to(root).parts
    if parts[0] == "include" and len(parts) > 2 and parts[1] == "coshell":
        return parts[2]
    if parts[0] == "source" and len(parts) > 1:
        return parts[1]
    return None


def resolve(header, including, root):
    """The file a quoted or <coshell/...> include names, or None for a
    header outside the project (deal.II, the standard library)."""
    candidates = [root / "include" / "coshell" / header,
                  including.parent / header]
    for candidate in candidates:
        if candidate.is_file():
            return candidate.resolve()
    return None


def include_graph(root):
    files = sorted(p.resolve() for folder in ("include", "source")
                   for p in (root / folder).rglob("*")
                   if p.suffix in (".h", ".cc"))
    graph = {}
    for path in files:
        targets = []
        for line in path.read_text(encoding="utf-8").splitlines():
            match = INCLUDE.match(line)
            if match:
                target = resolve(match.group(1), path, root)
                if target is not None:
                    targets.append(target)
        graph[path] = targets
    return graph


def find_cycle(graph):
    """One include cycle as a list of files, or None."""
    colour = {node: 0 for node in graph}  # 0 new, 1 on the path, 2 done
    path = []

    def visit(node):
        colour[node] = 1
        path.append(node)
        for target in graph.get(node, []):
            if colour.get(target, 0) == 1:
                return path[path.index(target):] + [target]
            if colour.get(target, 0) == 0:
                cycle = visit(target)
                if cycle:
                    return cycle
        path.pop()
        colour[node] = 2
        return None

    for node in graph:
        if colour[node] == 0:
            cycle = visit(node)
            if cycle:
                return cycle
    return None


def write_dot(edges, path):
    with open(path, "w", encoding="utf-8") as dot:
        dot.write("digraph layers {\n  rankdir=BT;\n")
        for (source, target), count in sorted(edges.items()):
            dot.write(f'  "{source}" -> "{target}" [label="{count}"];\n')
        dot.write("}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=pathlib.Path, required=True)
    parser.add_argument("--graph", type=pathlib.Path,
                        help="also write the layer graph as Graphviz dot")
    args = parser.parse_args()
    root = args.root.resolve()
    rank = {layer: k for k, layer in enumerate(LAYERS)}

    graph = include_graph(root)
    problems = []
    edges = collections.Counter()
    for path, targets in graph.items():
        source = layer_of(path, root)
        if source not in rank:
            problems.append(f"{path.relative_to(root)}: not in a known layer "
                            f"({', '.join(LAYERS)})")
            continue
        for target_path in targets:
            target = layer_of(target_path, root)
            if target not in rank:
                problems.append(f"{path.relative_to(root)} includes "
                                f"{target_path.relative_to(root)}, outside "
                                f"the layers")
                continue
            if target != source:
                edges[(source, target)] += 1
            if rank[target] > rank[source]:
                problems.append(
                    f"upward edge {source} -> {target}: "
                    f"{path.relative_to(root)} includes "
                    f"{target_path.relative_to(root)}")
            elif target in NEVER.get(source, ()):
                problems.append(
                    f"forbidden edge {source} -> {target}: "
                    f"{path.relative_to(root)} includes "
                    f"{target_path.relative_to(root)}")
    cycle = find_cycle(graph)
    if cycle:
        problems.append("include cycle: " + " -> ".join(
            str(p.relative_to(root)) for p in cycle))

    for (source, target), count in sorted(
            edges.items(), key=lambda e: (rank[e[0][0]], rank[e[0][1]])):
        print(f"{source:>8} -> {target:<8} {count:4d} include(s)")
    if args.graph:
        write_dot(edges, args.graph)
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_layers: {len(problems)} problem(s)")
        return 1
    print(f"check_layers: {len(graph)} files, no upward or forbidden edge, "
          f"no cycle "
          f"(layers bottom up: {', '.join(LAYERS)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
