#!/usr/bin/env bash
# Builds propbet's Python package (crates/python: a wheel by maturin, the release profile) and
# installs it into the virtual environment .venv that scripts/setup.sh made.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/maturin ]; then
  echo "python-package: .venv has no maturin: run scripts/setup.sh first" >&2
  exit 2
fi
rm -rf target/wheels
VIRTUAL_ENV="$PWD/.venv" .venv/bin/maturin build --quiet --release --locked \
  -m crates/python/Cargo.toml -i .venv/bin/python -o target/wheels
.venv/bin/pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/wheels/propbet-*.whl
echo "python-package: installed $(ls target/wheels/propbet-*.whl) into .venv"
