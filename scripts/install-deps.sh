#!/usr/bin/env bash
# Installs every Debian 12 package PGE needs, skipping those already present.
# Idempotent: a second run installs nothing. Exit codes:
#   0  everything needed is installed
#   1  a package could not be installed (the message says which and why)
#   2  not a Debian-like system with apt-get and dpkg-query
# Usage: scripts/install-deps.sh [--with-optional]
#   --with-optional  also installs packages used only by optional commands (none today: the
#                    report's plots need gnuplot-nox and its test Chromium, both required).
set -euo pipefail

required=(
  build-essential cmake git pkg-config
  libboost-dev libgmp-dev libmpfr-dev libmpfi-dev libcgal-dev libflint-arb-dev
  libgtest-dev libgmock-dev librapidcheck-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  gnuplot-nox chromium python3 libbox2d-dev libchipmunk-dev
)
# gnuplot-nox draws the report's plots; chromium loads the report's page in a test (headless);
# python3 checks XML and JSON in the command-line tests; Box2D and Chipmunk are the peers of
# `pge compare` (without them it skips them and says so).
optional=()

packages=("${required[@]}")
if [[ "${1:-}" == "--with-optional" ]]; then
  packages+=(${optional[@]+"${optional[@]}"})
elif [[ $# -gt 0 ]]; then
  echo "install-deps: unknown argument '$1' (use --with-optional or nothing)" >&2
  exit 2
fi

if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: this script needs Debian's apt-get and dpkg-query; install these by hand: ${packages[*]}" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "install-deps: missing packages (${missing[*]}) and not root, and sudo is not available" >&2
    exit 1
  fi
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if ! "${sudo_cmd[@]}" apt-get update -q >/dev/null; then
  echo "install-deps: 'apt-get update' failed; check the network or apt sources" >&2
  exit 1
fi
if ! "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"; then
  echo "install-deps: 'apt-get install ${missing[*]}' failed" >&2
  exit 1
fi
echo "install-deps: done"
