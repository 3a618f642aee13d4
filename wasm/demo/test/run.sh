#!/usr/bin/env bash
# Browser test of the demo: installs Debian's chromium (apt) and
# puppeteer-core (npm ci) when missing, builds the demo (wasm/demo/build.sh),
# writes the host core's expected output and the Rust CLI's text for the
# bundled image, serves wasm/demo on a free localhost port, and runs
# `node --test wasm/demo/test/` (headless Chromium). The server is stopped on
# exit, whatever happens; the test closes the browser (puppeteer also kills it
# if node dies). Screenshot: $CARGO_TARGET_DIR/demo-test/screenshot.png.
set -euo pipefail
cd "$(dirname "$0")/../../.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
work=$target_dir/demo-test
chromium=${CHROMIUM:-/usr/bin/chromium}

if [ ! -x "$chromium" ]; then
    echo "==> apt-get install chromium"
    apt-get -o DPkg::Lock::Timeout=600 update
    DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 install -y chromium
fi
if [ ! -d wasm/demo/test/node_modules/puppeteer-core ]; then
    echo "==> npm ci (puppeteer-core)"
    (cd wasm/demo/test && npm ci --no-audit --no-fund)
fi

echo "==> build the demo"
bash wasm/demo/build.sh

echo "==> expected output from the host Rust core and the Rust CLI"
cargo run --quiet -p aaglsd-wasm --release --example wasm_expected -- "$work"
cargo build --quiet --release --example detect
"$target_dir/release/examples/detect" "$work/input.pgm" >"$work/cli-default.txt"
"$target_dir/release/examples/detect" "$work/input.pgm" --scores >"$work/cli-scores.txt"

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server -d wasm/demo "$port" --bind 127.0.0.1 >"$work/server.log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
for _ in $(seq 50); do
    python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/')" 2>/dev/null && break
    sleep 0.1
done

echo "==> node --test wasm/demo/test/ (Chromium $("$chromium" --version 2>/dev/null | sed -n 's/^Chromium \([^ ]*\).*/\1/p'))"
AAGLSD_DEMO_URL=http://127.0.0.1:$port/ AAGLSD_DEMO_WORK=$work CHROMIUM=$chromium \
    timeout 300 node --test wasm/demo/test/
