# bash completion for ballfilm(1): commands, each command's options (read
# from its --help), scene files and outputs, and the scene's section.key
# names after --set and --vary (from the program's own key table,
# `ballfilm --complete-keys`).  `make install` puts it in
# PREFIX/share/bash-completion/completions/ballfilm, where Debian's
# bash-completion loads it on first use; `source` it to try it.

# The options that `PROG CMD --help` lists: the words that begin with '-'
# in the first column of its option lines (before the scene keys).
_ballfilm_options()
{
    "$1" "$2" --help 2>/dev/null | awk '
        /^Scene files/ { exit }
        /^ +-/ {
            sub(/^ +/, "")
            n = index($0, "  ")
            s = n ? substr($0, 1, n - 1) : $0
            m = split(s, w, /[ ,]+/)
            for (i = 1; i <= m; i++)
                if (w[i] ~ /^--?[A-Za-z]/)
                    print w[i]
        }'
    printf '%s\n' -h --help
}

# section.key= names for the word $2; a section of several ([ball.N])
# takes the number typed (ball.3.) or 1.
_ballfilm_keys()
{
    local prog=$1 cur=$2 n=1
    [[ $cur =~ ^[a-z_]+\.([0-9]+) ]] && n=${BASH_REMATCH[1]}
    local keys
    keys=$("$prog" --complete-keys 2>/dev/null | sed "s/\.N\./.$n./")
    if [[ $cur != *.* ]]; then
        # first the sections (scene., ball.), then their keys
        keys=$(printf '%s\n' $keys | sed 's/^\([a-z0-9_]*\)\..*/\1./' | sort -u)
        COMPREPLY=($(compgen -W "$keys" -- "$cur"))
    else
        COMPREPLY=($(compgen -W "$(printf '%s=\n' $keys)" -- "$cur"))
    fi
    compopt -o nospace 2>/dev/null
}

_ballfilm()
{
    local cur=${COMP_WORDS[COMP_CWORD]} prev=
    local prog=${COMP_WORDS[0]} cmd= i
    ((COMP_CWORD > 0)) && prev=${COMP_WORDS[COMP_CWORD - 1]}
    COMPREPLY=()
    for ((i = 1; i < COMP_CWORD; i++)); do
        case ${COMP_WORDS[i]} in
            -*) ;;
            *) cmd=${COMP_WORDS[i]}; break ;;
        esac
    done
    if [[ -z $cmd ]]; then
        if [[ $cur == -* ]]; then
            COMPREPLY=($(compgen -W "-h --help -V --version" -- "$cur"))
        else
            COMPREPLY=($(compgen -W "run sweep converge xdmf animate info
                                     export help version" -- "$cur"))
        fi
        return 0
    fi
    # --set=KEY: bash splits the word at '=' (COMP_WORDBREAKS)
    local opt=$prev
    if [[ $prev == = ]] && ((COMP_CWORD > 1)); then
        opt=${COMP_WORDS[COMP_CWORD - 2]}
    elif [[ $cur == = ]]; then
        opt=$prev
        cur=
    fi
    case $opt in
        --set | --vary)
            _ballfilm_keys "$prog" "$cur"
            return 0
            ;;
        -o | --output | --restart)
            COMPREPLY=($(compgen -f -- "$cur"))
            return 0
            ;;
        --field)
            COMPREPLY=($(compgen -W "speed p" -- "$cur"))
            return 0
            ;;
        -j | --jobs | --stop-after | --fps | --frames | --t0 | --t1 | --size | \
            --xlim | --methods | --dt | --tol | --t-end | --rows | --repeats | \
            --ref-rtol | --ref-table | --max-step | --max-steps)
            return 0
            ;;
    esac
    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$(_ballfilm_options "$prog" "$cmd")" \
                     -- "$cur"))
        return 0
    fi
    case $cmd in
        run | sweep | converge)
            COMPREPLY=($(compgen -f -X '!*.ini' -- "$cur")
                       $(compgen -d -- "$cur")) ;;
        xdmf | animate | info | export)
            COMPREPLY=($(compgen -f -X '!*.h5*' -- "$cur")
                       $(compgen -d -- "$cur")) ;;
    esac
    return 0
} &&
    complete -F _ballfilm ballfilm ballfilm-mpi
