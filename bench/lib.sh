# The opening shared by the whole-process timing scripts of bench/, sourced by each:
#   source "$(dirname "$0")/lib.sh"
#   bench_init NAME DEFAULT_RUNS "$@"   # root, build (1st argument), runs (2nd), kimp, records
#   bench_require fem time              # what the script needs, else an error naming NAME
#   bench_workdir                       # work: a temporary directory removed on exit
# shellcheck shell=bash disable=SC2034  # the variables are the sourcing script's

bench_init() {
  bench_name="$1"
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  build="${3:-$root/build}"
  runs="${4:-$2}"
  kimp="$build/kimp"
  records="${KIMP_RECORDS_DIR:-$root/../shared/data/records}"
}

# bench_require NEED...: kimp (always); fem: also kimp-fem, run as root under MPI; time:
# /usr/bin/time; records FILE: the PEER record FILE in $records.
bench_require() {
  local with_fem=""
  [[ " $* " == *" fem "* ]] && with_fem=" (with FEM)"
  [[ -x "$kimp" && ( -z "$with_fem" || -x "$build/kimp-fem" ) ]] ||
    { echo "$bench_name: build the target kimp$with_fem in $build" >&2; exit 1; }
  while (($#)); do
    case "$1" in
      fem)
        export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
               OMPI_MCA_rmaps_base_oversubscribe=1 ;;
      time)
        [[ -x /usr/bin/time ]] ||
          { echo "$bench_name: needs /usr/bin/time (Debian package time)" >&2; exit 1; } ;;
      records)
        shift
        [[ -f "$records/$1" ]] ||
          { echo "$bench_name: $1 not in $records (set KIMP_RECORDS_DIR)" >&2; exit 1; } ;;
    esac
    shift
  done
}

bench_workdir() {
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
}
