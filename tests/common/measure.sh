# Sourced by the shell tests that record measured values for docs/verification.md
# (scripts/verification_report.py): the shell twin of pf_test_measure in test_common.c.
# With PF_MEASURE_DIR set (ctest sets it), sourcing this empties $PF_MEASURE_DIR/<test>.tsv
# (<test> is $PF_MEASURE_TEST when set, else the script's name, e.g. calculix_compare), and
# `pf_measure KEY VALUE [UNIT]` appends "KEY<TAB>VALUE<TAB>UNIT" to it. Without PF_MEASURE_DIR
# both do nothing. The document quotes the value as <!--m <test>.<KEY> FORMAT-->value<!--/m-->.
pf_measure_file=""
if [ -n "${PF_MEASURE_DIR:-}" ]; then
  pf_measure_file="$PF_MEASURE_DIR/${PF_MEASURE_TEST:-$(basename "${BASH_SOURCE[1]:-$0}" .sh)}.tsv"
  mkdir -p "$PF_MEASURE_DIR"
  : > "$pf_measure_file"
fi
pf_measure() {
  [ -n "$pf_measure_file" ] || return 0
  printf '%s\t%s\t%s\n' "$1" "$2" "${3:-}" >> "$pf_measure_file"
}
