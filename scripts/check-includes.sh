#!/usr/bin/env bash
# Checks that every #include under src/ (and python/) points the way docs/architecture.md §3
# allows: a module includes only the modules in its "may use" column (and what those use), and
# a third-party header (Bullet, Embree, GL, roscpp, Cyclone, yaml-cpp, ...) appears only in the
# folders whose row names that library. The table is read as data, so a new module needs only
# a new row.
#
#   scripts/check-includes.sh [--table FILE] [ROOT]
#
# ROOT is the tree to check (default: this repository); the table defaults to
# ROOT/docs/architecture.md, else this repository's. Exit 0: clean; 1: violations, one line
# each as `file:line: includes "<mod>/..." but <module> may only use ...`; 2: bad arguments or
# an unreadable table. An include line carrying `// check-includes: allow <reason>` is exempt.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exec python3 - "$here" "$@" <<'PYTHON'
import os, re, sys

# third-party libraries the check knows: name as written in the table -> header prefixes
LIBRARIES = {
    "bullet": [r"btBullet\w*\.h$", r"BulletCollision/", r"BulletDynamics/", r"BulletSoftBody/",
               r"LinearMath/", r"HACD/", r"Bullet3\w*/"],
    "linearmath": [r"LinearMath/"],
    "hacd": [r"HACD/"],
    "embree": [r"embree[34]/"],
    "tbb": [r"tbb/", r"oneapi/tbb"],
    "epoxy": [r"epoxy/"],
    "egl": [r"EGL/"],
    "glfw": [r"GLFW/"],
    "imgui": [r"imgui\.h$", r"imgui/", r"backends/imgui_"],
    "roscpp": [r"ros/", r"xmlrpcpp/", r"rosbag/", r"roscpp/"],
    "cyclone": [r"dds/"],
    "yaml-cpp": [r"yaml-cpp/"],
    "tinyxml2": [r"tinyxml2\.h$"],
    "urdfdom": [r"urdf_model/", r"urdf_parser/", r"urdf_world/", r"urdf_sensor/", r"console_bridge/"],
    "assimp": [r"assimp/"],
    "sdformat": [r"sdf/"],
    "pybind11": [r"pybind11/"],
    "libpng": [r"png\.h$", r"libpng\d*/"],
}
HEADER_EXT = (".h", ".hpp", ".hh", ".hxx", ".inl")
SOURCE_EXT = HEADER_EXT + (".cpp", ".cc", ".cxx", ".c")


def die(msg):
    print(f"check-includes: {msg}", file=sys.stderr)
    sys.exit(2)


def parse_args(argv):
    repo, table, root = argv[0], None, None
    args = argv[1:]
    while args:
        a = args.pop(0)
        if a == "--table":
            if not args:
                die("--table needs a file")
            table = args.pop(0)
        elif a in ("-h", "--help"):
            print("usage: scripts/check-includes.sh [--table FILE] [ROOT]")
            sys.exit(0)
        elif a.startswith("-"):
            die(f"unknown option '{a}' (usage: scripts/check-includes.sh [--table FILE] [ROOT])")
        elif root is None:
            root = a
        else:
            die(f"unexpected argument '{a}'")
    root = os.path.abspath(root or repo)
    if not os.path.isdir(root):
        die(f"{root}: not a directory")
    if table is None:
        table = os.path.join(root, "docs/architecture.md")
        if not os.path.exists(table):
            table = os.path.join(repo, "docs/architecture.md")
    return root, table


class Row:
    def __init__(self, name, folder, line):
        self.name, self.folder, self.line = name, folder, line
        self.uses = set()       # module names written in the cell
        self.everything_above = False
        self.all_modules = False
        self.libs = []          # (library, scope folder or None, cpp_only)


def read_table(path):
    """The module rows of §3: `| `src/x` | responsibility | may use |`."""
    try:
        lines = open(path, encoding="utf-8").read().splitlines()
    except OSError as e:
        die(f"{path}: {e.strerror}")
    rows, in_section = [], False
    for n, line in enumerate(lines, 1):
        if line.startswith("## "):
            in_section = line.startswith("## 3.")
            continue
        m = re.match(r"\|\s*`([^`]+)`\s*\|.*\|\s*([^|]*?)\s*\|\s*$", line)
        if not in_section or not m:
            continue
        folder, cell = m.group(1).rstrip("/"), m.group(2)
        # `src/bridges/{ros1,ros2}`: one module per name
        b = re.match(r"(.*)\{([^}]*)\}(.*)", folder)
        folders = [b.group(1) + x.strip() + b.group(3) for x in b.group(2).split(",")] if b else [folder]
        for f in folders:
            name = f[4:] if f.startswith("src/") else f
            row = Row(name, f, n)
            parse_cell(row, cell, path)
            rows.append(row)
    if not rows:
        die(f"{path}: no module rows (| `src/x` | ... | may use |) found in section 3")
    names = {r.name for r in rows}
    for r in rows:
        for u in r.uses:
            if u not in names:
                die(f"{path}:{r.line}: `{r.folder}` may use `{u}`, which is not a module row")
    return rows


def parse_cell(row, cell, path):
    cell = re.sub(r"\([^)]*\)", "", cell)  # parenthesised notes are prose
    for clause in cell.split(";"):
        scope = re.search(r"only in `([^`]+)`", clause)
        scope = scope.group(1).rstrip("/") if scope else None
        cpp_only = ".cpp only" in clause
        text = re.sub(r"only in `[^`]+`", "", clause)
        if "everything above" in text:
            row.everything_above = True
        if "all modules" in text:
            row.all_modules = True
        for tok in re.findall(r"`([^`]+)`", text):
            row.uses.add(tok)
        for word in re.findall(r"[A-Za-z][\w+-]*", re.sub(r"`[^`]+`", "", text)):
            if word.lower() in LIBRARIES:
                row.libs.append((word.lower(), scope, cpp_only))


