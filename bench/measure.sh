# Timing helpers shared by bench/run.sh and bench/parts/*.sh (source this file;
# run.sh exports its path as GC_BENCH_LIB).
#
#   gc_measure OUT CMD [ARGS...]
#       Runs CMD with standard output to OUT, GC_BENCH_RUNS times (default 3),
#       and sets GC_SECONDS (the best wall-clock time), GC_CPU_SECONDS (the
#       best user + system CPU time: steadier than wall time on a busy
#       machine) and GC_RSS_KB (the peak resident set size of CMD, largest
#       over the runs; from GNU time).
#       CMD's standard error is kept back and shown only if CMD fails, in
#       which case gc_measure returns 1.
#   gc_row NAME MB_PER_S LINES_PER_S RSS_KB NOTE
#       Prints one row for the summary table that bench/run.sh prints at the
#       end ("-" for a figure that does not apply). A part's other output is
#       shown as it is.
#   gc_rate BYTES_OR_LINES SECONDS [SCALE]
#       Prints BYTES_OR_LINES / SECONDS / SCALE with one decimal.
#   gc_bench_input NAME
#       For a part that runs a filter on the large file and on its first half
#       (memory must stay flat): sets in (GC_BENCH_FILE), in_bytes, in_lines,
#       out (GC_BENCH_TMP/NAME.out) and half (GC_BENCH_TMP/NAME-half.gcode,
#       written: the first half of the lines).

gc_measure() {
  local out=$1
  shift
  local runs=${GC_BENCH_RUNS:-3} best="" cpu="" rss=0 i t0 t1 s r c
  local timefile
  timefile=$(mktemp)
  for ((i = 0; i < runs; i++)); do
    t0=$(date +%s%N)
    if ! /usr/bin/time -f "%M %U %S" -o "$timefile" "$@" >"$out" 2>"$timefile.err"; then
      echo "bench: failed: $*" >&2
      cat "$timefile.err" >&2
      rm -f "$timefile" "$timefile.err"
      return 1
    fi
    t1=$(date +%s%N)
    s=$(((t1 - t0) / 1000))
    read -r r c <<<"$(tail -n 1 "$timefile" | awk '{ printf "%d %d", $1, ($2 + $3) * 1e6 }')"
    if [ -z "$best" ] || [ "$s" -lt "$best" ]; then best=$s; fi
    if [ -z "$cpu" ] || [ "$c" -lt "$cpu" ]; then cpu=$c; fi
    if [ "$r" -gt "$rss" ]; then rss=$r; fi
  done
  rm -f "$timefile" "$timefile.err"
  GC_SECONDS=$(awk -v us="$best" 'BEGIN { printf "%.4f", us / 1e6 }')
  GC_CPU_SECONDS=$(awk -v us="$cpu" 'BEGIN { printf "%.2f", us / 1e6 }')
  GC_RSS_KB=$rss
}

# shellcheck disable=SC2034  # the variables are the caller's
gc_bench_input() {
  in=$GC_BENCH_FILE
  out=$GC_BENCH_TMP/$1.out
  half=$GC_BENCH_TMP/$1-half.gcode
  in_bytes=$(stat -c %s "$in")
  in_lines=$(wc -l <"$in")
  head -n $((in_lines / 2)) "$in" >"$half"
}

gc_rate() {
  awk -v n="$1" -v s="$2" -v k="${3:-1}" 'BEGIN { if (s > 0) printf "%.1f", n / s / k; else print "-" }'
}

gc_row() {
  printf 'BENCH_ROW\t%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" "${5:-}"
}
