# SPDX-License-Identifier: MIT
# Bash completion for keyrot: commands, each command's flags, the values of
# enumerated flags, and files. tests/completion_test.sh checks it against
# the program's own --help, so that the two cannot drift apart.

_keyrot() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD - 1]}
    # --flag=value: bash splits it at '=' into "--flag" "=" "value".
    if [[ $cur == = ]]; then
        cur=""
    elif [[ $prev == = ]] && ((COMP_CWORD >= 2)); then
        prev=${COMP_WORDS[COMP_CWORD - 2]}
    fi
    local commands="resample convert slerp compare info reduce plot help"
    local command="" i
    for ((i = 1; i < COMP_CWORD; i++)); do
        case ${COMP_WORDS[i]} in
            resample | convert | slerp | compare | info | reduce | plot | help) command=${COMP_WORDS[i]}; break ;;
        esac
    done

    local input="--from --strict --key-fps --max-bytes --animation"
    local conventions="--euler --quat-order --radians"
    local output="-o --output --fsync --to --rep --out-euler --out-degrees --out-radians --precision --compact --euler-continuous --settings-line $conventions"
    local interpolation="--method --path"
    local flags
    case $command in
        resample) flags="--output-dir --jobs $input $output $interpolation --fps --max-frames --velocity --acceleration --velocity-frame" ;;
        convert) flags="--output-dir --jobs $input $output" ;;
        slerp) flags="-t --steps --max-frames --from-rep $interpolation $output" ;;
        compare) flags="--tol --tol-translation --tol-velocity --tol-acceleration --ignore-extra --report -o --output --plot --fsync $input $conventions" ;;
        info) flags="-o --output --fsync --to --precision --segments $interpolation $input $conventions" ;;
        reduce) flags="--output-dir --jobs $input $output $interpolation --tol --tol-translation --report --plot" ;;
        plot) flags="-o --output --fsync --rep --out-euler --track --speed $interpolation $input $conventions" ;;
        help) flags="" ;;
        *) flags="--version" ;;
    esac
    [[ $command == help ]] || flags="-h --help $flags"

    local euler="XYZ XZY YXZ YZX ZXY ZYX XYX XZX YXY YZY ZXZ ZYZ xyz xzy yxz yzx zxy zyx xyx xzx yxy yzy zxz zyz"
    local values
    case $prev in
        --from) values="csv json ndjson gltf glb bvh" ;;
        --to) [[ $command == info ]] && values="json" || values="csv json ndjson gltf glb bvh" ;;
        --rep) [[ $command == plot ]] && values="quat euler angle" || values="axis-angle quat rotvec euler matrix matrix4" ;;
        --from-rep) values="quat axis-angle rotvec euler" ;;
        --method) values="slerp nlerp squad step euler cubic" ;;
        --velocity-frame) values="body world" ;;
        --path) values="shortest direct" ;;
        --quat-order) values="wxyz xyzw" ;;
        --report) [[ $command == compare ]] && values="csv json" || values="json" ;;
        --settings-line) values="never always" ;;
        --euler | --out-euler) values=$euler ;;
        -o | --output | --plot)
            COMPREPLY=($(compgen -f -- "$cur"))
            return ;;
        --output-dir)
            COMPREPLY=($(compgen -d -- "$cur"))
            return ;;
        -t | --steps | --fps | --key-fps | --max-frames | --max-bytes | --jobs | --precision | --tol | --tol-translation | \
            --tol-velocity | --tol-acceleration | \
            --animation | --track)
            COMPREPLY=()  # a number, or a name
            return ;;
    esac
    if [[ -n ${values-} && $prev == -* ]]; then
        COMPREPLY=($(compgen -W "$values" -- "$cur"))
        return
    fi

    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$flags" -- "$cur"))
    elif [[ -z $command ]]; then
        COMPREPLY=($(compgen -W "$commands" -- "$cur"))
    elif [[ $command == help ]]; then
        ((COMP_CWORD == i + 1)) && COMPREPLY=($(compgen -W "formats resample convert slerp compare info reduce plot" -- "$cur"))
    elif [[ $command != slerp ]]; then
        COMPREPLY=($(compgen -f -- "$cur"))  # slerp's operands are numbers
    fi
}
complete -o filenames -F _keyrot keyrot
