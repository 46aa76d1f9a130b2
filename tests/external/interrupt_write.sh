#!/usr/bin/env bash
# Slow check of the output safety (README, "The command": interrupts end the run): a SIGTERM or
# SIGINT while `polydual convert` writes a large VTU or an OpenFOAM case leaves
# no output (or the previous one, byte for byte) and no temporary, and the
# command exits with 128 + signal saying "interrupted"; a full disk gives the
# system's reason and no temporary.
# Timing-robust: the main attempts wait until the writer's temporary exists
# and signal then; a sweep of fixed delays accepts "finished before the
# signal" (exit 0) only when the output is complete (`polydual check` reads it
# back). At least one attempt must have hit a write in progress.
# usage: interrupt_write.sh POLYDUAL_BINARY SCRATCH_DIR   (POLYDUAL_INTERRUPT_TETS, default 150000)
set -uo pipefail
set -m  # job control: background jobs get SIGINT (not ignored as in plain scripts)
bin=$1
out=$2
tets=${POLYDUAL_INTERRUPT_TETS:-150000}
mkdir -p "$out"
msh="$out/twomat_$tets.msh"
work="$out/work"
status=0
hits=0
fail() { echo "interrupt_write: FAIL: $*"; status=1; }

# Our temporaries and aside copies anywhere under $work.
leftovers() { find "$work" \( -name '*.tmp.*' -o -name '*.old.*' \) -print; }
# Listing and checksums of a tree, to compare before/after.
tree_sum() { (cd "$1" && find . -print0 | sort -z | xargs -0 -I{} sh -c 'if [ -f "{}" ]; then md5sum "{}"; else echo "{}"; fi'); }
# The VTU is complete when polydual reads every cell of it back (and finds it
# sound: `check` exits 1 on a mesh with defects).
vtu_complete() { "$bin" check "$1" --json > /dev/null 2>&1; }
# Every polyMesh file ends with OpenFOAM's footer line.
case_complete() {
  local f
  for f in points faces owner neighbour boundary cellZones faceZones; do
    tail -n 1 "$1/constant/polyMesh/$f" 2>/dev/null | grep -q '^// \*\*\*' || return 1
  done
}

# run_and_signal SIG PATTERN|DELAY TARGET...: starts the conversion (the
# remaining arguments), then signals when a file matching the glob PATTERN
# exists (or after DELAY seconds when PATTERN is a number). Sets $rc, $hit
# (1 when the temporary was seen before signalling) and $err (stderr).
run_and_signal() {
  local sig=$1 when=$2
  shift 2
  "$bin" convert "$msh" --optimize none "$@" > /dev/null 2> "$out/stderr" &
  local pid=$!
  hit=0
  if [[ $when =~ ^[0-9.]+$ ]]; then
    sleep "$when"
    compgen -G "$work/*.tmp.*" > /dev/null || compgen -G "$work/*/constant/*.tmp.*" > /dev/null && hit=1
  else
    while kill -0 "$pid" 2> /dev/null; do
      if compgen -G "$when" > /dev/null; then hit=1; break; fi
      sleep 0.005
    done
  fi
  kill -s "$sig" "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  rc=$?
  err=$(cat "$out/stderr")
}

# judge NAME SIG KIND TARGET BEFORE: the outcome of one attempt. BEFORE is the
# tree_sum of an existing target ("" when there was none).
judge() {
  local name=$1 sig=$2 kind=$3 target=$4 before=$5 code
  code=$((128 + $(kill -l "$sig")))
  local left
  left=$(leftovers)
  [[ -z $left ]] || fail "$name: temporaries left: $left"
  if [[ $rc -eq $code ]]; then
    # Empty stderr: the signal came before main installed the handlers (the
    # dynamic loader takes ~1 s here), the default action ended the process
    # before anything was written; the checks below still apply.
    [[ $err == *interrupted* || ( -z $err && $hit -eq 0 ) ]] || fail "$name: exit $rc without 'interrupted' ($err)"
    if [[ -z $before ]]; then
      [[ ! -e $target ]] || fail "$name: interrupted but $target exists"
    else
      [[ $(tree_sum "$target") == "$before" ]] || fail "$name: interrupted and $target changed"
    fi
    ((hits += hit))
    echo "interrupt_write $name: interrupted (exit $rc, temporary seen: $hit), nothing left"
  elif [[ $rc -eq 0 ]]; then
    if [[ $kind == vtu ]]; then vtu_complete "$target" || fail "$name: exit 0 but $target is incomplete"
    else case_complete "$target" || fail "$name: exit 0 but $target is incomplete"; fi
    echo "interrupt_write $name: finished before the signal, output complete"
  else
    fail "$name: exit $rc (expected $code or 0): $err"
  fi
}

