#!/usr/bin/env bash
# compare_runs.sh BIN_A BIN_B [WORKDIR] [NAME-REGEX]
#
# Runs every case of tests/compare/cases.txt with two ballfilm binaries and
# compares, case by case, the exit statuses and every dataset (and root
# attribute) of the files written, bit for bit (tests/compare/h5same.py).
# This is how a refactor proves that it changed no result: build the
# commit before it in a directory of your choice, DIR, e.g.
#   git worktree add DIR HEAD~1 && make -C DIR
#   tests/compare/compare_runs.sh DIR/bin/ballfilm bin/ballfilm
# Run from the repository root.  Exit 0 when every case is the same, or
# differs only where cases.txt declares it with a line
#   !differs NAME: why (the commit that changed it on purpose)
# (a change of results made by its own commit, not by a refactor); such a
# case is listed as "expected" and, if it turns out the same, as that.
# A line
#   !ulps N DATASET...: why (the commit)
# lets the named datasets of every case differ by at most N units in the
# last place (h5same.py --ulps): a change of rounding only, declared.
# A line
#   !default KEY...: why (the commit)
# lets the recorded value of scene keys whose default changed on purpose
# differ where both runs left them at their default (h5same.py
# --new-default); the datasets are compared as always.
set -u
if [ $# -lt 2 ]; then
    echo "usage: $0 BIN_A BIN_B [WORKDIR] [NAME-REGEX]" >&2
    exit 2
fi
A=$(readlink -f "$1")
B=$(readlink -f "$2")
W=${3:-build/compare}
FILTER=${4:-.}
HERE=$(dirname "$0")
PY=/usr/bin/python3
rm -rf "$W/a" "$W/b"
mkdir -p "$W/a" "$W/b"

# run_side BIN DIR: every case into DIR (exit statuses in DIR/NAME.rc)
run_side() {
    local bin=$1 dir=$2 name cmds cmd rc
    while IFS= read -r line; do
        case "$line" in ''|'#'*|'!'*) continue ;; esac
        name=${line%%:*}
        [[ $name =~ $FILTER ]] || continue
        cmds=${line#*: }
        rc=""
        while [ -n "$cmds" ]; do
            cmd=${cmds%% ;; *}
            if [ "$cmd" = "$cmds" ]; then cmds=""; else cmds=${cmds#* ;; }; fi
            cmd=${cmd//@OUT/$dir/$name}
            eval "\"$bin\" $cmd" > "$dir/$name.log" 2>&1
            rc="$rc $?"
        done
        echo "$rc" > "$dir/$name.rc"
    done < "$HERE/cases.txt"
}

run_side "$A" "$W/a" &
pid=$!
run_side "$B" "$W/b"
wait $pid

ncase=0
ndiff=0
nexpect=0
# the --ulps arguments of h5same.py from the !ulps lines
ULPS=()
while IFS= read -r line; do
    spec=${line#!ulps }
    spec=${spec%%:*}
    read -r n names <<< "$spec"
    for d in $names; do ULPS+=(--ulps "$d=$n"); done
done < <(grep '^!ulps ' "$HERE/cases.txt")
while IFS= read -r line; do
    spec=${line#!default }
    for k in ${spec%%:*}; do ULPS+=(--new-default "$k"); done
done < <(grep '^!default ' "$HERE/cases.txt")
# expected NAME: the reason declared in cases.txt, or nothing
expected() {
    sed -n "s/^!differs $1: //p" "$HERE/cases.txt"
}
for rcfile in "$W"/a/*.rc; do
    name=$(basename "$rcfile" .rc)
    ncase=$((ncase + 1))
    msg=""
    if ! cmp -s "$rcfile" "$W/b/$name.rc"; then
        msg="exit status $(cat "$rcfile") vs $(cat "$W/b/$name.rc" 2>/dev/null)"
    fi
    files=()
    [ -f "$W/a/$name.h5" ] && files+=("$name.h5")
    if [ -d "$W/a/$name.d" ]; then
        for f in "$W/a/$name.d"/*.h5; do files+=("$name.d/$(basename "$f")"); done
    fi
    for f in "${files[@]}"; do
        if [ ! -f "$W/b/$f" ]; then
            msg="$msg; $f missing"
        elif ! out=$($PY "$HERE/h5same.py" "$W/a/$f" "$W/b/$f" "${ULPS[@]}"); then
            msg="$msg; $f:"$'\n'"$out"
        fi
    done
    why=$(expected "$name")
    if [ -n "$msg" ] && [ -n "$why" ]; then
        nexpect=$((nexpect + 1))
        echo "expected $name differs: $why"
        echo "         ${msg#; }" | head -3
    elif [ -n "$msg" ]; then
        ndiff=$((ndiff + 1))
        echo "DIFFERS  $name: $msg"
    else
        echo "same     $name (${#files[@]} files, exit$(cat "$rcfile"))"
    fi
done
echo "compare_runs: $ncase cases, $((ncase - ndiff - nexpect)) the same," \
    "$nexpect differ as declared, $ndiff differ"
[ $ndiff -eq 0 ]
