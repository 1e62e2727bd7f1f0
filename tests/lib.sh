# tests/lib.sh - helpers for the command tests in tests/cmd/*.sh.
#
# A test script sources this file and calls run_case / check_* ; each call
# counts one pass or one failure.  The runner reads the closing line.
#
#   run_case STATUS "command" [stdout-file|""] [stderr-prefix]
#       runs the command with sh, from the top folder, with $FCT_BIN first
#       in PATH; checks the exit status, the exact stdout (when a file is
#       named; "" skips) and that stderr is one line starting with the prefix
#       (when given; for non-zero status the one-line rule always holds).
#       A stdout file in tests/cmd/expected is a golden file: make regold
#       rewrites it (see regold below).

: "${FCT_BIN:=build/bin}"
case $FCT_BIN in /*) ;; *) FCT_BIN=$(pwd)/$FCT_BIN ;; esac
PATH=$FCT_BIN:$PATH
export PATH FCT_BIN
TMP=$(mktemp -d "${TMPDIR:-/tmp}/facet-test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
pass=0
fail=0

ok() { pass=$((pass + 1)); }
not_ok() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

run_case() {
	want_status=$1 cmd=$2 want_out=${3:-} want_err=${4:-}
	sh -c "$cmd" >"$TMP/out" 2>"$TMP/err"
	st=$?
	if [ "$st" != "$want_status" ]; then
		not_ok "$cmd: exit status $st, expected $want_status; stderr: $(head -c 300 "$TMP/err")"
		return
	fi
	case $want_out in tests/cmd/expected/*) regold "$TMP/out" "$want_out" ;; esac
	if [ -n "$want_out" ] && ! cmp -s "$TMP/out" "$want_out"; then
		not_ok "$cmd: output differs from $want_out"
		return
	fi
	if [ "$want_status" != 0 ]; then
		lines=$(wc -l <"$TMP/err")
		if [ "$lines" != 1 ]; then
			not_ok "$cmd: stderr has $lines lines, expected one: $(head -c 300 "$TMP/err")"
			return
		fi
	fi
	if [ -n "$want_err" ]; then
		case $(cat "$TMP/err") in
		"$want_err"*) ;;
		*) not_ok "$cmd: stderr \"$(head -c 300 "$TMP/err")\" does not start with \"$want_err\""; return ;;
		esac
	fi
	ok
}

# regold GOT GOLDEN: nothing in a test run.  Under make regold (tests/regold
# sets FCT_REGOLD to its log) GOT, this build's output, replaces the golden
# file GOLDEN, and the log says whether that changed it.  Golden files are
# the programs' own outputs kept for comparison; expected outputs computed
# another way (by hand, by a generator script, by another decoder) are not
# golden and are never rewritten.
regold() {
	[ -n "${FCT_REGOLD:-}" ] || return 0
	if [ ! -s "$1" ]; then
		echo "no-output $2" >>"$FCT_REGOLD"
		return 1
	elif cmp -s "$1" "$2"; then
		echo "unchanged $2" >>"$FCT_REGOLD"
	else
		cp "$1" "$2" && echo "changed $2" >>"$FCT_REGOLD"
	fi
}

# check_true "description" command...: passes when the command succeeds.
check_true() {
	desc=$1
	shift
	if "$@"; then ok; else not_ok "$desc"; fi
}

# holds VALUE OP REF: numeric comparison with awk (OP: < <= > >= == !=), as a
# status; a VALUE that is not a number holds nothing.
holds() {
	awk -v a="$1" -v b="$3" -v op="$2" 'BEGIN {
		if (a !~ /^[-+0-9.eEinfa]+$/) exit 1
		if (op == "<") exit !(a + 0 < b + 0); if (op == "<=") exit !(a + 0 <= b + 0)
		if (op == ">") exit !(a + 0 > b + 0); if (op == ">=") exit !(a + 0 >= b + 0)
		if (op == "==") exit !(a + 0 == b + 0); if (op == "!=") exit !(a + 0 != b + 0); exit 1 }'
}

# check_num "description" VALUE OP REF: passes when holds VALUE OP REF.
check_num() {
	if holds "$2" "$3" "$4"; then ok; else not_ok "$1: $2 $3 $4 does not hold"; fi
}

# xfail "description" command...: a check known to fail today, a bug
# reported to the lead.  It counts as passed while it fails (saying so on
# stderr), and fails once it holds: delete the mark then, and keep the
# check.  The margins asserted beside it catch a worse failure.
xfail() {
	desc=$1
	shift
	if "$@"; then
		not_ok "$desc now holds: remove its expected-failure mark (xfail) in $0"
	else
		echo "$(basename "$0"): expected failure: $desc" >&2
		ok
	fi
}

# scratch_with_tree DIR: make DIR for documented examples, holding the
# tree's samples/ and tests/, and bunny/ (the Stanford scans of
# ../shared/data/stanford_bunny, not in the repository) when present; sets
# $bunny to that folder, or empty.
scratch_with_tree() {
	bunny=
	for d in ../shared/data/stanford_bunny /work/shared/data/stanford_bunny; do
		[ -f "$d/data/bun.conf" ] && bunny=$(cd "$d" && pwd) && break
	done
	mkdir -p "$1"
	ln -s "$(pwd)/samples" "$(pwd)/tests" "$1/"
	[ -z "$bunny" ] || ln -s "$bunny" "$1/bunny"
}

# run_example DIR SCRIPT: run a documented example in DIR with bash -e -o
# pipefail (a stage failing inside a pipe counts), 300 s at most, stdout
# dropped, stderr in SCRIPT.err; its status.  example_failed DESC SCRIPT
# reports it failed, with its text and the end of its stderr.
run_example() {
	(cd "$1" && timeout 300 bash -e -o pipefail "$2" >/dev/null 2>"$2.err")
}
example_failed() {
	not_ok "$1: $(cat "$2")
  stderr: $(tail -n 3 "$2.err")"
}

# The closing line the runner sums.
finish() {
	echo "$(basename "$0"): $pass passed, $fail failed"
	[ "$fail" = 0 ]
}
