#!/usr/bin/env bash
# Mutation testing of the physics (issue 13). Not part of CI: it takes long (a build and the
# unit|quick suite per mutant).
#
# Each mutants/NN_name.mut is a one-line physics bug of the kind a referee would plant: a file, the
# exact line to find (it must occur exactly once) and its replacement, and WHY (what it breaks). The
# script copies the working tree to a scratch directory, builds it once, then for each mutant applies
# it, rebuilds incrementally, runs `ctest -L "unit|quick"` and restores the file. A mutant is KILLED
# when a test fails (the first failing test is named; --full runs the whole suite and lists all),
# SURVIVED when every test passes, STALE when its line is no longer in the source (update the .mut),
# INVALID when it does not compile.
#
# usage: tests/mutation/run.sh [--scratch DIR] [--jobs N] [--labels REGEX] [--exclude REGEX] [--full]
#                              [--no-baseline] [MUTANT ...]   (default: all mutants; a name or a path)
# --exclude: tests not to run (ctest -E); default 'scale_out\.restart': the restart tests kill a run
# after its first checkpoint and fail ("the run ended before it could be killed") when a loaded
# machine lets the run finish first; they test checkpointing, not physics.
# env:   NICE (default "nice -n 10") prefixes builds and tests.
set -u
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
scratch=${TMPDIR:-/tmp}/gdsmc-mutation
jobs=1
labels='unit|quick'
exclude='scale_out\.restart'
full=0
baseline=1
nice_cmd=${NICE-nice -n 10}
mutants=()
while [ $# -gt 0 ]; do
  case "$1" in
    --scratch) scratch=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --labels) labels=$2; shift 2 ;;
    --exclude) exclude=$2; shift 2 ;;
    --full) full=1; shift ;;
    --no-baseline) baseline=0; shift ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) mutants+=("$1"); shift ;;
  esac
done
if [ ${#mutants[@]} -eq 0 ]; then
  for m in "$here"/mutants/*.mut; do mutants+=("$m"); done
fi

tree=$scratch/tree
build=$scratch/build
mkdir -p "$tree" "$build"
echo "== copying $src to $tree"
# The files git knows plus untracked ones not ignored (so uncommitted work is tested too). Only files
# whose content differs are copied (with a new modification time), so a second run over the same
# scratch directory rebuilds what changed and nothing else.
(cd "$src" && git ls-files -co --exclude-standard -z | while IFS= read -r -d '' f; do
   [ -f "$f" ] || continue
   if ! cmp -s "$f" "$tree/$f"; then mkdir -p "$tree/$(dirname "$f")" && cp "$f" "$tree/$f" || exit 2; fi
 done) || exit 2
echo "== configuring and building (baseline)"
$nice_cmd cmake -S "$tree" -B "$build" -DCMAKE_BUILD_TYPE=Release > "$scratch/configure.log" 2>&1 || {
  tail -30 "$scratch/configure.log"; exit 2; }
$nice_cmd cmake --build "$build" -j "$jobs" > "$scratch/build.log" 2>&1 || { tail -30 "$scratch/build.log"; exit 2; }

run_tests() {  # $1 = log file; prints the failing tests
  local stop=--stop-on-failure
  [ "$full" = 1 ] && stop=
  (cd "$build" && $nice_cmd ctest -L "$labels" ${exclude:+-E "$exclude"} -j "$jobs" --timeout 900 $stop > "$1" 2>&1)
  local rc=$?
  # ctest's closing list "N - name (STATUS)": any status but Skipped and Disabled (Failed, Timeout,
  # SEGFAULT, NUMERICAL, ILLEGAL, Subprocess aborted, ...): a crash kills a mutant as surely as a failure
  # (until 2026-11-27 only some statuses counted: mutant 32, a division by zero, was reported SURVIVED).
  local names
  names=$(grep -E '^\s*[0-9]+ - [^ ]+ \(' "$1" | grep -vE '\((Skipped|Disabled)\)' |
    sed -E 's/^\s*[0-9]+ - ([^ ]+).*/\1/' | tr '\n' ' ')
  [ -z "$names" ] && [ $rc -ne 0 ] && names="(ctest exit status $rc)"
  printf '%s' "$names"
  return $rc
}

if [ "$baseline" = 1 ]; then
  echo "== baseline: ctest -L \"$labels\" on the unmutated tree"
  failing=$(run_tests "$scratch/baseline.log")
  if [ -n "$failing" ]; then
    echo "baseline fails ($failing): fix that first (log: $scratch/baseline.log)"; exit 2
  fi
fi

apply() {  # $1 = .mut file, $2 = tree; exit 0 applied, 3 stale
  python3 - "$1" "$2" <<'PY'
import sys, pathlib
text = pathlib.Path(sys.argv[1]).read_text().split('\n')
f = text[0].split(' ', 1)[1]
i, j, k = text.index('FIND'), text.index('REPLACE'), text.index('END')
find, repl = '\n'.join(text[i + 1:j]), '\n'.join(text[j + 1:k])
p = pathlib.Path(sys.argv[2]) / f
s = p.read_text()
if s.count(find) != 1:
    sys.exit(3)
p.write_text(s.replace(find, repl))
PY
}

declare -a rows
killed=0 survived=0 other=0
for m in "${mutants[@]}"; do
  [ -f "$m" ] || m=$here/mutants/${m%.mut}.mut
  name=$(basename "$m" .mut)
  file=$(sed -n 's/^FILE //p' "$m")
  why=$(sed -n 's/^WHY //p' "$m")
  echo "== $name: $why"
  cp "$tree/$file" "$scratch/pristine"
  apply "$m" "$tree"
  rc=$?
  if [ $rc -ne 0 ]; then
    rows+=("$(printf '%-28s %-9s %s' "$name" STALE "line not found once in $file")")
    other=$((other + 1))
    continue
  fi
  if ! $nice_cmd cmake --build "$build" -j "$jobs" > "$scratch/$name.build.log" 2>&1; then
    rows+=("$(printf '%-28s %-9s %s' "$name" INVALID "does not compile")")
    other=$((other + 1))
  else
    failing=$(run_tests "$scratch/$name.ctest.log")
    if [ -n "$failing" ]; then
      rows+=("$(printf '%-28s %-9s %s' "$name" KILLED "$failing")")
      killed=$((killed + 1))
    else
      rows+=("$(printf '%-28s %-9s %s' "$name" SURVIVED "-")")
      survived=$((survived + 1))
    fi
  fi
  cp "$scratch/pristine" "$tree/$file"
  touch "$tree/$file"
done
# Leave the scratch build matching the unmutated tree.
$nice_cmd cmake --build "$build" -j "$jobs" > "$scratch/restore.log" 2>&1

echo
echo "== kill matrix (labels \"$labels\"$([ "$full" = 1 ] && echo ', full suite' || echo ', first failing test'))"
printf '%-28s %-9s %s\n' mutant status "killed by"
for r in "${rows[@]}"; do echo "$r"; done
echo "== $killed killed, $survived survived, $other stale/invalid, of ${#mutants[@]}"
[ "$survived" -eq 0 ] && [ "$other" -eq 0 ]
