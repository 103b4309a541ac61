#!/usr/bin/env bash
# Install the Debian packages listed in scripts/packages.txt that are missing.
# Idempotent and offline once everything is installed: apt is only called when needed.
# Usage: scripts/install-deps.sh [extra package list files...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lists=("$here/packages.txt" "$@")

missing=()
for list in "${lists[@]}"; do
  while read -r pkg _; do
    [[ -z "$pkg" || "$pkg" == \#* ]] && continue
    status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
    [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
  done <"$list"
done

if ((${#missing[@]} == 0)); then
  echo "deps: all Debian packages present"
  exit 0
fi

echo "deps: installing ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null; then
  sudo=(sudo)
else
  echo "deps: missing packages (${missing[*]}) and not root and no sudo: install them and rerun" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
# Try without refreshing the index first (works offline from a warm cache), then refresh.
if ! "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"; then
  "${sudo[@]}" apt-get update -qq
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
