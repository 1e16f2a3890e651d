#!/usr/bin/env bash
# Runs every tutorial of docs/tutorials/ as a reader would: the fenced ```sh and ```python blocks
# of each page, in order, in a fresh directory of its own.
#
# Usage: tutorials.sh SCATTERLAB_EXE PYTHON_MODULE_DIR SOURCE_DIR [MPIEXEC]
#
#   SCATTERLAB_EXE     the program (build/sim/scatterlab); its directory goes first on PATH, so
#                      that `scatterlab` in a tutorial is this program
#   PYTHON_MODULE_DIR  the folder holding the Python module (build/python), put on PYTHONPATH
#   SOURCE_DIR         the source tree: its data/ is linked into each tutorial's directory as
#                      ./data, so that a tutorial names data/scenes/... as a reader in the
#                      source checkout does
#   MPIEXEC            optional: the MPI launcher. Each block that says `mpirun` runs with it in
#                      place of `mpirun`; without it those blocks are skipped, and so is a block
#                      preceded by the line <!-- tutorials.sh: needs mpirun --> (one that reads
#                      what an mpirun block wrote)
#
# Environment: PYTHON (default /usr/bin/python3) runs the python blocks and the extraction;
# TUTORIALS="name ..." runs only those pages (names without .md); BLOCK_TIMEOUT (seconds, default
# 300) bounds each block; KEEP=1 keeps every tutorial's directory (to look at its figures).
#
# sh blocks run with `bash -euo pipefail`, python blocks with $PYTHON, each in the tutorial's
# directory; a tutorial fails at its first failing block, which is printed with its output (the
# pages' links are docs.site's to check). One PASS/FAIL line per tutorial; the exit status is 1
# when any failed, 2 on bad usage.

set -uo pipefail

