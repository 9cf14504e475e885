#!/usr/bin/env bash
# Fails when a C++ source under the project's own directories is not clang-formatted.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
mapfile -t files < <(find base lumped geometry fem fit io app report server cli tests bench -type f \( -name '*.h' -o -name '*.cc' \) | sort)
[ ${#files[@]} -gt 0 ] || exit 0
clang-format --dry-run --Werror "${files[@]}"
echo "check-format: ${#files[@]} files formatted"