if [[ ! -s $msh ]]; then
  "$bin" generate twomat --tets "$tets" -o "$msh" > /dev/null || { echo "interrupt_write: generate failed"; exit 1; }
fi
rm -rf "$work"
mkdir -p "$work"

# 1. A fresh VTU, SIGTERM while its temporary exists: no output at all.
run_and_signal TERM "$work/out.vtu.tmp.*" -o "$work/out.vtu"
judge vtu-fresh-TERM TERM vtu "$work/out.vtu" ""
[[ $hit -eq 1 ]] || fail "vtu-fresh-TERM: the write's temporary was never seen"

# 2. Over a previous VTU, SIGINT: the previous file stays byte for byte.
"$bin" convert "$msh" --optimize none -o "$work/out.vtu" > /dev/null || fail "baseline convert failed"
before=$(tree_sum "$work")
run_and_signal INT "$work/out.vtu.tmp.*" -o "$work/out.vtu"
judge vtu-existing-INT INT vtu "$work" "$before"

# 3. An existing case with the user's files: only polyMesh may change, and an
#    interrupted swap keeps the old one.
mkdir -p "$work/case/0" "$work/case/system"
echo "user field" > "$work/case/0/U"
echo "user controlDict" > "$work/case/system/controlDict"
"$bin" convert "$msh" --optimize none --format foam -o "$work/case" > /dev/null || fail "baseline case failed"
[[ $(cat "$work/case/0/U") == "user field" ]] || fail "the case lost the user's 0/U"
[[ $(cat "$work/case/system/controlDict") == "user controlDict" && ! -e $work/case/system/fvSchemes ]] ||
  fail "the user's system/ was written into"
before=$(tree_sum "$work/case")
run_and_signal TERM "$work/case/constant/polyMesh.tmp.*" --format foam -o "$work/case"
judge foam-existing-TERM TERM foam "$work/case" "$before"

# 4. A fresh case: nothing, not even the directory.
run_and_signal TERM "$work/fresh/constant/polyMesh.tmp.*" --format foam -o "$work/fresh"
judge foam-fresh-TERM TERM foam "$work/fresh" ""

# 5. Fixed delays around the write (the baseline's timing): each run is either
#    cleanly interrupted or complete.
start=$(date +%s.%N)
"$bin" convert "$msh" --optimize none -o "$work/timing.vtu" > /dev/null
total=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
rm -f "$work/timing.vtu"
for frac in 0.3 0.6 0.8 0.9 0.95 1.05; do
  rm -f "$work/sweep.vtu"
  run_and_signal TERM "$(awk -v t="$total" -v f="$frac" 'BEGIN { printf "%.3f", t * f }')" -o "$work/sweep.vtu"
  judge "vtu-delay-$frac" TERM vtu "$work/sweep.vtu" ""
done

# 6. A full disk (a 2 MB tmpfs, when mounting is allowed): the system's reason,
#    the previous file kept, no temporary.
full="$work/full"
mkdir -p "$full"
if mount -t tmpfs -o size=2m tmpfs "$full" 2> /dev/null; then
  echo previous > "$full/out.vtu"
  "$bin" convert "$msh" --optimize none -o "$full/out.vtu" > /dev/null 2> "$out/stderr"
  rc=$?
  err=$(cat "$out/stderr")
  [[ $rc -eq 1 && $err == *"$full/out.vtu: write failed: No space left on device"* ]] ||
    fail "full disk: exit $rc, '$err'"
  [[ $(cat "$full/out.vtu") == previous ]] || fail "full disk: the previous file changed"
  [[ -z $(leftovers) ]] || fail "full disk: temporaries left: $(leftovers)"
  umount "$full"
  echo "interrupt_write full-disk: $err"
else
  echo "interrupt_write full-disk: skipped (mount not permitted)"
fi

((hits > 0)) || fail "no attempt signalled a write in progress"
echo "interrupt_write: $hits attempts interrupted a write in progress; status $status"
exit $status
