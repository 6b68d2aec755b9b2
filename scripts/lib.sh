# What the scripts share (sourced, after `cd` to the repository root): their usage text, the one
# way they refuse (exit 2 naming the script), and one option parser.
#   lib_usage FIRST LAST       the script's comment lines FIRST..LAST ('# ' stripped); LAST may be
#                              a sed address such as /^#   default:/
#   lib_die MESSAGE...         "SCRIPT: MESSAGE" on stderr, exit 2
#   lib_options SPEC -- ARGS   parses ARGS by SPEC, a list of "--name=VAR" (the next argument is
#                              the value: missing, or another option, is refused), "--name=VAR!"
#                              (a flag: VAR=1) and "@=VAR" (a bare argument); -h/--help runs
#                              $LIB_USAGE (a command) and exits 0; anything else is refused.
lib_usage() { sed -n "$1,${2}p" "$0" | sed 's/^# \{0,1\}//'; }
lib_die() {
  echo "$(basename "$0"): $*" >&2
  exit 2
}
lib_options() {
  local spec=() s name var found
  while (($#)) && [[ $1 != -- ]]; do spec+=("$1"); shift; done
  shift
  while (($#)); do
    if [[ $1 == -h || $1 == --help ]]; then
      ${LIB_USAGE:-lib_usage 2 20}
      exit 0
    fi
    found=0
    for s in "${spec[@]}"; do
      name=${s%%=*} var=${s#*=}
      if [[ $name == @ && $1 != -* ]]; then
        printf -v "$var" '%s' "$1"
      elif [[ $1 != "$name" ]]; then
        continue
      elif [[ $var == *! ]]; then
        printf -v "${var%!}" 1
      else
        [[ $# -ge 2 && -n $2 && $2 != --* ]] || lib_die "$name needs a value (see --help)"
        printf -v "$var" '%s' "$2"
        shift
      fi
      found=1
      break
    done
    ((found)) || lib_die "unknown argument '$1' (see --help)"
    shift
  done
}
