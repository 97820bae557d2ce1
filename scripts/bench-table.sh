#!/usr/bin/env bash
# Runs the issue-15 benchmarks and prints one table: workload, figure (divan median), goal, met.
#
#   scripts/bench-table.sh            # all workloads (builds the benches in release first)
#   scripts/bench-table.sh picking    # only the rows whose workload or bench matches a word
#
# Figures are divan medians on this machine as it is: note the load average printed at the top and
# run on an idle machine for figures to quote. The drag row runs the loopback example
# (`drag_under_load`, 200 drags under eight heavy clients) and reads its p99. The Monte-Carlo row
# runs the release CLI on examples/pick-montecarlo.toml with 10^6 draws on one thread (wall time).
set -euo pipefail
cd "$(dirname "$0")/.."
only="${1:-}"

# workload | package | bench | divan filter | row label in divan's tree | goal | unit of the figure
# unit: "us"/"ms" compare the median time with the goal; "Mps" compares items/s (M) with the goal.
rows=(
  "law evaluation 10^7 points, cycloidal|loomkin-laws|laws|sample_grid_10m|cycloidal|300|Mps"
  "law evaluation 10^7 points, poly345|loomkin-laws|laws|sample_grid_10m|poly345|300|Mps"
  # Reference rows: the same kernel on 10^4 points (320 KB, in the core's cache), i.e. without the
  # memory traffic that bounds the 10^7 rows (see docs/design/performance.md).
  "law kernel in cache (10^4 points), cycloidal|loomkin-laws|laws|sample_grid_10k|cycloidal|300|Mps"
  "law kernel in cache (10^4 points), poly345|loomkin-laws|laws|sample_grid_10k|poly345|300|Mps"
  "exact metrics, constant-acceleration|loomkin-laws|laws|metrics|constant-acceleration|5|us"
  "exact metrics, harmonic|loomkin-laws|laws|metrics|harmonic|5|us"
  "exact metrics, cycloidal|loomkin-laws|laws|metrics|cycloidal|5|us"
  "exact metrics, poly345|loomkin-laws|laws|metrics|poly345|5|us"
  "exact metrics, poly4567|loomkin-laws|laws|metrics|poly4567|5|us"
  "exact metrics, modified-trapezoid|loomkin-laws|laws|metrics|modified-trapezoid|5|us"
  "exact metrics, modified-sine|loomkin-laws|laws|metrics|modified-sine|5|us"
  "picking, closed form (15.5 mm play)|loomkin-picking|picking|scenario_play|Closed|10|us"
  "picking, ODE (15.5 mm play)|loomkin-picking|picking|scenario_play|Ode|200|us"
  "dobby analysis, 3601 angles|loomkin-mech|dobby|analyze_ellipse_0_1deg|analyze_ellipse_0_1deg|500|us"
  "dobby synthesis with checks, 3601 angles|loomkin-mech|dobby|synthesize_default_0_1deg|synthesize_default_0_1deg|500|us"
  # Reference rows: the same work into an earlier result's tables (`analyze_into`/`synthesize_into`,
  # what the workbench and a sweep do), without the fresh allocation of ~1.6 MB per call.
  "dobby analysis into an earlier result|loomkin-mech|dobby|analyze_ellipse_0_1deg_into|analyze_ellipse_0_1deg_into|500|us"
  "dobby synthesis into an earlier result|loomkin-mech|dobby|synthesize_default_0_1deg_into|synthesize_default_0_1deg_into|500|us"
  "servo optimisation, peak torque, 7 points, 2 speeds|loomkin-servo|servo|optimize_peak|2|30|ms"
  "Pareto front of 10^6 points|loomkin-study|pareto|front_1m_two_objectives|front_1m_two_objectives|50|ms"
  "speed ripple, 3600 angles, constant torque|loomkin-drive|ripple|periodic_solution_3600_angles|constant|1000|us"
  "speed ripple, 3600 angles, induction (Kloss)|loomkin-drive|ripple|periodic_solution_3600_angles|induction|1000|us"
  "speed ripple, 3600 angles, servo|loomkin-drive|ripple|periodic_solution_3600_angles|servo|1000|us"
  "reduced inertia, 24 frames, 10^4 picks|loomkin-loom|inertia|inertia_24_frames_10k_picks|inertia_24_frames_10k_picks|50|ms"
  "electronic shedding, 24 frames, 10^4 picks (twill)|loomkin-eshed|eshed|twill_24_frames_10k_picks|twill_24_frames_10k_picks|50|ms"
)

wanted() { [[ -z "$only" || "$1" == *"$only"* ]]; }

