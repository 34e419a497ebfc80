#!/usr/bin/env bash
# ctest: what `prt view`'s server refuses (cli/view/request_target.h, view_server.h). Starts
# `prt view --port 0` on the bundled demo and sends each request with `curl --path-as-is` (so
# curl sends the path as written) or, for request lines curl cannot write, through a raw socket
# (bash's /dev/tcp). Every refusal must come with its status and no payload. Exits 77 (skipped)
# when curl is missing or the page was not built.
# Usage: check_server_refusals.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR WEB_DIR
set -euo pipefail
prt="$1" root="$2" out="$3" web="$4"
command -v curl >/dev/null 2>&1 || { echo "skipping: curl is not installed"; exit 77; }
[ -f "$web/index.html" ] || { echo "skipping: the viewer's page was not built ($web)"; exit 77; }
rm -rf "$out" && mkdir -p "$out"
"$prt" bake "$root/data/demo.glb" -o "$out/demo.prt" --order 2 --samples 16 --quiet
# Without the page's build (a build without node): one line, status 1, nothing served.
status=0
PRT_VIEW_WEB_DIR="$out/no-web" "$prt" view "$root/data/demo.glb" "$out/demo.prt" --port 0 \
  >"$out/noweb.out" 2>"$out/noweb.err" || status=$?
if [ "$status" != 1 ] || [ "$(wc -l <"$out/noweb.err")" != 1 ] || ! grep -q "web assets were not built" "$out/noweb.err" || [ -s "$out/noweb.out" ]; then
  echo "FAIL: without the page: status $status, stderr: $(cat "$out/noweb.err"), stdout: $(cat "$out/noweb.out")"; exit 1
fi
echo "ok   without the page: $(cat "$out/noweb.err")"
# --also files that do not match FILE: one line naming the file and the difference, status 1,
# nothing printed on stdout (no port was opened: the URL is printed once the port is bound).
"$prt" bake "$root/data/demo.glb" -o "$out/demo3.prt" --order 3 --samples 16 --quiet
cp "$root/tests/scripts/fixtures/room.obj" "$root/tests/scripts/fixtures/room.mtl" "$out/"
"$prt" bake "$out/room.obj" -o "$out/room.prt" --order 2 --samples 4 --quiet
refuse_also() {  # refuse_also DESCRIPTION EXPECTED_TEXT ARGS...
  local what="$1" want="$2" status=0; shift 2
  "$prt" view "$@" --port 0 >"$out/also.out" 2>"$out/also.err" || status=$?
  if [ "$status" = 0 ] || [ "$(wc -l <"$out/also.err")" != 1 ] || ! grep -qF -- "$want" "$out/also.err" || [ -s "$out/also.out" ]; then
    echo "FAIL: $what: status $status, stderr: $(cat "$out/also.err"), stdout: $(cat "$out/also.out")"; exit 1
  fi
  echo "ok   $what: $(cat "$out/also.err")"
}
refuse_also "--also of another order" "demo3.prt: SH order 3, but $out/demo.prt has 2" \
  "$root/data/demo.glb" "$out/demo.prt" --also "$out/demo3.prt"
refuse_also "--also of another scene" "room.prt" "$root/data/demo.glb" "$out/demo.prt" --also "$out/room.prt"
# Payloads larger than --memory-limit (the demo's at order 3: 0.6 MB of transfer after 0.6 MB of
# mesh): one line naming the file, the part, the total and the limit, status 1, no port opened.
# The served demo below runs under a limit that fits (order 2 with --also: 1.2 MB in all).
refuse_also "payloads over --memory-limit" \
  "demo3.prt: the transfer payload would take 639.8 KB, 1.3 MB in all; the memory limit is 1.0 MB" \
  "$root/data/demo.glb" "$out/demo3.prt" --memory-limit 1M
