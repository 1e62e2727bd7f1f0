# Every man page's EXAMPLES run as written (STYLE.md: the documentation
# cannot rot): each .Dl line and each .Bd -literal block is one example,
# run with bash -e -o pipefail (a stage failing inside a pipe counts) in a
# scratch folder per page, in order, so that later examples use what
# earlier ones made.  The folder holds the tree's samples/ and tests/, and
# bunny/ (the Stanford scans, ../shared/data/stanford_bunny) when present;
# an example that needs bunny/ without it is skipped with a message.
# FCT_EXAMPLES_TIME=1 prints each example's seconds on stderr.
. tests/lib.sh

top=$(pwd)
bunny=
for d in ../shared/data/stanford_bunny /work/shared/data/stanford_bunny; do
	[ -f "$d/data/bun.conf" ] && bunny=$(cd "$d" && pwd) && break
done

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
	mkdir -p "$dir"
	ln -s "$top/samples" "$top/tests" "$dir/"
	[ -z "$bunny" ] || ln -s "$bunny" "$dir/bunny"
	examples "$man" | awk -v d="$dir" '/^#@ / { f = d "/ex" $2 ".sh"; next } { print > f }'
	n=0
	for ex in "$dir"/ex*.sh; do
		[ -e "$ex" ] || continue
		n=$((n + 1))
		if [ -z "$bunny" ] && grep -q 'bunny/' "$ex"; then
			echo "man_examples.sh: $page(1) example $n skipped: no ../shared/data/stanford_bunny" >&2
			continue
		fi
		t0=$(date +%s.%N)
		if (cd "$dir" && timeout 300 bash -e -o pipefail "$ex" >/dev/null 2>"$ex.err"); then
			ok
			[ -z "${FCT_EXAMPLES_TIME:-}" ] || echo "$page $n $(echo "$(date +%s.%N) - $t0" | bc)" >&2
		else
			not_ok "$page(1) example $n: $(cat "$ex")
  stderr: $(tail -n 3 "$ex.err")"
		fi
	done
	check_num "$page(1) has examples" "$n" ">" 0
done
finish
