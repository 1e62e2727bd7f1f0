# Every program's --help starts with its man page's SYNOPSIS (the same
# words and brackets, blanks aside), so the two cannot drift apart; and
# every man page has the sections a user looks for; every program built has
# a man page and a row in the README's table.
. tests/lib.sh

command -v mandoc >/dev/null || { echo "manpages.sh: mandoc missing, skipped" >&2; finish; exit; }
for man in man/man1/*.1; do
	prog=$(basename "$man" .1)
	[ -x "$FCT_BIN/$prog" ] || continue
	mandoc -Tascii "$man" | col -b | awk '/^SYNOPSIS/ { f = 1; next } /^[A-Z]/ { f = 0 } f' |
		tr -s ' \t\n' '   ' | sed 's/^ //; s/ $//' >"$TMP/syn"
	# The usage: its first line and the continuation lines (indented, an
	# option bracket or a second form of the command).
	"$FCT_BIN/$prog" --help | awk -v p="$prog" '
		/^usage: / { f = 1; sub(/^usage: /, ""); print; next }
		f && ($0 ~ "^ +\\[" || $0 ~ "^ +-" || $0 ~ "^ +" p " ") { print; next } { f = 0 }' |
		tr -s ' \t\n' '   ' | sed 's/^ //; s/ $//' >"$TMP/use"
	check_true "$prog: --help usage = man page SYNOPSIS:
  man:  $(cat "$TMP/syn")
  help: $(cat "$TMP/use")" cmp -s "$TMP/syn" "$TMP/use"
	for section in NAME SYNOPSIS DESCRIPTION "EXIT STATUS" EXAMPLES; do
		check_true "$prog.1 has $section" grep -q "^\\.Sh $section\$" "$man"
	done
done
# Every program built has its man page and its row in the README's table of
# programs (issue 24 item 11: the README described stages "being built"
# after they were there; it says what is there, and stays so).
for prog in "$FCT_BIN"/*; do
	prog=$(basename "$prog")
	check_true "$prog has man/man1/$prog.1" test -f "man/man1/$prog.1"
	check_true "$prog has a row in the README's table" grep -q "^| \`$prog\` |" README.md
done
finish
