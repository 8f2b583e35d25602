#!/usr/bin/env bash
# Fails, listing the files, if any C++ file git tracks differs from what the repository's
# .clang-format makes of it. Run by ctest (test format_check, label unit) and so by CI.
#
#   scripts/check_format.sh     # then, to fix: clang-format -i <the files listed>
#
# Needs git (the files are those `git ls-files` lists) and clang-format (scripts/setup.sh
# installs Debian's).
set -euo pipefail
cd "$(dirname "$0")/.."

for tool in git clang-format; do
    if ! command -v "$tool" >/dev/null; then
        echo "check_format: $tool not found (scripts/setup.sh --deps installs it)" >&2
        exit 1
    fi
done
if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    echo "check_format: $(pwd) is not a git checkout; the files checked are git's" >&2
    exit 1
fi

# One clang-format run over all files; its diagnostics name each file that differs.
report="$(git ls-files -z -- '*.cpp' '*.h' | xargs -0 clang-format --dry-run --Werror 2>&1)" ||
    true
mapfile -t unformatted < <(sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' \
                           <<<"$report" | sort -u)
if [ "${#unformatted[@]}" -ne 0 ]; then
    echo "check_format: ${#unformatted[@]} file(s) not formatted as .clang-format says" \
         "($(clang-format --version | head -n 1)):" >&2
    printf '  %s\n' "${unformatted[@]}" >&2
    echo "check_format: fix with clang-format -i on the files above" >&2
    exit 1
fi
if [ -n "$report" ]; then # clang-format failed otherwise (a bad .clang-format, a missing file)
    echo "$report" >&2
    exit 1
fi
echo "check_format: $(git ls-files -- '*.cpp' '*.h' | wc -l) files formatted"
