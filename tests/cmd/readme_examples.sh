# The README's example commands run as written: every indented code block
# whose first word is one of facet's programs, in order, in one scratch
# folder holding the tree's samples/ and tests/ and bunny/ (the Stanford
# scans, ../shared/data/stanford_bunny) when present, with bash -e -o
# pipefail.  Blocks that are not facet commands (make, a Makefile rule, GNU
# parallel, a Slurm script, the layout) are named and left out; a block
# that needs bunny/ without it is skipped with a message.
. tests/lib.sh

progs=" $(cd man/man1 && ls ./*.1 | sed 's|^\./||; s|\.1$||' | tr '\n' ' ')"

dir=$TMP/readme
scratch_with_tree "$dir"
# Each indented block after a blank line to its own file, the indent gone.
awk -v d="$dir" '
	/^(    |\t)/ && (blank || inblock) { if (!inblock) f = d "/block" sprintf("%02d", ++n) ".sh";
		inblock = 1; sub(/^(    |\t)/, ""); print > f; next }
	{ inblock = 0; blank = ($0 ~ /^[ \t]*$/) }
	' README.md
n=0
for b in "$dir"/block*.sh; do
	first=$(head -n 1 "$b")
	word=${first%% *}
	case $progs in
	*" $word "*) ;;
	*) echo "readme_examples.sh: not a facet command, left out: $first" >&2; continue ;;
	esac
	n=$((n + 1))
	if [ -z "$bunny" ] && grep -q 'bunny/' "$b"; then
		echo "readme_examples.sh: skipped, no ../shared/data/stanford_bunny: $first" >&2
		continue
	fi
	run_example "$dir" "$b"
	st=$?
	if [ "$st" = 0 ]; then
		ok
	else
		example_failed "README block $n (exit $st)" "$b"
	fi
done
check_num "README blocks run" "$n" ">=" 8
finish
