#!/usr/bin/env bash
# Rewrites the generated part of docs/options.md from `pointnpr options --markdown`.
#   scripts/options-doc.sh [PATH/TO/pointnpr]   (default: build/pointnpr)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/pointnpr}
doc=$root/docs/options.md
tmp=$(mktemp "$doc.XXXXXX")
trap 'rm -f "$tmp"' EXIT
{
  sed '/<!-- pointnpr options --markdown: begin -->/q' "$doc"
  "$bin" options --markdown
  echo "<!-- pointnpr options --markdown: end -->"
} > "$tmp"
mv "$tmp" "$doc"
trap - EXIT
