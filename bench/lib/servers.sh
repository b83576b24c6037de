# Sourced by the bench scripts that run physics-server and physics-netsim as
# programs: each is started in the sourcing shell itself (not in a command
# substitution's subshell), so that bench_stop_all finds and stops every one.
bench_pids=()

# bench_start VAR LOG COMMAND...: starts COMMAND, which prints "listening on
# ADDRESS:PORT", in the background with its output in LOG (LOG.err), and sets VAR to
# the port once it listens; exits with COMMAND's errors when it does not in 10 s.
bench_start() {
  local var="$1" log="$2"
  shift 2
  "$@" >"$log" 2>"$log.err" &
  bench_pids+=($!)
  for _ in $(seq 100); do
    if grep -q '^listening on ' "$log"; then
      printf -v "$var" '%s' "$(sed -n 's/^listening on .*:\([0-9]*\)$/\1/p' "$log" | head -n 1)"
      return 0
    fi
    sleep 0.1
  done
  echo "$(basename "$0"): $1 did not listen" >&2
  cat "$log.err" >&2
  exit 1
}

# Stops every program bench_start started.
bench_stop_all() {
  for pid in "${bench_pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  bench_pids=()
}
