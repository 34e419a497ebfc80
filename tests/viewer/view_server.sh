# Sourced by the viewer's test drivers and benchmarks (tests/viewer/run_*_check.sh,
# check_server_refusals.sh, bench/viewer/measure_*.sh): `prt view` in the background, its URL,
# and its end when the script exits. Needs `set -euo pipefail` and $prt (the prt binary) set by
# the script that sources it.
#   require_browser ROOT [WEB_DIR]   exit 77 (ctest: skipped) with a message unless chromium, node,
#                                    tests/viewer's npm packages and (given WEB_DIR) the page's
#                                    build are there
#   start_view DIR ARGS...           `prt view ARGS... --port 0` in the background, its output in
#                                    DIR/view.out and DIR/view.err; sets $server (its pid) and
#                                    $url (http://127.0.0.1:PORT/) once it serves; exits 1 with
#                                    its stderr when it stops first or prints no URL in 600 s
#   stop_view                        ends the server start_view started (also done at exit)

server=""
trap '[ -z "$server" ] || kill "$server" 2>/dev/null || true' EXIT

require_browser() {
  local root="$1" web="${2:-}"
  local how="(bash scripts/install-deps.sh --for test installs it)"
  [ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "skipping: chromium is not installed $how"; exit 77; }
  command -v node >/dev/null 2>&1 || { echo "skipping: node is not installed $how"; exit 77; }
  [ -d "$root/tests/viewer/node_modules/puppeteer-core" ] ||
    { echo "skipping: $root/tests/viewer/node_modules/puppeteer-core is missing $how"; exit 77; }
  [ -z "$web" ] || [ -f "$web/index.html" ] ||
    { echo "skipping: the viewer's page was not built ($web/index.html)"; exit 77; }
}

start_view() {
  local dir="$1"; shift
  "$prt" view "$@" --port 0 >"$dir/view.out" 2>"$dir/view.err" &
  server=$!
  url=""
  for _ in $(seq 1 6000); do
    # the whole "serving URL (Ctrl-C stops)" line, not a URL still being written
    url="$(sed -n 's|^serving \(http://[^ ]*/\) .*|\1|p' "$dir/view.out" 2>/dev/null || true)"
    [ -n "$url" ] && return 0
    kill -0 "$server" 2>/dev/null || { cat "$dir/view.err"; server=""; exit 1; }
    sleep 0.1
  done
  echo "prt view printed no URL in 600 s"
  exit 1
}

stop_view() {
  [ -z "$server" ] || { kill "$server" && wait "$server" 2>/dev/null || true; }
  server=""
}
