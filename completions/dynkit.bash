# SPDX-License-Identifier: BSD-3-Clause
# bash completion of dynkit (bash-completion's programmable completion, `complete -F`):
# commands; each command's options, read from its --help (so they follow the installed
# dynkit); model names (`dynkit models`) and model files (.ode, .mech, .c, .so); method names
# (`dynkit methods`, with aliases and MATLAB's ode45, ode23, ode15s, ode23s); parameter and
# state names for --set and --init (`dynkit info MODEL`); the values of --end, --interp and
# --header; files for --output, --forces and --events-output.
# Installed by `cmake --install` into share/bash-completion/completions/dynkit; or
# `source completions/dynkit.bash`.

_dynkit_commands="run models methods info inverse report animate plot verify sweep linearize derive equilibria lyapunov steady continue bvp help"

# The options of a command, from its --help (cached per command for the shell's life).
declare -gA _dynkit_options_cache 2>/dev/null || true
_dynkit_options() {
    local cmd=$1 prog=$2
    if [[ -z ${_dynkit_options_cache[$cmd]+set} ]]; then
        # the lines that define options: "  --name ..." or "  -o, --name ..."
        _dynkit_options_cache[$cmd]=$("$prog" "$cmd" --help 2>/dev/null |
            grep -oE '^  (-[a-z], )?--[a-z][a-z0-9-]*' | grep -oE -- '--?[a-z][a-z0-9-]*' |
            sort -u | tr '\n' ' ')
        _dynkit_options_cache[$cmd]+=" --help --verbose"
    fi
    printf '%s' "${_dynkit_options_cache[$cmd]}"
}

_dynkit_models() {
    "$1" models 2>/dev/null | awk 'NR > 1 { print $1 }'
}

_dynkit_methods() {
    "$1" methods 2>/dev/null | awk 'NR > 1 { print $1; if ($2 != "-") print $2 }'
    printf '%s\n' ode15s ode23s
}

# NAME= of the parameters (--set) or states (--init) of a model.
_dynkit_names() {
    local prog=$1 model=$2 section=$3
    "$prog" info "$model" 2>/dev/null |
        awk -v s="$section" '/^[A-Z]/ { on = index($0, s) == 1 } on && /^  [^ ]/ { print $1 "=" }'
}

_dynkit_files() {
    # model files and directories (the pattern needs extglob, on under bash-completion)
    local IFS=$'\n' restore=""
    shopt -q extglob || { shopt -s extglob; restore=1; }
    COMPREPLY+=($(compgen -d -- "$1"))
    COMPREPLY+=($(compgen -f -X "!*.@(${2:-ode|mech|c|so})" -- "$1"))
    [[ -n $restore ]] && shopt -u extglob
    return 0
}

_dynkit() {
    local cur prev prog cmd i model
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD - 1]}
    prog=${COMP_WORDS[0]}
    COMPREPLY=()
    # the command: the first word after dynkit that is not an option
    cmd=""
    for ((i = 1; i < COMP_CWORD; i++)); do
        if [[ ${COMP_WORDS[i]} != -* ]]; then
            cmd=${COMP_WORDS[i]}
            break
        fi
    done
    if [[ -z $cmd ]]; then
        COMPREPLY=($(compgen -W "$_dynkit_commands --help --version --verbose" -- "$cur"))
        return 0
    fi
    # the model: the word after run/info/animate/plot
    model=""
    if ((i + 1 < COMP_CWORD)); then
        model=${COMP_WORDS[i + 1]}
    fi
    case $prev in
    -m | --method | --compare)
        COMPREPLY=($(compgen -W "$(_dynkit_methods "$prog")" -- "$cur"))
        return 0
        ;;
    -o | --output | --events-output | --html)
        compopt -o filenames 2>/dev/null
        COMPREPLY=($(compgen -f -- "$cur"))
        return 0
        ;;
    --forces | --from | --resume)
        compopt -o filenames 2>/dev/null
        COMPREPLY=($(compgen -d -- "$cur") $(compgen -f -X '!*.[cC][sS][vV]' -- "$cur"))
        return 0
        ;;
    --ani)
        compopt -o filenames 2>/dev/null
        COMPREPLY=($(compgen -d -- "$cur") $(compgen -f -X '!*.ani' -- "$cur"))
        return 0
        ;;
    --end)
        COMPREPLY=($(compgen -W "exact grid" -- "$cur"))
        return 0
        ;;
    --interp)
        COMPREPLY=($(compgen -W "hold linear" -- "$cur"))
        return 0
        ;;
    --header)
        COMPREPLY=($(compgen -W "names units none" -- "$cur"))
        return 0
        ;;
    --problem)
        COMPREPLY=($(compgen -W "vanderpol-mu1 arenstorf oscillator vanderpol-mu1000 robertson hires" -- "$cur"))
        return 0
        ;;
    --set | --init)
        local section=Parameters
        [[ $prev == --init ]] && section=States
        [[ $cmd == inverse ]] && model=cart
        compopt -o nospace 2>/dev/null
        COMPREPLY=($(compgen -W "$(_dynkit_names "$prog" "$model" "$section")" -- "$cur"))
        return 0
        ;;
    --step | --tspan | --rtol | --atol | --times | --max-step | --initial-step | --max-steps | \
        --every | --trace | --event | --x | --y | --title | --vary | --sample | --runs | \
        --seed | --reduce | --threads | --t)
        return 0
        ;;
    --jacobian)
        COMPREPLY=($(compgen -W "auto analytic central richardson" -- "$cur"))
        return 0
        ;;
    esac
    case $cmd in
    help)
        ((COMP_CWORD == i + 1)) &&
            COMPREPLY=($(compgen -W "$_dynkit_commands" -- "$cur"))
        return 0
        ;;
    run | info | animate | plot | sweep | linearize | equilibria | lyapunov | steady | continue)
        if ((COMP_CWORD == i + 1)); then
            compopt -o filenames 2>/dev/null
            COMPREPLY=($(compgen -W "$(_dynkit_models "$prog")" -- "$cur"))
            if [[ $cmd == plot ]]; then # or a sweep's table
                _dynkit_files "$cur" "ode|mech|c|so|csv|json"
            else
                _dynkit_files "$cur"
            fi
            return 0
        fi
        ;;
    derive)
        if ((COMP_CWORD == i + 1)); then
            compopt -o filenames 2>/dev/null
            COMPREPLY=()
            _dynkit_files "$cur" mech
            return 0
        fi
        ;;
    bvp)
        if ((COMP_CWORD == i + 1)); then
            compopt -o filenames 2>/dev/null
            COMPREPLY=()
            _dynkit_files "$cur" ode
            return 0
        fi
        ;;
    inverse)
        if ((COMP_CWORD == i + 1)); then
            COMPREPLY=($(compgen -W "cart" -- "$cur"))
            return 0
        fi
        ;;
    esac
    COMPREPLY=($(compgen -W "$(_dynkit_options "$cmd" "$prog")" -- "$cur"))
    return 0
}

complete -F _dynkit dynkit
