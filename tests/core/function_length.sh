#!/bin/sh
# Function length check: every function body in the given folders' .cpp/.hpp files is at most
# MAX lines, counted from the first line of its declaration to its closing brace (comments
# inside count, the comment above does not). A brace-matching scan, not a parser: a `{` opens a
# function when the code before it (since the last `;`, `{` or `}`) has a `(` and no
# namespace/class/struct/union/enum keyword; braces inside a function are its blocks.
# Usage: function_length.sh MAX DIR...   Exit: 0 all within MAX, 1 some longer (listed), 2 usage.
set -eu
[ $# -ge 2 ] || { echo "usage: $0 MAX DIR..." >&2; exit 2; }
MAX=$1; shift
FILES=$(find "$@" -type f \( -name '*.cpp' -o -name '*.hpp' \) | sort)
[ -n "$FILES" ] || { echo "no .cpp/.hpp files in $*" >&2; exit 2; }
# shellcheck disable=SC2086  # the file names have no spaces
exec awk -v max="$MAX" '
FNR == 1 { depth = 0; infn = 0; head = ""; head_line = 0; incomment = 0; prev = "" }
{
  line = $0
  if (!incomment && line ~ /^[ \t]*#/) next  # preprocessor
  n = length(line)
  for (i = 1; i <= n; ++i) {
    c = substr(line, i, 1); d = substr(line, i, 2)
    if (incomment) { if (d == "*/") { incomment = 0; ++i } continue }
    if (d == "/*") { incomment = 1; ++i; continue }
    if (d == "//") break
    # A string or char literal; a quote after a digit is a digit separator (80\047000).
    if (c == "\"" || (c == "\047" && prev !~ /[0-9A-Fa-f]/)) {
      q = c
      for (++i; i <= n; ++i) { e = substr(line, i, 1); if (e == "\\") ++i; else if (e == q) break }
      head = head " "; prev = q; continue
    }
    if (c == "{") {
      ++depth
      if (infn) { continue }
      if (head ~ /\(/ && head !~ /(^|[^A-Za-z0-9_])(namespace|class|struct|union|enum)([^A-Za-z0-9_]|$)/) {
        infn = depth; start = head_line ? head_line : FNR; name = head
      }
      head = ""; head_line = 0; prev = c; continue
    }
    if (c == "}") {
      if (infn == depth) {
        len = FNR - start + 1
        if (len > max) {
          sub(/\(.*/, "", name); gsub(/.*[ \t*&]/, "", name)
          printf "%s:%d: %s is %d lines (max %d)\n", FILENAME, start, name, len, max
          bad = 1
        }
        infn = 0
      }
      --depth; head = ""; head_line = 0; prev = c; continue
    }
    if (!infn) {
      if (c == ";") { head = ""; head_line = 0 }
      else { if (head_line == 0 && c !~ /[ \t]/) head_line = FNR; head = head c }
      if (c == ":" && head ~ /^[ \t]*(public|protected|private)[ \t]*:$/) { head = ""; head_line = 0 }
    }
    if (c !~ /[ \t]/) prev = c
  }
  if (!infn && head_line) head = head " "
}
END { exit bad ? 1 : 0 }' $FILES
