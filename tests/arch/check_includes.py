#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The library has no circles, between files or between folders.

Files: source file A depends on B when A's object file uses a symbol that
B's defines (read with nm from the library's objects in BUILD/CMakeFiles/
rt.dir); the graph must be acyclic, so that no two files call each other.
Folders: the stage folders of host/ (base, scene, formats, accel, layout,
backend, render, opencl, vulkan, cli with its view/), cpu_ref, kernels and
bench (its programs, engines/ and peer/); folder X depends on Y when a file in
X includes a file in Y; also acyclic, so that data and calls flow one way
(docs/ARCHITECTURE.md): rtcl (host/cli) may use the benchmark engines
(bench/engines), never the other way round. Also: only bench/ includes the
benchmark peer; backends include no scene header; host/cli includes no header
of the library but rt.h (the CLI is a program on the public API), and the
bench/engines headers it includes include nothing of the library but rt.h.

Usage: check_includes.py SOURCE_ROOT BUILD_DIR. Exit 1 with the circle or
problem found, 0 when there is none."""
import os
import re
import sys

import subprocess

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
root = os.path.abspath(root)
build = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else None
dirs = ["host", "cpu_ref", "kernels", "bench"]
# The include paths the build gives: the library's folders, bench/ (for
# "peer/..." and "engines/..."), and rtcl's own folders.
include_roots = [os.path.join(root, d) for d in dirs + ["host/cli", "host/cli/view"]]

files = []
for d in dirs:
    for base, _, names in os.walk(os.path.join(root, d)):
        for n in names:
            if n.endswith((".c", ".h", ".cpp", ".cl")):
                files.append(os.path.join(base, n))


def resolve(src, name):
    for cand in [os.path.join(os.path.dirname(src), name)] + [os.path.join(r, name) for r in include_roots]:
        if os.path.isfile(cand):
            return os.path.abspath(cand)
    return None


def folder(path):
    rel = os.path.relpath(path, root).split(os.sep)
    if rel[0] == "host" and len(rel) > 2:
        return "host/" + rel[1]
    return rel[0] if rel[0] != "host" else "host"


def unit(path):
    return os.path.splitext(path)[0]


def rel(path):
    return os.path.relpath(path, root)


# What a file of rtcl (host/cli) may include: rt.h, its own folder's headers
# and the benchmark engines' interface (bench/engines/*.h), which in turn may
# include nothing of the library but rt.h.
def cli_may_include(target):
    r = rel(target)
    return r == os.path.join("host", "rt.h") or r.startswith(os.path.join("host", "cli") + os.sep) or (
        r.startswith(os.path.join("bench", "engines") + os.sep) and r.endswith(".h"))


def library_header(target):
    r = rel(target)
    return r.split(os.sep)[0] in ("host", "cpu_ref", "kernels") and not r.startswith(
        os.path.join("host", "cli") + os.sep)


edges_unit, edges_folder, where = {}, {}, {}
problems = []
for f in files:
    text = open(f, encoding="utf-8", errors="replace").read()
    for m in re.finditer(r'^\s*#\s*include\s+"([^"]+)"', text, re.M):
        target = resolve(f, m.group(1))
        if target is None:
            if "peer/" in m.group(1) and not rel(f).startswith("bench" + os.sep):
                problems.append(f"{rel(f)} includes the benchmark peer {m.group(1)}")
            continue
        if rel(target).startswith(os.path.join("bench", "peer") + os.sep) and not rel(f).startswith(
                "bench" + os.sep):
            problems.append(f"{rel(f)} includes the benchmark peer {m.group(1)}: only bench/ may")
        if rel(f).startswith(os.path.join("host", "cli") + os.sep) and not cli_may_include(target):
            problems.append(f"{rel(f)} includes {m.group(1)}: host/cli uses only rt.h (and bench/engines/*.h)")
        if (rel(f).startswith(os.path.join("bench", "engines") + os.sep) and f.endswith(".h")
                and library_header(target) and rel(target) != os.path.join("host", "rt.h")):
            problems.append(f"{rel(f)} includes {m.group(1)}: the engines' interface, which rtcl "
                            f"includes, may use only rt.h")
        fa, fb = folder(f), folder(target)
        if fa != fb:
            edges_folder.setdefault(fa, set()).add(fb)
            where[(fa, fb)] = os.path.relpath(f, root) + " -> " + os.path.relpath(target, root)
        if fa in ("cpu_ref", "host/opencl", "host/backend") and os.path.relpath(target, root).startswith("host/scene/"):
            problems.append(f"backend file {os.path.relpath(f, root)} includes {m.group(1)}: backends see only the layout")


def find_cycle(edges):
    state, stack = {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(edges.get(n, ())):
            if state.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if not state.get(m):
                c = visit(m)
                if c:
                    return c
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(edges):
        if not state.get(n):
            c = visit(n)
            if c:
                return c
    return None


# Files: who uses whose symbols, from the library's object files.
objects = []
if build:
    for base, _, names in os.walk(os.path.join(build, "CMakeFiles", "rt.dir")):
        objects += [os.path.join(base, n) for n in names if n.endswith(".o")]
if build and not objects:
    problems.append(f"no object files of the library under {build}/CMakeFiles/rt.dir")
defined, used = {}, {}
for o in objects:
    src = os.path.relpath(o, os.path.join(build, "CMakeFiles", "rt.dir"))[:-2]
    out = subprocess.run(["nm", o], capture_output=True, text=True).stdout
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[0] == "U":
            used.setdefault(src, set()).add(parts[1])
        elif len(parts) == 3 and parts[1] in "TDBR":
            defined[parts[2]] = src
for src, syms in used.items():
    for sym in syms:
        owner = defined.get(sym)
        if owner and owner != src:
            edges_unit.setdefault(src, set()).add(owner)
            where[(src, owner)] = sym

for name, edges, show in (("file", edges_unit, str), ("folder", edges_folder, str)):
    c = find_cycle(edges)
    if c:
        steps = [f"{show(c[i])} -> {show(c[i + 1])} ({where.get((c[i], c[i + 1]), '?')})" for i in range(len(c) - 1)]
        problems.append(f"{name} include circle:\n    " + "\n    ".join(steps))

for p in problems:
    print("FAIL:", p)
print(f"{len(files)} files, {len(objects)} objects, {len(edges_folder)} folders with outgoing includes: "
      f"{'no circles' if not problems else str(len(problems)) + ' problem(s)'}")
sys.exit(1 if problems else 0)
