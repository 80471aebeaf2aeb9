#!/usr/bin/env bash
# The Python package's test step (docs/reference/python.md), run by .ci/run before `cargo xtask test`:
# a virtual environment with maturin, numpy, pandas, dask[distributed], pytest (and pygmo and
# pymoo if they install: their tests skip otherwise), the wheel built with `maturin build --release` and
# installed, fmt/clippy of the bindings crate, then pytest against the host-sim binary.
# Exits non-zero on any failure, including pytest collecting no tests (its exit code 5).
# Usage: bash python/ci.sh   (from anywhere; needs python3 and cargo)
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$repo/target}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

if ! python3 -m venv "$work/venv" >/dev/null 2>&1; then
  # Debian/Ubuntu ship venv/ensurepip separately.
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv python3-pip >/dev/null
  elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    sudo apt-get update -qq && sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv python3-pip >/dev/null
  else
    echo "python3 -m venv failed; install python3-venv (apt-get install python3-venv)" >&2
    exit 1
  fi
  rm -rf "$work/venv"
  python3 -m venv "$work/venv"
fi
py="$work/venv/bin/python"
"$py" -m pip install --quiet --upgrade pip
"$py" -m pip install --quiet maturin numpy pandas "dask[distributed]" pytest
for optional in pygmo pymoo; do
  if ! "$py" -m pip install --quiet "$optional"; then
    echo "python step: $optional does not install here; its tests will be skipped" >&2
  fi
done

echo "python step: fmt and clippy of the bindings crate (python/)"
if command -v rustup >/dev/null 2>&1; then rustup component add clippy rustfmt >/dev/null 2>&1 || true; fi
cargo fmt --manifest-path python/Cargo.toml --check
cargo clippy --manifest-path python/Cargo.toml --release --all-targets -- -D warnings

echo "python step: wheel"
(cd python && "$work/venv/bin/maturin" build --release --quiet --interpreter "$py" --out "$work/wheels")
"$py" -m pip install --quiet "$work"/wheels/reentry-*.whl

echo "python step: host-sim binary for the round trips"
cargo build --release -p host-sim --quiet
export HOST_SIM="$CARGO_TARGET_DIR/release/host-sim" REENTRY_REQUIRE_HOST_SIM=1

echo "python step: pytest"
rc=0
(cd "$work" && "$py" -m pytest -q -p no:cacheprovider "$repo/python/tests") || rc=$?
if [ "$rc" = 5 ]; then
  echo "python step: pytest collected no tests" >&2
  exit 1
fi
exit "$rc"
