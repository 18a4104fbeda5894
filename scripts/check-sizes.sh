#!/usr/bin/env bash
# Checks the size limits of issue 13 for generator/ and runtime/: no source file over 600 lines,
# no function over 120 lines (function extents from Universal Ctags). Prints each offender and
# exits non-zero if there is one.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
status=0
files=$(git ls-files 'generator/*.cpp' 'generator/*.hpp' 'runtime/*.hpp' 'runtime/*.cpp')
for f in $files; do
  lines=$(wc -l < "$f")
  if [ "$lines" -gt 600 ]; then echo "$f: $lines lines (limit 600)"; status=1; fi
done
# function extents from ctags: name, file, start line, end line
long=$(ctags --language-force=C++ --kinds-C++=f --fields=+ne -o - $files 2>/dev/null |
       awk -F'\t' '{s=""; e=""; for (i=4;i<=NF;i++) { if ($i ~ /^line:/) s=substr($i,6); if ($i ~ /^end:/) e=substr($i,5) }
                    if (s != "" && e != "" && e - s + 1 > 120) printf "%s:%s: function %s is %d lines (limit 120)\n", $2, s, $1, e - s + 1}')
if [ -n "$long" ]; then echo "$long"; status=1; fi
exit $status