# Median and fastest of one divan row, in the unit asked ("us", "ms") or in M items/s ("Mps").
median() { # output label unit
  awk -v label="$2" -v unit="$3" '
    function num(v) { gsub(/[^0-9.]/, "", v); return v + 0 }
    function tosec(v,   u) {
      u = v; gsub(/[0-9. ]/, "", u)
      if (u == "ns") return num(v) * 1e-9; if (u == "µs" || u == "us") return num(v) * 1e-6
      if (u == "ms") return num(v) * 1e-3; if (u == "s") return num(v); return -1
    }
    function torate(v) {
      if (v ~ /Gitem/) return num(v) * 1e3; if (v ~ /Mitem/) return num(v); if (v ~ /Kitem/) return num(v) * 1e-3
      return num(v) * 1e-6
    }
    {
      # Drop the tree drawing, then split the columns: name and fastest | slowest | median | ...
      line = $0; sub(/^[ ├╰│─]*/, "", line); split(line, c, "│"); split(c[1], w, /[ \t]+/)
      f = (unit == "us") ? 1e6 : 1e3
      if (w[1] == label) { found = 1; if (unit != "Mps") { print tosec(c[3]) * f, tosec(w[2] " " w[3]) * f; exit } ; next }
      if (found && unit == "Mps" && c[3] ~ /item\/s/) { print torate(c[3]), torate(c[1]); exit }
    }' <<<"$1"
}

printf 'load average: %s\n' "$(cut -d' ' -f1-3 /proc/loadavg)"
fmt() { awk -v v="$1" -v u="$2" 'BEGIN {
  if (u == "Mps") printf "%.0f M/s", v; else if (u == "us" && v >= 1000) printf "%.3g ms", v / 1000;
  else printf "%.3g %s", v, (u == "us") ? "µs" : u }'; }
printf '%-52s %12s %12s %12s  %s\n' "workload" "median" "fastest" "goal" "met (median)"
declare -A done_out
for r in "${rows[@]}"; do
  IFS='|' read -r work pkg bench filter label goal unit <<<"$r"
  wanted "$work $bench" || continue
  key="$pkg/$bench/$filter"
  if [[ -z "${done_out[$key]:-}" ]]; then
    done_out[$key]="$(cargo bench -q -p "$pkg" --bench "$bench" -- "$filter" 2>/dev/null || true)"
  fi
  read -r fig fast <<<"$(median "${done_out[$key]}" "$label" "$unit")"
  if [[ -z "${fig:-}" ]]; then
    printf '%-52s %12s %12s %12s  %s\n' "$work" "n/a" "n/a" "$goal $unit" "not measured"
    continue
  fi
  if [[ "$unit" == "Mps" ]]; then
    met=$(awk -v f="$fig" -v g="$goal" 'BEGIN { print (f >= g) ? "yes" : "no" }')
    goal_txt="≥ $goal M/s"
  else
    met=$(awk -v f="$fig" -v g="$goal" 'BEGIN { print (f < g) ? "yes" : "no" }')
    goal_txt="< $(fmt "$goal" "$unit")"
  fi
  printf '%-52s %12s %12s %12s  %s\n' "$work" "$(fmt "$fig" "$unit")" "$(fmt "$fast" "$unit")" "$goal_txt" "$met"
done

if wanted "picking Monte-Carlo montecarlo"; then
  study="$(mktemp)"
  sed 's/^draws = .*/draws = 1000000/' examples/pick-montecarlo.toml >"$study"
  cargo build -q --release -p loomkin-cli 2>/dev/null || true
  bin="$(cargo metadata -q --format-version 1 --no-deps 2>/dev/null |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')/release/loomkin"
  start=$(date +%s.%N)
  if RAYON_NUM_THREADS=1 "$bin" pick montecarlo "$study" --json >/dev/null 2>&1; then
    s=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    met=$(awk -v f="$s" 'BEGIN { print (f < 10) ? "yes" : "no" }')
    printf '%-52s %12s %12s %12s  %s\n' "picking Monte-Carlo, 10^6 draws, closed form, 1 core" "$s s" "-" "< 10 s" "$met"
  else
    printf '%-52s %12s %12s %12s  %s\n' "picking Monte-Carlo, 10^6 draws, closed form, 1 core" "n/a" "-" "< 10 s" "not measured"
  fi
  rm -f "$study"
fi

if wanted "workbench drag update p99 web"; then
  line="$(cargo run -q --release -p loomkin-web --example drag_under_load -- 200 2>/dev/null | grep 'p99' || true)"
  p99="$(sed -n 's/.*p99 \([0-9.]*\) ms.*/\1/p' <<<"$line")"
  if [[ -n "$p99" ]]; then
    met=$(awk -v f="$p99" 'BEGIN { print (f < 2) ? "yes" : "no" }')
    printf '%-52s %12s %12s %12s  %s\n' "workbench drag p99, loopback, under load" "$p99 ms" "-" "< 2 ms" "$met"
  else
    printf '%-52s %12s %12s %12s  %s\n' "workbench drag p99, loopback" "n/a" "-" "< 2 ms" "not measured"
  fi
fi