. "$root/tests/viewer/view_server.sh"
start_view "$out" "$root/data/demo.glb" "$out/demo.prt" --also "$out/demo.prt" --memory-limit 4M --quiet
case "$url" in http://127.0.0.1:*/) ;; *) echo "FAIL: not on loopback by default: '$url'"; exit 1 ;; esac
port="${url#http://127.0.0.1:}" port="${port%/}"
failures=0
expect() {  # expect STATUS DESCRIPTION CURL_ARGS...
  local want="$1" what="$2"; shift 2
  local got
  got="$(curl -s --path-as-is -o "$out/body" -w '%{http_code}' "$@" || true)"
  if [ "$got" = "$want" ]; then echo "ok   $want $what"; else echo "FAIL $what: HTTP $got, expected $want"; failures=$((failures + 1)); fi
  if [ "$want" != 200 ] && grep -q '"format"' "$out/body" 2>/dev/null; then
    echo "FAIL $what: a refused request got a payload"; failures=$((failures + 1))
  fi
}
raw() {  # raw STATUS DESCRIPTION REQUEST_LINE [HOST]
  local want="$1" what="$2" line="$3" host="${4:-127.0.0.1:$port}" got
  exec 3<>"/dev/tcp/127.0.0.1/$port"
  printf '%s\r\nHost: %s\r\nConnection: close\r\n\r\n' "$line" "$host" >&3
  got="$(head -n 1 <&3 | tr -d '\r' | cut -d' ' -f2)"
  exec 3<&- 3>&-
  if [ "$got" = "$want" ]; then echo "ok   $want $what"; else echo "FAIL $what: HTTP '$got', expected $want"; failures=$((failures + 1)); fi
}
base="http://127.0.0.1:$port"
expect 200 "the page" "$base/"
expect 200 "the page with a query" "$base/?rotate=90,0,0&exposure=-1"
expect 200 "the manifest" "$base/api/manifest.json"
expect 200 "the transfer" "$base/api/transfer.bin"
expect 200 "the --also file's transfer, by number" "$base/api/also0.bin"
expect 404 "no second --also file" "$base/api/also1.bin"
expect 404 "nor an --also file by name" "$base/api/demo.prt"
for method in POST PUT DELETE OPTIONS PATCH TRACE; do
  expect 405 "method $method" -X "$method" "$base/api/manifest.json"
done
expect 405 "method HEAD" -I "$base/"
raw 400 "a method HTTP does not define" "FOO / HTTP/1.1"
expect 400 "/../" "$base/../../../../etc/passwd"
expect 400 "/api/../" "$base/api/../api/manifest.json"
expect 400 "/vendor/../ (to a real route)" "$base/vendor/../index.html"
expect 400 "%2e%2e" "$base/%2e%2e/%2e%2e/etc/passwd"
expect 400 "%2E%2E" "$base/%2E%2E/etc/passwd"
expect 400 "..%2f" "$base/..%2f..%2fetc%2fpasswd"
expect 400 "%2f in a route" "$base/api%2fmanifest.json"
expect 400 "double-encoded %252e%252e" "$base/%252e%252e/%252e%252e/etc/passwd"
expect 400 "backslashes" "$base/..\\..\\etc\\passwd"
expect 400 "%5c" "$base/..%5c..%5cetc%5cpasswd"
expect 400 "an empty segment" "$base//etc/passwd"
expect 400 "a space-like byte" "$base/api/manifest.json%00"
raw 400 "a target without its leading slash" "GET ../../etc/passwd HTTP/1.1"
raw 400 "an absolute-form target" "GET http://127.0.0.1:$port/api/manifest.json HTTP/1.1"
raw 400 "a raw /../ the client did not normalise" "GET /../../etc/passwd HTTP/1.1"
raw 400 "a control byte in the query" "GET /?a$(printf '\x01')b HTTP/1.1"
raw 400 "a Host header naming another server (DNS rebinding)" "GET /api/manifest.json HTTP/1.1" "attacker.example:$port"
raw 200 "Host: localhost" "GET /api/manifest.json HTTP/1.1" "localhost:$port"
expect 404 "an unknown path" "$base/nope"
expect 404 "the given files are not served by name" "$base/demo.prt"
expect 404 "nor is the scene" "$base/demo.glb"
expect 404 "nor index.html by name" "$base/index.html"
expect 404 "/api/ itself" "$base/api/"
kill -0 $server 2>/dev/null || { echo "FAIL: the server died"; exit 1; }
# Ctrl-C stops the server with status 0 (a script's background job starts with SIGINT ignored;
# prt view resets it, and its worker threads have it blocked).
kill -INT "$server"
status=0
wait "$server" || status=$?
server=""
if [ "$status" = 0 ]; then echo "ok   SIGINT stops the server, status 0"; else echo "FAIL SIGINT: status $status"; failures=$((failures + 1)); fi
[ "$failures" -eq 0 ] || { echo "$failures refusal checks failed"; exit 1; }
echo "every refusal held"
