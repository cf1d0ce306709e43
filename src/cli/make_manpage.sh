#!/bin/sh
# Writes the man page rollsim(1) from the program's own help (rollsim --help and
# rollsim help COMMAND for every command the overview lists), so that the two never differ.
# usage: make_manpage.sh ROLLSIM OUT.1
set -eu
bin=$1
out=$2

# roff: backslashes, hyphens (so that options copy as ASCII '-') and control characters at a
# line's start are escaped; the help's own line breaks are kept (.nf).
esc() { sed -e 's/\\/\\e/g' -e 's/-/\\-/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"; }

overview=$("$bin" --help)
version=$("$bin" --version | sed 's/^rollsim //')
commands=$(printf '%s\n' "$overview" | sed -n 's/^  \([a-z][a-z]*\)  .*/\1/p')
[ -n "$commands" ] || { echo "make_manpage.sh: no commands in '$bin --help'" >&2; exit 1; }
# the first paragraph after the usage lines, up to its first '(' or '.'
summary=$(printf '%s\n' "$overview" | sed -n '/^$/,/^$/p' | sed '/^$/d' | tr '\n' ' ' |
  sed -e 's/[(.].*//' -e 's/ *$//')
# the options every command takes: once, after the commands (each command's help ends with them)
first=$(printf '%s\n' "$commands" | head -1)

tmp=$out.tmp
{
  printf '.TH ROLLSIM 1 "" "rollsim %s" "User Commands"\n' "$version"
  printf '.SH NAME\nrollsim \\- %s\n' "$(printf '%s\n' "$summary" | esc)"
  printf '.SH SYNOPSIS\n.nf\n'
  printf '%s\n' "$overview" | sed '/^$/,$d' | sed 's/^usage: //; s/^       //' | esc
  printf '.fi\n.SH DESCRIPTION\n.nf\n'
  printf '%s\n' "$overview" | sed '1,/^$/d' | esc
  printf '.fi\n.SH COMMANDS\n'
  for c in $commands; do
    printf '.SS %s\n.nf\n' "$c"
    "$bin" help "$c" | sed '/^Options for every command:/,$d' | esc
    printf '.fi\n'
  done
  printf '.SH OPTIONS FOR EVERY COMMAND\n.nf\n'
  "$bin" help "$first" | sed '1,/^Options for every command:/d' | esc
  printf '.fi\n'
} >"$tmp"
mv "$tmp" "$out"
