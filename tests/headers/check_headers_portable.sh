#!/usr/bin/env bash
# The installed headers are portable C++ (docs/architecture.md): no compiler builtins or attributes, no pragmas, no
# inline assembly, no class-specific operator new or delete, no offsetof. Lists every line that breaks the rule.
# Usage: check_headers_portable.sh <source root> <header list file>
set -euo pipefail
root="$1" list="$2"
# Builtins and attributes, pragmas, class-specific operator new or delete (not a call of ::operator new), offsetof,
# inline assembly.
pattern='__builtin_|__attribute__|^[[:space:]]*#[[:space:]]*pragma'
pattern+='|(^|[^:])operator[[:space:]]+(new|delete)[[:space:]]*\(|offsetof|__asm|\basm[[:space:]]*\('
found=0
while read -r header; do
    [ -n "$header" ] || continue
    if grep -nHE "$pattern" "$root/$header"; then found=1; fi
done <"$list"
if [ "$found" = 1 ]; then
    echo "installed headers must be portable C++: the lines above use compiler-specific features"
    exit 1
fi
echo "$(grep -c . "$list") installed headers, none with builtins, attributes, pragmas, assembly," \
    "operator new or offsetof"
