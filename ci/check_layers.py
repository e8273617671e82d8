#!/usr/bin/env python3
"""The layer rules of docs/ARCHITECTURE.md, checked on the source tree (run by ctest as ci.layers).

1. The module table in docs/ARCHITECTURE.md lists, per target, exactly the project targets its
   target_link_libraries names.
2. No include runs upward: a module's files include only headers of its own module and of the
   modules it depends on, directly or not.
3. A PUBLIC link to a project target is one that a header of the module includes; the rest are
   PRIVATE.
4. Vulkan headers and calls appear only in vk/; GLFW only in the viewer; MPI only in comm/mpi/ and
   in situ (the in-situ library, its example, the Python module's binding of it).
5. Nothing includes an executable's own files.
6. No top-level module (a folder under src/, or vk, comm, compositor, shaders, python, tools) holds
   more than 15% of the source lines.
7. The renderer takes boxes, not meshes: src/render includes no header of src/mesh but
   mesh/bounds.h (defaults that read the mesh live in scene/view_defaults.h).

Usage: check_layers.py [SOURCE_ROOT]. Prints one line per violation and exits 1 when there is any;
tests are not checked.
"""
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                       os.path.join(os.path.dirname(__file__), ".."))
SOURCE_DIRS = ["vk", "comm", "compositor", "src", "python/src"]
SOURCE_EXT = (".h", ".hpp", ".cpp")

# Include prefix -> folder, longest first (a subfolder that is its own module comes before its
# parent).
EXECUTABLE_FOLDERS = ["compositor/bench"]
# Executables' own files in a library's folder, and the executable they belong to.
EXECUTABLE_FILES = {"src/cli/main.cpp": "shellmarch", "src/cli/cmd_view.cpp": "shellmarch",
                    "src/bench/main.cpp": "shellmarch-bench"}
VULKAN_FOLDERS = ["vk"]
GLFW_FOLDERS = ["src/viewer"]
MPI_FOLDERS = ["comm/mpi", "src/insitu", "python/src/mpi_comm", "python/src/mesh_renderer"]


def read(path):
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        return f.read()


def module_table():
    """target -> (folder, set of short dependency names) from docs/ARCHITECTURE.md."""
    table = {}
    for line in read("docs/ARCHITECTURE.md").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 4 or not cells[0].startswith("`shellmarch"):
            continue
        targets = re.findall(r"`([\w-]+)`", cells[0])
        folder = re.findall(r"`([^`]+)`", cells[1])
        deps = set(re.findall(r"[\w-]+", cells[3])) - {"-"}
        for t in targets:
            table[t] = (folder[0] if folder else "", deps)
    return table


def short(target):
    return target[len("shellmarch_"):] if target.startswith("shellmarch_") else target


def cmake_links():
    """target -> {dependency target: 'PUBLIC'|'PRIVATE'|'INTERFACE'} for project targets."""
    links = {}
    for folder in ["vk", "comm", "compositor", "src", "python"]:
        for dirpath, _, files in os.walk(os.path.join(ROOT, folder)):
            if "CMakeLists.txt" not in files:
                continue
            text = read(os.path.relpath(os.path.join(dirpath, "CMakeLists.txt"), ROOT))
            text = re.sub(r"#[^\n]*", "", text)
            for m in re.finditer(r"target_link_libraries\(\s*([\w-]+)([^)]*)\)", text):
                scope = "PUBLIC"
                deps = links.setdefault(m.group(1), {})
                for word in m.group(2).split():
                    if word in ("PUBLIC", "PRIVATE", "INTERFACE"):
                        scope = word
                    elif word.startswith("shellmarch") and word != m.group(1):
                        deps[word] = scope
    return links


def sources():
    for top in SOURCE_DIRS:
        for dirpath, _, files in os.walk(os.path.join(ROOT, top)):
            for name in files:
                if name.endswith(SOURCE_EXT):
                    yield os.path.relpath(os.path.join(dirpath, name), ROOT)


def within(path, folders):
    return any(path == f or path.startswith(f.rstrip("/") + "/") or path.startswith(f + ".")
               for f in folders)


