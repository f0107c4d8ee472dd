#!/usr/bin/env bash
# The project's lint (`make lint`), three parts:
#   columns  no line over 140 columns in the sources of src, tests, python and examples (C++,
#            Python, JavaScript, CMake, shell; tests/data holds third-party files and is left
#            out). The whole tree, every time: it takes well under a second.
#            `scripts/lint.sh --fix columns -- PATH...` wraps the C++ ones under PATH with
#            clang-format (review the result: a trailing ///< comment reads better above its line).
#   format   clang-format (.clang-format) on the lines a change touches: fails when it would
#            change them. `scripts/lint.sh --fix` reformats those lines in place instead.
#   tidy     clang-tidy (.clang-tidy) on the C++ files a change touches (each touched .cpp, and
#            the .cpp beside a touched header), reporting what it finds on the touched lines.
#            It reads BUILD/compile_commands.json (configure first: `make configure`).
#
# "A change" is everything between LINT_BASE and the working tree: commits since LINT_BASE,
# staged and unstaged edits, and new files git does not ignore. A moved or copied file counts
# only for what changed in it (committed: git's rename and copy detection; not yet added: it is
# compared with the deleted file of its name, or else the one it is at least half the same as).
# LINT_BASE defaults to the merge-base with origin/main when there is one (a branch's
# own work), else HEAD~1 (the last commit and what is not committed yet). CI sets it (.ci/run).
#
# Usage: scripts/lint.sh [--fix] [columns|format|tidy ...] [-- PATH...]
#        (no part named: all three; PATHs limit format and tidy to changes under them)
# Environment: LINT_BASE (a commit), BUILD (default build), LINT_JOBS (default: cores),
#              LINT_TIDY_ALL=1 (clang-tidy on every .cpp of the build, warnings on every line).
# Prints file:line: messages; exits 1 when a part fails, 2 on a usage or set-up error.
set -uo pipefail
cd "$(dirname "$0")/.."
# the whole script is one block, read before it runs: editing it meanwhile cannot derail a run
{

CLANG_FORMAT=${CLANG_FORMAT:-clang-format-14}
CLANG_TIDY=${CLANG_TIDY:-clang-tidy-14}
BUILD=${BUILD:-build}
JOBS=${LINT_JOBS:-$(nproc 2>/dev/null || echo 2)}
MAX_COLUMNS=140

fix=0
parts=()
paths=(src tests python examples bench fuzz cmake)
paths_given=0
while [ $# -gt 0 ]; do
  a=$1; shift
  case "$a" in
    --) [ $# -gt 0 ] && paths=("$@") && paths_given=1; break ;;
    --fix) fix=1 ;;
    columns|format|tidy) parts+=("$a") ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "lint: unknown argument '$a' (see scripts/lint.sh --help)" >&2; exit 2 ;;
  esac
