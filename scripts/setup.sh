#!/usr/bin/env bash
# Sets up a fresh Debian machine for propbet: installs the Debian packages it needs
# (scripts/debian-packages.txt), checks the Rust toolchain, and builds the release binary.
# Usage: scripts/setup.sh            install + build
#        scripts/setup.sh --no-build install only (CI)
set -euo pipefail
cd "$(dirname "$0")/.."

need_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

missing=()
while read -r pkg; do
  case "$pkg" in ''|'#'*) continue ;; esac
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done < scripts/debian-packages.txt
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  # Another apt (unattended upgrades on a fresh machine) may hold the lock: wait for it, up to
  # 10 minutes, instead of failing at once.
  lock=(-o DPkg::Lock::Timeout=600)
  need_root apt-get "${lock[@]}" update -qq
  need_root env DEBIAN_FRONTEND=noninteractive apt-get "${lock[@]}" install -y -qq "${missing[@]}"
fi

required=$(sed -n 's/^rust-version *= *"\(.*\)"/\1/p' Cargo.toml)
if ! command -v cargo >/dev/null 2>&1; then
  echo "setup: no Rust toolchain found. Install Rust $required or newer with rustup" >&2
  echo "       (https://rustup.rs), then run this script again." >&2
  exit 2
fi
have=$(rustc --version | awk '{print $2}')
if [ "$(printf '%s\n%s\n' "$required" "$have" | sort -V | head -n1)" != "$required" ]; then
  echo "setup: rustc $have is older than the required $required; run 'rustup update'" >&2
  exit 2
fi
for comp in rustfmt clippy; do
  if ! cargo "${comp/rustfmt/fmt}" --version >/dev/null 2>&1; then
    command -v rustup >/dev/null 2>&1 && rustup component add "$comp"
  fi
done

# The book (docs/, `mdbook build docs`): mdBook from crates.io, built once.
if ! command -v mdbook >/dev/null 2>&1; then
  echo "setup: installing mdBook (cargo install, a few minutes once)"
  cargo install mdbook --version 0.5.4 --locked
fi

# Python packages of the tests (scripts/python-requirements.txt, pinned, from the Python
# registry) in a virtual environment, .venv, made again when the list changes.
if [ ! -x .venv/bin/python ] || ! cmp -s scripts/python-requirements.txt .venv/requirements.txt; then
  echo "setup: installing Python packages into .venv: $(grep -v '^#' scripts/python-requirements.txt | xargs)"
  rm -rf .venv
  python3 -m venv .venv
  .venv/bin/pip install --quiet --disable-pip-version-check -r scripts/python-requirements.txt
  cp scripts/python-requirements.txt .venv/requirements.txt
fi

if [ "${1:-}" != "--no-build" ]; then
  cargo build --release --locked -p propbet-cli
  echo "setup: built target/release/propbet"
  # The Python package over the same engine, into .venv (`.venv/bin/python -c "import propbet"`).
  scripts/python-package.sh
fi
