# Every file in tests/bad/ is malformed or hostile: the program that reads it
# must exit 1 with one line "prog: tests/bad/FILE..." on stderr, without
# crashing, hanging or asking for memory the file does not justify.
. tests/lib.sh

# Outside the sanitizer build, cap the address space so that an allocation
# the input does not justify fails loudly ("out of memory") instead of
# quietly succeeding on a big machine.
limit=
[ -z "${FCT_SANITIZE:-}" ] && limit="ulimit -v 524288;"

for f in tests/bad/*; do
	case $f in
	*.png|*.pfm|*.jpg) progs=imginfo ;;
	# well-formed PLY whose plane element lies: every planar stage reads it
	*/planes_*) progs="simpchain projverts tripatch planedecim" ;;
	*) progs=meshconv ;;
	esac
	for prog in $progs; do
		[ -x "$FCT_BIN/$prog" ] || { not_ok "$f: $prog is not built"; continue; }
		run_case 1 "$limit timeout 20 $prog $f >/dev/null" "" "$prog: $f"
		if grep -q "out of memory" "$TMP/err"; then
			not_ok "$f: $(cat "$TMP/err")"
		fi
	done
done
finish
