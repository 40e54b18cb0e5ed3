#!/usr/bin/env bash
# Install what building and testing dynkit needs on Debian/Ubuntu (as root, or through sudo).
# The core library needs only a C11 compiler and libm; the rest is for the CLI's tests.
set -euo pipefail
packages=(build-essential cmake pkg-config libcmocka-dev clang)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: everything is installed"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
