#!/usr/bin/env bash
# signal_after_line.sh SIGNAL PATTERN COMMAND...: runs COMMAND, sends it SIGNAL as soon as a line of its
# standard output or error matches PATTERN (grep -E), and exits with COMMAND's status; its two streams are
# passed through. A test that means "a signal while the command is at stage X" waits for the line that
# says X instead of guessing a delay, which a loaded machine can exceed (the signal then comes before the
# command has installed its handlers).
set -u
sig=$1 pattern=$2
shift 2
out=$(mktemp) err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT
"$@" >"$out" 2>"$err" &
pid=$!
for _ in $(seq 12000); do  # 2 minutes at most
  if grep -qE "$pattern" "$out" "$err"; then kill -s "$sig" "$pid"; break; fi
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.01
done
wait "$pid"
rc=$?
cat "$out"
cat "$err" >&2
exit "$rc"
