# Every man page's EXAMPLES run as written (STYLE.md: the documentation
# cannot rot): each .Dl line and each .Bd -literal block is one example,
# run with bash -e -o pipefail (a stage failing inside a pipe counts) in a
# scratch folder per page, in order, so that later examples use what
# earlier ones made.  The folder holds the tree's samples/ and tests/, and
# bunny/ (the Stanford scans, ../shared/data/stanford_bunny) when present;
# an example that needs bunny/ without it is skipped with a message.
. tests/lib.sh

# The examples of page $1, each after a line "#@ N", with mdoc's escapes
# undone and a shell prompt "$ " dropped.
examples() {
	awk '
	/^\.Sh / { ex = ($2 == "EXAMPLES"); next }
	!ex { next }
	/^\.Bd -literal/ { lit = 1; print "#@ " ++n; next }
	/^\.Ed/ { lit = 0; next }
	lit { print; next }
	/^\.Dl / { sub(/^\.Dl /, ""); print "#@ " ++n; print }
	' "$1" | sed -e 's/\\e/\\/g' -e 's/\\&//g' -e 's/\\-/-/g' -e 's/^\$ //'
}

for man in man/man1/*.1; do
	page=$(basename "$man" .1)
	dir=$TMP/$page
	scratch_with_tree "$dir"
	examples "$man" | awk -v d="$dir" '/^#@ / { f = d "/ex" sprintf("%02d", $2) ".sh"; next } { print > f }'
	n=0
	for ex in "$dir"/ex*.sh; do
		[ -e "$ex" ] || continue
		n=$((n + 1))
		if [ -z "$bunny" ] && grep -q 'bunny/' "$ex"; then
			echo "man_examples.sh: $page(1) example $n skipped: no ../shared/data/stanford_bunny" >&2
			continue
		fi
		if run_example "$dir" "$ex"; then ok; else example_failed "$page(1) example $n" "$ex"; fi
	done
	check_num "$page(1) has examples" "$n" ">" 0
done
finish