if [[ $# -lt 3 || $# -gt 4 ]]; then
  echo "usage: $0 SCATTERLAB_EXE PYTHON_MODULE_DIR SOURCE_DIR [MPIEXEC]" >&2
  exit 2
fi

exe=$(realpath -e "$1") || { echo "tutorials.sh: SCATTERLAB_EXE: no such file: $1" >&2; exit 2; }
pymod=$(realpath -e "$2") || { echo "tutorials.sh: PYTHON_MODULE_DIR: no such folder: $2" >&2; exit 2; }
src=$(realpath -e "$3") || { echo "tutorials.sh: SOURCE_DIR: no such folder: $3" >&2; exit 2; }
mpiexec=${4:-}
if [[ -n "$mpiexec" ]]; then
  mpiexec=$(command -v "$mpiexec") || { echo "tutorials.sh: MPIEXEC: not found: $4" >&2; exit 2; }
fi
python=${PYTHON:-/usr/bin/python3}
block_timeout=${BLOCK_TIMEOUT:-300}
[[ -x "$exe" ]] || { echo "tutorials.sh: SCATTERLAB_EXE is not executable: $exe" >&2; exit 2; }
[[ -d "$src/docs/tutorials" ]] || { echo "tutorials.sh: no docs/tutorials in $src" >&2; exit 2; }
[[ -d "$src/data" ]] || { echo "tutorials.sh: no data/ in $src" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/scatterlab-tutorials.XXXXXX")
# `scatterlab` must be the given program whatever its file is called: a link of that name
# goes first on PATH, then the program's own directory (where scatterlab-fit lives).
mkdir -p "$work/bin"
ln -s "$exe" "$work/bin/scatterlab"
export PATH="$work/bin:$(dirname "$exe"):$PATH"
export PYTHONPATH="$pymod${PYTHONPATH:+:$PYTHONPATH}"
export MPLBACKEND=Agg
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1

# Splits a page into its blocks: BLOCKDIR/NNN.sh or NNN.py, and BLOCKDIR/index with one line per
# block: "NNN LANG LINE RUN|SKIP".
extract() {
  "$python" - "$1" "$2" "$mpiexec" <<'PY'
import os, re, shlex, sys

page, out, mpiexec = sys.argv[1], sys.argv[2], sys.argv[3]
lines = open(page, encoding="utf-8").read().split("\n")
index = []
marker = "<!-- tutorials.sh: needs mpirun -->"
fence = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([^\s`]*)\s*$")
i, n, previous = 0, 0, ""
while i < len(lines):
    m = fence.match(lines[i])
    if not m:
        if lines[i].strip():
            previous = lines[i].strip()
        i += 1
        continue
    indent, ticks, lang = m.group(1), m.group(2), m.group(3)
    start = i + 1
    body = []
    i += 1
    while i < len(lines) and not re.match(r"^\s*" + re.escape(ticks[0]) + "{" + str(len(ticks)) +
                                          r",}\s*$", lines[i]):
        line = lines[i]
        body.append(line[len(indent):] if line.startswith(indent) else line.lstrip())
        i += 1
    i += 1
    if lang not in ("sh", "python"):
        previous = ""
        continue
    n += 1
    text = "\n".join(body) + "\n"
    needs_mpi = previous == marker or re.search(r"\bmpirun\b", text) is not None
    if needs_mpi and mpiexec:
        text = re.sub(r"\bmpirun\b", shlex.quote(mpiexec), text)
    name = f"{n:03d}"
    with open(os.path.join(out, name + (".sh" if lang == "sh" else ".py")), "w") as f:
        f.write(text)
    index.append(f"{name} {lang} {start} {'SKIP' if needs_mpi and not mpiexec else 'RUN'}")
    previous = ""
with open(os.path.join(out, "index"), "w") as f:
    f.write("\n".join(index) + ("\n" if index else ""))
PY
}

passed=0
failed=0
failures=()
start_all=$SECONDS
shopt -s nullglob
pages=("$src"/docs/tutorials/*.md)
if [[ ${#pages[@]} -eq 0 ]]; then
  echo "tutorials.sh: no pages in $src/docs/tutorials" >&2
  exit 2
fi

for page in "${pages[@]}"; do
  name=$(basename "$page" .md)
  if [[ -n "${TUTORIALS:-}" && " $TUTORIALS " != *" $name "* ]]; then
    continue
  fi
  dir="$work/$name"
  blocks="$work/$name.blocks"
  mkdir -p "$dir" "$blocks"
  ln -s "$src/data" "$dir/data"
  start=$SECONDS
  ok=1
  if ! extract "$page" "$blocks" 2>"$blocks/extract.log"; then
    echo "FAIL $name: the page could not be read"
    sed 's/^/    /' "$blocks/extract.log"
    failed=$((failed + 1)); failures+=("$name")
    continue
  fi
  ran=0
  skipped=0
  while read -r id lang line mode; do
    if [[ "$mode" == SKIP ]]; then
      skipped=$((skipped + 1))
      continue
    fi
    if [[ "$lang" == sh ]]; then
      cmd=(bash -euo pipefail "$blocks/$id.sh")
    else
      cmd=("$python" "$blocks/$id.py")
    fi
    status=0
    (cd "$dir" && timeout "$block_timeout" "${cmd[@]}") >"$blocks/$id.log" 2>&1 </dev/null || status=$?
    if [[ $status -ne 0 ]]; then
      ok=0
      why="exited with status $status"
      [[ $status -eq 124 ]] && why="timed out after $block_timeout s"
      echo "FAIL $name: block $((10#$id)) (\`\`\`$lang at line $line of $name.md) $why"
      echo "  --- block ---"
      sed 's/^/    /' "$blocks/$id.${lang/python/py}"
      echo "  --- output (last 60 lines) ---"
      tail -n 60 "$blocks/$id.log" | sed 's/^/    /'
      echo "  (the tutorial's directory is kept: $dir)"
      break
    fi
    ran=$((ran + 1))
  done <"$blocks/index"
  if [[ $ok -eq 1 && $ran -eq 0 ]]; then
    ok=0
    echo "FAIL $name: no sh or python block ran"
  fi
  if [[ $ok -eq 1 ]]; then
    note=""
    [[ $skipped -gt 0 ]] && note=", $skipped skipped (no MPIEXEC)"
    echo "PASS $name ($ran blocks$note, $((SECONDS - start)) s)"
    passed=$((passed + 1))
    [[ "${KEEP:-0}" == 1 ]] || rm -rf "$dir" "$blocks"
  else
    failed=$((failed + 1)); failures+=("$name")
  fi
done

echo "tutorials: $passed passed, $failed failed, $((SECONDS - start_all)) s in all"
if [[ $failed -gt 0 ]]; then
  echo "failed: ${failures[*]} (directories under $work)"
  exit 1
fi
if [[ "${KEEP:-0}" == 1 ]]; then
  echo "kept: $work"
else
  rm -rf "$work"
fi
exit 0
