#!/usr/bin/env bash
# docs/options.md states the defaults and ranges as the library's tables do: its generated part is
# exactly `pointnpr options --markdown` (scripts/options-doc.sh rewrites it).
#   bash cli_options_doc.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2/cli_options_doc
rm -rf "$dir"; mkdir -p "$dir"
doc=$(dirname "$0")/../docs/options.md
sed -n '/<!-- pointnpr options --markdown: begin -->/,/<!-- pointnpr options --markdown: end -->/p' "$doc" \
  | sed '1d;$d' > "$dir/doc.md"
"$bin" options --markdown > "$dir/cli.md"
if [ ! -s "$dir/cli.md" ] || ! grep -q '^## features$' "$dir/cli.md"; then
  echo "FAILED: pointnpr options --markdown printed no features table" >&2; exit 1
fi
if ! diff -u "$dir/doc.md" "$dir/cli.md" >&2; then
  echo "FAILED: docs/options.md differs from 'pointnpr options --markdown' (run scripts/options-doc.sh)" >&2; exit 1
fi
"$bin" options --bogus > /dev/null 2>&1 && { echo "FAILED: options --bogus accepted" >&2; exit 1; }
echo "cli_options_doc: ok"
