#!/usr/bin/env bash
# Every code name the docs cite in backquotes with `::` or `()` (README.md, CHANGELOG.md,
# docs/*.md) exists in the source tree, so that a rename cannot leave a doc behind:
#   - each part of `a::b::c` and the `f` of `f()` is a word of the code (sources,
#     TypeScript included, .proto, CMake and shell files);
#   - the last two parts of a qualified name, `Type::member`, appear in one file
#     together (a `StepRunner::run` fails once no file holds both).
# Code blocks (```) are skipped: they are examples, built by their own tests.
# Prints each missing name with the doc that cites it; exits 1 if there is any.
set -euo pipefail
cd "$(dirname "$0")/../.."

code_files=()
while IFS= read -r -d '' file; do code_files+=("$file"); done < <(
  find server client shared testing tests bench proto cmake scripts -type f \
    \( -name '*.h' -o -name '*.cpp' -o -name '*.proto' -o -name '*.cmake' \
       -o -name 'CMakeLists.txt' -o -name '*.sh' -o -name '*.in' -o -name '*.ts' \) \
    ! -path tests/docs/code_names_test.sh ! -path '*/node_modules/*' ! -path '*/dist/*' \
    ! -path '*/src/gen/*' -print0 | sort -z)
words="$(mktemp)"
trap 'rm -f "$words"' EXIT
grep -ohE '[A-Za-z_][A-Za-z0-9_]*' "${code_files[@]}" | sort -u > "$words"

is_word() { grep -qxF -- "$1" "$words"; }
# A file of the code that holds both words.
together() {
  local first
  while IFS= read -r first; do
    if grep -qw -- "$2" "$first"; then return 0; fi
  done < <(grep -lw -- "$1" "${code_files[@]}")
  return 1
}

missing=0
checked=0
for doc in README.md CHANGELOG.md docs/*.md; do
  [ -f "$doc" ] || continue
  # The backquoted spans outside code blocks, then the names in them.
  names=$(awk '/^[[:space:]]*```/ { fenced = !fenced; next } !fenced' "$doc" |
    grep -oE '`[^`]+`' |
    grep -oE '([A-Za-z_][A-Za-z0-9_]*::)+(operator[^ ,()`]+|~?[A-Za-z_][A-Za-z0-9_]*)|[A-Za-z_][A-Za-z0-9_]*\(\)' |
    sort -u) || true
  for name in $names; do
    checked=$((checked + 1))
    plain="${name%()}"
    IFS=':' read -r -a parts <<< "${plain//::/:}"
    problem=""
    for part in "${parts[@]}"; do
      part="${part#\~}"
      case "$part" in operator*) continue ;; esac
      if ! is_word "$part"; then problem="no '$part' in the code"; break; fi
    done
    count=${#parts[@]}
    if [ -z "$problem" ] && [ "$count" -ge 2 ]; then
      owner="${parts[count - 2]}"
      member="${parts[count - 1]#\~}"
      case "$member" in operator*) member="operator" ;; esac
      if ! together "$owner" "$member"; then problem="no file holds both '$owner' and '$member'"; fi
    fi
    if [ -n "$problem" ]; then
      echo "$doc: \`$name\`: $problem"
      missing=$((missing + 1))
    fi
  done
done
echo "code names cited by the docs: $checked checked, $missing missing"
[ "$missing" -eq 0 ]
