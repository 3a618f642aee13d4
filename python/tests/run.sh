#!/usr/bin/env bash
# Python package test: builds the wheel with maturin (from PyPI), installs it
# into a fresh venv under the target directory, builds the Rust CLI (the
# `detect` example) for the bit-exactness tests, and runs pytest on
# python/tests. Honours CARGO_TARGET_DIR; PYTHON picks the interpreter
# (default python3). opencv-contrib-python-headless is installed too, for the
# check that colour input equals cv2.cvtColor and for the bench's OpenCV rows;
# AAGLSD_PY_OPENCV=0 leaves it out (those tests then skip, saying so).
set -euo pipefail
cd "$(dirname "$0")/../.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
venv=$target_dir/py-venv
tools=$target_dir/py-tools
python=${PYTHON:-python3}

# The build tools live in their own venv, kept between runs; the wheel is
# installed into a venv made afresh each run, with pytest and mypy (stubtest).
if [ ! -x "$tools/bin/maturin" ]; then
    echo "==> venv with maturin: $tools"
    "$python" -m venv "$tools"
    "$tools/bin/pip" install --quiet --disable-pip-version-check 'maturin>=1.9,<2'
fi
echo "==> maturin build --release (wheel)"
rm -rf "$target_dir/wheels"
"$tools/bin/maturin" build --quiet --release -m python/Cargo.toml --out "$target_dir/wheels" \
    --interpreter "$python"
wheel=$(ls "$target_dir"/wheels/aaglsd-*.whl)
echo "    $wheel: $(wc -c <"$wheel") bytes"

echo "==> fresh venv: $venv"
rm -rf "$venv"
"$python" -m venv "$venv"
pip=("$venv/bin/pip" install --quiet --disable-pip-version-check)
"${pip[@]}" "$wheel" pytest mypy
if [ "${AAGLSD_PY_OPENCV:-1}" = 1 ]; then
    "${pip[@]}" opencv-contrib-python-headless ||
        echo "!!! opencv-contrib-python-headless did not install: its checks will SKIP !!!"
fi

echo "==> the Rust CLI (cargo build --release --example detect)"
cargo build --quiet --release --example detect

echo "==> pytest python/tests"
# Run from the tests folder so that `import aaglsd` finds the installed
# wheel, not the source folder python/aaglsd.
cd python/tests
AAGLSD_CLI=$target_dir/release/examples/detect "$venv/bin/python" -m pytest -q -rs -p no:cacheprovider .