def main():
    errors = []
    table = module_table()
    links = cmake_links()
    if not table:
        errors.append("docs/ARCHITECTURE.md: no module table found")

    # 1. The table against the build.
    for target, (folder, deps) in sorted(table.items()):
        if target not in links and deps:
            errors.append(f"docs/ARCHITECTURE.md: {target} has no target_link_libraries")
            continue
        actual = {short(d) for d in links.get(target, {})}
        if actual != deps:
            errors.append(f"docs/ARCHITECTURE.md: {target} depends on {sorted(deps)} in the table "
                          f"but on {sorted(actual)} in CMake")
    for target in sorted(links):
        if target not in table and target.startswith("shellmarch") and not target.startswith(
                ("shellmarch_test", "shellmarch_python", "shellmarch_spv",
                 "shellmarch_heat_insitu")):
            errors.append(f"docs/ARCHITECTURE.md: target {target} is missing from the table")

    # Folders -> targets (the longest folder holding a file owns it).
    folders = sorted(((f, t) for t, (f, _) in table.items() if f), key=lambda p: -len(p[0]))

    def owner(path):
        if path in EXECUTABLE_FILES:
            return EXECUTABLE_FILES[path]
        for f, t in folders:
            if path.startswith(f.rstrip("/") + "/"):
                return t
        return None

    closure = {}

    def reach(t):
        if t not in closure:
            closure[t] = {t}
            for d in links.get(t, {}):
                closure[t] |= reach(d)
        return closure[t]

    def header_owner(include):
        for f, t in folders:
            base = re.sub(r"^(src|shaders)/", "", f)
            if include.startswith(base.rstrip("/") + "/"):
                return t
        return None

    public_use = {}
    include_re = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
    for path in sources():
        text = read(path)
        me = owner(path)
        for quote, inc in include_re.findall(text):
            if quote == "<":
                if inc.startswith("vulkan/") and not within(path, VULKAN_FOLDERS):
                    errors.append(f"{path}: includes <{inc}>: Vulkan belongs in vk/")
                if inc.startswith("GLFW/") and not within(path, GLFW_FOLDERS):
                    errors.append(f"{path}: includes <{inc}>: GLFW belongs in the viewer")
                if inc == "mpi.h" and not within(path, MPI_FOLDERS):
                    errors.append(f"{path}: includes <mpi.h>: MPI belongs in comm/mpi/ or in situ")
                continue
            if inc.endswith(".cpp"):
                errors.append(f"{path}: includes {inc}, an executable's source")
            if within(path, ["src/render"]) and inc.startswith("mesh/") and inc != "mesh/bounds.h":
                errors.append(f"{path}: includes {inc}: the renderer takes boxes, not meshes")
            for ex in EXECUTABLE_FOLDERS:
                if inc.startswith(ex + "/") and not path.startswith(ex + "/"):
                    errors.append(f"{path}: includes {inc}, a header of an executable")
            them = header_owner(inc)
            if me and them and them not in reach(me):
                errors.append(f"{path}: includes {inc} of {them}, which {me} does not depend on "
                              f"(an include running upward or sideways)")
            if me and them and them != me and path.endswith((".h", ".hpp")):
                public_use.setdefault(me, set()).add(them)
        if not within(path, VULKAN_FOLDERS):
            for m in re.finditer(r"\bvk[A-Z]\w*\s*\(", re.sub(r"//[^\n]*", "", text)):
                errors.append(f"{path}: calls {m.group(0)[:-1].strip()}: Vulkan calls belong in vk/")
        if not within(path, MPI_FOLDERS):
            for m in re.finditer(r"\bMPI_[A-Z][a-z_]+\s*\(", re.sub(r"//[^\n]*", "", text)):
                errors.append(f"{path}: calls {m.group(0)[:-1].strip()}: MPI belongs in comm/mpi/")

    # 3. PUBLIC links are the ones headers need.
    for target, deps in sorted(links.items()):
        if target not in table:
            continue
        for dep, scope in sorted(deps.items()):
            if scope != "PUBLIC" or dep not in table:
                continue
            # A header's include that this dependency alone brings (common also gives every module
            # under src/ its include directory).
            others = [d for d, s in deps.items() if s == "PUBLIC" and d != dep]
            needed = dep == "shellmarch_common" or any(
                u == dep or (u in reach(dep) and not any(u in reach(d) for d in others))
                for u in public_use.get(target, set()))
            if not needed:
                errors.append(f"{table[target][0]}/CMakeLists.txt: {target} links {dep} PUBLIC but "
                              "none of its headers includes it (make it PRIVATE)")

    # 6. No module dominates.
    lines = {}
    for top in ["vk", "comm", "compositor", "src", "shaders", "python", "tools"]:
        for dirpath, _, files in os.walk(os.path.join(ROOT, top)):
            rel = os.path.relpath(dirpath, ROOT).split(os.sep)
            module = "/".join(rel[:2]) if rel[0] == "src" and len(rel) > 1 else rel[0]
            for name in files:
                if name.endswith(SOURCE_EXT + (".glsl", ".comp", ".rgen", ".rint", ".rahit",
                                               ".rchit", ".rmiss", ".py")):
                    with open(os.path.join(dirpath, name), encoding="utf-8", errors="replace") as f:
                        lines[module] = lines.get(module, 0) + sum(1 for _ in f)
    total = sum(lines.values()) or 1
    largest = max(lines, key=lines.get) if lines else ""
    for module, n in sorted(lines.items()):
        if n > 0.15 * total:
            errors.append(f"{module}: {n} of {total} source lines ({100 * n / total:.1f}%), more "
                          "than 15%: split it by what its parts hold")

    for e in errors:
        print(e)
    if errors:
        print(f"check_layers: {len(errors)} violation(s)")
        return 1
    print(f"check_layers: {len(table)} modules, {sum(1 for _ in sources())} files: rules hold; "
          f"largest module {largest}, {100 * lines.get(largest, 0) / total:.1f}% of {total} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
