#!/bin/sh
# One row of tests/cli/guards_table.txt: run `granwave VERB INPUT ARGS` and check its answer.
# usage: expect.sh GRANWAVE SOURCE_DIR TMP_DIR NAME VERB INPUT "ARGS" RC "FRAGMENT && FRAGMENT ..."
gw=$1 src=$2 tmp=$3 name=$4 verb=$5 input=$6 args=$7 rc_expected=$8 fragments=$9
out=$tmp/$name
rm -rf "$out" && mkdir -p "$out"
case $verb in
  run|build|sweep) set -- -o "$out/result.h5" ;;
  *) set -- ;;
esac
# shellcheck disable=SC2086  # ARGS is a list of words
"$gw" "$verb" "$src/$input" "$@" $args > "$out/stdout" 2> "$out/stderr"
rc=$?
cat "$out/stdout" "$out/stderr" > "$out/all"
fail() { echo "FAIL ($name): $1"; echo "--- stdout + stderr:"; head -c 3000 "$out/all"; exit 1; }
[ "$rc" -eq "$rc_expected" ] || fail "exit code $rc, expected $rc_expected"
rest=$fragments
while [ -n "$rest" ]; do
  case $rest in
    *" && "*) frag=${rest%%" && "*}; rest=${rest#*" && "} ;;
    *) frag=$rest; rest= ;;
  esac
  grep -qF -- "$frag" "$out/all" || fail "the answer lacks: $frag"
done
if [ "$rc_expected" -eq 2 ]; then
  # The message names the input file, or the command-line option it refuses.
  grep -qF -- "$input" "$out/stderr" || grep -qE -- '--[a-z-]+ must be' "$out/stderr" ||
    fail "the message names neither the input file $input nor an option"
  [ -z "$(ls -A "$out"/result.h5* 2>/dev/null)" ] || fail "wrote $(ls "$out"/result.h5*)"
  [ ! -s "$out/stdout" ] || [ "$verb" = sweep ] || fail "printed on stdout although refused"
fi
rm -rf "$out"
exit 0