def closure(rows):
    """What each module may include: itself, its may-use list and, transitively, theirs."""
    by_name = {r.name: r for r in rows}
    src_rows = [r for r in rows if r.folder.startswith("src/")]
    direct = {}
    for i, r in enumerate(rows):
        d = set(r.uses)
        if r.everything_above:
            d |= {x.name for x in rows[:i]}
        if r.all_modules:
            d |= {x.name for x in src_rows if x is not r}
        direct[r.name] = d
    allowed = {}
    for r in rows:
        seen, todo = {r.name}, list(direct[r.name])
        while todo:
            u = todo.pop()
            if u not in seen:
                seen.add(u)
                todo.extend(direct.get(u, ()))
        allowed[r.name] = seen
    return allowed, by_name, direct


def module_of(rel, rows):
    """The row owning a path (longest folder prefix), or None."""
    best = None
    for r in rows:
        if rel == r.folder or rel.startswith(r.folder + "/"):
            if best is None or len(r.folder) > len(best.folder):
                best = r
    return best


def main():
    root, table = parse_args(sys.argv[1:])
    rows = read_table(table)
    allowed, by_name, direct = closure(rows)
    include_re = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">](.*)$')
    problems, unrowed = [], set()
    tops = sorted({r.folder.split("/")[0] for r in rows})
    for top in tops:
        base = os.path.join(root, top)
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames.sort()
            for fn in sorted(filenames):
                if not fn.endswith(SOURCE_EXT):
                    continue
                full = os.path.join(dirpath, fn)
                rel = os.path.relpath(full, root)
                row = module_of(rel, rows)
                if row is None:
                    folder = os.path.dirname(rel)
                    if rel.startswith("src/") and folder not in unrowed:
                        unrowed.add(folder)
                        problems.append(f"{rel}:1: {folder}/ is in no module row of docs/architecture.md §3 (add a row)")
                    continue
                check_file(root, full, rel, row, rows, allowed, direct, include_re, problems)
    for p in problems:
        print(p)
    if problems:
        print(f"check-includes: {len(problems)} include(s) against docs/architecture.md §3", file=sys.stderr)
        return 1
    return 0


def may_only(row, direct):
    mods = sorted(direct[row.name]) if direct[row.name] else []
    libs = sorted({l for l, _, _ in row.libs})
    parts = []
    if row.everything_above:
        parts.append("the modules above it")
    elif row.all_modules:
        parts.append("all modules")
    elif mods:
        parts.append(", ".join(mods))
    if libs:
        parts.append("third-party " + ", ".join(libs))
    return "; ".join(parts) if parts else "itself"


def check_file(root, full, rel, row, rows, allowed, direct, include_re, problems):
    is_header = rel.endswith(HEADER_EXT)
    src = os.path.join(root, "src")
    with open(full, encoding="utf-8", errors="replace") as f:
        for n, line in enumerate(f, 1):
            m = include_re.match(line)
            if not m:
                continue
            bracket, inc, rest = m.groups()
            if "check-includes: allow" in rest:
                if not re.search(r"check-includes: allow\s+\S", rest):
                    problems.append(f"{rel}:{n}: 'check-includes: allow' needs a reason")
                continue
            # ours: a path under src/ (or next to the file, for quoted includes)
            target = None
            if bracket == '"' and os.path.exists(os.path.join(os.path.dirname(full), inc)):
                target = os.path.relpath(os.path.normpath(os.path.join(os.path.dirname(full), inc)), root)
            elif os.path.exists(os.path.join(src, inc)):
                target = "src/" + inc
            elif bracket == '"' and "/" in inc and inc.split("/")[0] in {r.folder.split("/")[1] for r in rows if r.folder.startswith("src/")}:
                target = "src/" + inc  # a header of ours that does not exist (yet): still check direction
            if target is not None:
                to = module_of(target, rows)
                if to is None:
                    continue  # a folder without a row is reported once, on its own files
                if to.name not in allowed[row.name]:
                    problems.append(f"{rel}:{n}: includes \"{inc}\" but {row.name} may only use {may_only(row, direct)}")
                continue
            # third-party: allowed when this row names the library (in its scope, .cpp if asked)
            libs = [l for l, pats in LIBRARIES.items() if any(re.match(p, inc) for p in pats)]
            if not libs:
                continue  # std, Eigen, fmt, ... are not checked
            ok = False
            for lib, scope, cpp_only in row.libs:
                if lib not in libs:
                    continue
                if scope and not (rel == scope or rel.startswith(scope + "/") or rel.startswith("src/" + scope + "/")):
                    continue
                if cpp_only and is_header:
                    continue
                ok = True
            if not ok:
                problems.append(f"{rel}:{n}: includes <{inc}> ({'/'.join(libs)}) but {row.name} may only use {may_only(row, direct)}"
                                + scope_note(row, libs))


def scope_note(row, libs):
    notes = []
    for lib, scope, cpp_only in row.libs:
        if lib in libs:
            where = f"only in {scope}" if scope else ""
            if cpp_only:
                where = (where + " " if where else "") + ".cpp files only"
            if where:
                notes.append(f"{lib} {where}")
    if notes:
        return f" ({'; '.join(notes)})"
    return f", and {'/'.join(libs)} is not named in its row"


sys.exit(main())
PYTHON