done
[ ${#parts[@]} -eq 0 ] && parts=(columns format tidy)
want() { local p; for p in "${parts[@]}"; do [ "$p" = "$1" ] && return 0; done; return 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failed=()
now() { date +%s%N; }
took() { local ms=$(( ($(now) - $1) / 1000000 )); printf '%d.%d s' $((ms / 1000)) $((ms % 1000 / 100)); }

# ---- columns: the whole tree --------------------------------------------------------------
if want columns; then
  t0=$(now)
  echo "lint: columns: lines over $MAX_COLUMNS columns in src, tests, python, examples ..."
  git ls-files -z -co --exclude-standard -- src tests python examples ':!tests/data' \
    | CLANG_FORMAT=$CLANG_FORMAT python3 -c '
import re, sys
limit = int(sys.argv[1])
kinds = re.compile(r"\.(c|cc|cpp|cxx|h|hh|hpp|inl|ipp|py|js|mjs|sh|cmake)$|(^|/)CMakeLists\.txt$")
n = files = 0
fix, paths = sys.argv[2] == "1", [p.rstrip("/") for p in sys.argv[3:]]
cxx = re.compile(r"\.(c|cc|cpp|cxx|h|hh|hpp|inl|ipp)$")
for f in sys.stdin.buffer.read().split(b"\0"):
    f = f.decode()
    if not f or not kinds.search(f) or "node_modules/" in f:
        continue
    try:
        text = open(f, encoding="utf-8", errors="replace").read()
    except OSError:
        continue  # listed by git but deleted in the working tree
    files += 1
    long_lines = [i for i, line in enumerate(text.split("\n"), 1) if len(line) > limit]
    if fix and long_lines and cxx.search(f) and any(f == p or f.startswith(p + "/") for p in paths):
        import os, subprocess
        subprocess.run([os.environ["CLANG_FORMAT"], "-i", "--style=file"] + [f"--lines={i}:{i}" for i in long_lines] + [f], check=True)
        text = open(f, encoding="utf-8", errors="replace").read()
        long_lines = [i for i, line in enumerate(text.split("\n"), 1) if len(line) > limit]
    for i in long_lines:
        print(f"{f}:{i}: {len(text.split(chr(10))[i - 1])} columns (at most {limit})")
        n += 1
print(f"lint: columns: {n} lines over {limit} in {files} files", file=sys.stderr)
sys.exit(1 if n else 0)
' "$MAX_COLUMNS" "$((fix && paths_given))" "${paths[@]}" || failed+=(columns)
  echo "lint: columns: done in $(took "$t0")"
fi

# ---- what a change touches --------------------------------------------------------------
if want format || want tidy; then
  if [ -n "${LINT_BASE:-}" ]; then
    base_name=$LINT_BASE
  elif git rev-parse -q --verify origin/main >/dev/null; then
    base_name=$(git merge-base HEAD origin/main)
  else
    base_name=HEAD~1
  fi
  if ! base=$(git rev-parse -q --verify "$base_name^{commit}"); then
    if [ "$(git rev-parse --is-shallow-repository)" = true ] || [[ "$base_name" =~ ^HEAD~[0-9]+$ ]]; then
      # a shallow clone, or fewer commits than asked for: the oldest commit there is
      base=$(git rev-list --max-parents=0 HEAD | tail -1)
      echo "lint: $base_name is not in this clone; comparing with its oldest commit, $(git log -1 --format=%h "$base")" >&2
    else
      echo "lint: LINT_BASE=$base_name is not a commit" >&2
      exit 2
    fi
  fi
  echo "lint: a change = $(git log -1 --format='%h (%s)' "$base" | cut -c1-80) .. the working tree"

  # changed line ranges of tracked files (renames followed), then new files
  git diff -U0 -M -C --no-color --diff-filter=AMRC "$base" -- "${paths[@]}" > "$tmp/tracked.diff"
  git ls-files -o --exclude-standard -- "${paths[@]}" > "$tmp/new.txt"
  git diff --name-only --diff-filter=D "$base" > "$tmp/deleted.txt"
  python3 - "$tmp" "$base" <<'EOF'
import json, os, re, subprocess, sys
tmp, base = sys.argv[1], sys.argv[2]
cxx = re.compile(r"\.(c|cc|cpp|cxx|h|hh|hpp|inl|ipp)$")
ranges = {}  # file -> [[first, last], ...]
def add_diff(text, name=None):
    for line in text.splitlines():
        m = re.match(r"\+\+\+ (?:b/)?(.*)", line)
        if m:
            name = None if m.group(1) == "/dev/null" else m.group(1)
            continue
        m = re.match(r"@@ -\S+ \+(\d+)(?:,(\d+))? @@", line)
        if m and name and cxx.search(name):
            first, count = int(m.group(1)), int(m.group(2) or 1)
            if count:
                ranges.setdefault(name, []).append([first, first + count - 1])
add_diff(open(f"{tmp}/tracked.diff", encoding="utf-8", errors="replace").read())
deleted, was_text = {}, {}
for d in open(f"{tmp}/deleted.txt").read().split():
    deleted.setdefault(os.path.basename(d), []).append(d)
for new in open(f"{tmp}/new.txt").read().split():
    if not cxx.search(new) or not os.path.isfile(new):
        continue
    olds = deleted.get(os.path.basename(new), [])
    if len(olds) != 1:  # moved and renamed: the deleted file most like it, if it is half the same
        import difflib
        text = open(new, encoding="utf-8", errors="replace").read().splitlines()
        best = (0.5, None)
        for d in (d for ds in deleted.values() for d in ds if os.path.splitext(d)[1] == os.path.splitext(new)[1]):
            if d not in was_text:
                was_text[d] = subprocess.run(["git", "show", f"{base}:{d}"], capture_output=True, text=True,
                                             errors="replace").stdout.splitlines()
            m = difflib.SequenceMatcher(None, was_text[d], text, autojunk=False)
            if m.real_quick_ratio() > best[0] and m.quick_ratio() > best[0] and m.ratio() > best[0]:
                best = (m.ratio(), d)
        olds = [best[1]] if best[1] else []
    if len(olds) == 1:  # moved: compare with the file it was
        old = subprocess.run(["git", "show", f"{base}:{olds[0]}"], capture_output=True).stdout
        open(f"{tmp}/old", "wb").write(old)
        d = subprocess.run(["git", "diff", "--no-index", "-U0", "--no-color", f"{tmp}/old", new], capture_output=True, text=True,
                           errors="replace").stdout
        d = re.sub(r"^\+\+\+ .*$", f"+++ b/{new}", d, flags=re.M)
        add_diff(d)
    else:
        n = sum(1 for _ in open(new, "rb"))
        if n:
            ranges.setdefault(new, []).append([1, n])
json.dump(ranges, open(f"{tmp}/ranges.json", "w"))
lines = sum(b - a + 1 for rs in ranges.values() for a, b in rs)
print(f"lint: the change touches {lines} lines of C++ in {len(ranges)} files")
EOF
  [ $? -eq 0 ] || exit 2
fi

# ---- format: the touched lines ----------------------------------------------------------
if want format; then
  t0=$(now)
  command -v "$CLANG_FORMAT" >/dev/null || { echo "lint: $CLANG_FORMAT not found (scripts/install-deps.sh)" >&2; exit 2; }
  echo "lint: format: $CLANG_FORMAT on the touched lines ..."
  python3 - "$tmp/ranges.json" "$CLANG_FORMAT" "$fix" <<'EOF' || failed+=(format)
import json, re, subprocess, sys
ranges, binary, fix = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[3] == "1"
bad = 0
for f, rs in sorted(ranges.items()):
    lines = [f"--lines={a}:{b}" for a, b in rs]
    if fix:
        subprocess.run([binary, "-i", "--style=file"] + lines + [f], check=True)
        continue
    r = subprocess.run([binary, "--dry-run", "--style=file"] + lines + [f], capture_output=True, text=True)
    seen = set()
    for m in re.finditer(r"^(.+?):(\d+):\d+: (?:warning|error): code should be clang-formatted", r.stderr, re.M):
        if m.group(2) not in seen:
            seen.add(m.group(2))
            print(f"{f}:{m.group(2)}: not formatted as .clang-format says")
    if r.returncode and not seen:
        print(r.stderr, end="")
        seen.add("error")
    bad += len(seen)
if bad:
    print(f"lint: format: {bad} lines to reformat: `scripts/lint.sh --fix format` (same LINT_BASE) reformats them "
          f"in place, then see `git diff`")
sys.exit(1 if bad else 0)
EOF
  echo "lint: format: done in $(took "$t0")"
fi

# ---- tidy: the touched .cpp files ---------------------------------------------------------
if want tidy; then
  t0=$(now)
  command -v "$CLANG_TIDY" >/dev/null || { echo "lint: $CLANG_TIDY not found (scripts/install-deps.sh)" >&2; exit 2; }
  if [ ! -f "$BUILD/compile_commands.json" ]; then
    echo "lint: tidy: $BUILD/compile_commands.json is missing: configure first (make configure)" >&2
    exit 2
  fi
  # the build's commands without its precompiled header: clang cannot read GCC's .gch, and the
  # sanitizer build compiles without it too, so every file must include what it uses
  mkdir -p "$tmp/db"
  python3 - "$BUILD/compile_commands.json" "$tmp/db/compile_commands.json" "$tmp/ranges.json" "$tmp/tidy.txt" \
    "${LINT_TIDY_ALL:-0}" <<'EOF' || exit 2
import json, os, re, sys
src, dst, ranges_file, out, all_ = sys.argv[1:6]
db = json.load(open(src))
for e in db:
    key = "command" if "command" in e else None
    if key:
        e[key] = re.sub(r" -include \S*cmake_pch\.hxx| -Winvalid-pch", "", e[key])
    else:
        a, args = e["arguments"], []
        skip = False
        for i, x in enumerate(a):
            if skip:
                skip = False
                continue
            if x == "-include" and i + 1 < len(a) and a[i + 1].endswith("cmake_pch.hxx"):
                skip = True
                continue
            if x != "-Winvalid-pch":
                args.append(x)
        e["arguments"] = args
json.dump(db, open(dst, "w"))
root = os.getcwd()
in_db = {os.path.relpath(e["file"], root) for e in db if not os.path.relpath(e["file"], root).startswith("..")}
in_db = {f for f in in_db if not f.startswith(("build", "cmake/"))}
if all_ == "1":
    tus = sorted(in_db)
else:
    ranges = json.load(open(ranges_file))
    tus = set()
    for f in ranges:
        stem, ext = os.path.splitext(f)
        for cand in ([f] if ext != ".h" else [stem + ".cpp"]):
            if cand in in_db:
                tus.add(cand)
            elif ext != ".h":
                print(f"lint: tidy: {f} is not in the build's compile_commands.json (re-run cmake?); skipped", file=sys.stderr)
    tus = sorted(tus)
open(out, "w").write("".join(t + "\n" for t in tus))
EOF
  n=$(wc -l < "$tmp/tidy.txt")
  echo "lint: tidy: $CLANG_TIDY on $n files, $JOBS at a time ..."
  if [ "$n" -gt 0 ]; then
    # one clang-tidy per file; warnings on the touched lines only (all lines with LINT_TIDY_ALL=1)
    python3 - "$tmp/ranges.json" "${LINT_TIDY_ALL:-0}" > "$tmp/line-filter.json" <<'EOF'
import json, sys
if sys.argv[2] == "1":
    print("")
else:
    print(json.dumps([{"name": f, "lines": rs} for f, rs in json.load(open(sys.argv[1])).items()]))
EOF
    filter=$(cat "$tmp/line-filter.json")
    export CLANG_TIDY tmp filter
    xargs -a "$tmp/tidy.txt" -P "$JOBS" -I{} bash -c '
      f=$1
      out="$tmp/$(echo "$f" | tr / _).out"
      args=(-p "$tmp/db" --quiet)
      [ -n "$filter" ] && args+=("--line-filter=$filter")
      "$CLANG_TIDY" "${args[@]}" "$f" > "$out" 2> "$out.err"
      echo "lint: tidy:   $f ($(grep -cE "^/.*:[0-9]+:[0-9]+: (warning|error):" "$out") findings)"' _ {}
    # each finding once (a header included by two touched files is reported by both)
    cat "$tmp"/*.out 2>/dev/null | grep -E '^/.*:[0-9]+:[0-9]+: (warning|error):' | sed "s|^$PWD/||" | sort -u > "$tmp/findings.txt"
    if [ -s "$tmp/findings.txt" ]; then
      cat "$tmp/findings.txt"
      echo "lint: tidy: $(wc -l < "$tmp/findings.txt") findings"
      failed+=(tidy)
    fi
  fi
  echo "lint: tidy: done in $(took "$t0")"
fi

if [ ${#failed[@]} -gt 0 ]; then
  echo "lint: FAILED: ${failed[*]}"
  exit 1
fi
echo "lint: passed (${parts[*]})"
exit 0
}
