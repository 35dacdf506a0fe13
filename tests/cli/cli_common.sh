# The shared start of the CLI test scripts (test_cli.sh, test_cli_failures.sh, test_resume.sh):
# the program under test (exe), a scratch folder removed on exit (work), the check counter, and a
# small valid case (good_case). Usage: source cli_common.sh PATH_TO_UNSATMPM
set -u
exe=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
pass=0

check() {  # check NAME CONDITION...
  local name=$1; shift
  if "$@"; then pass=$((pass + 1)); else echo "FAIL: $name" >&2; fails=$((fails + 1)); fi
}

good_case() {
  cat <<'YAML'
name: tiny
dimension: 1
grid: {origin: [0.0], size: [1.0], cells: [10]}
shape_function: linear
gravity: [-9.81]
materials:
  - {name: soil, density: 1800, model: linear_elastic, young_modulus: 1.0e7, poisson_ratio: 0.3}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0.0], max: [0.5]}}
boundaries:
  - {name: base, plane: {axis: x, at: 0.0}, mechanical: fixed}
solver: {end_time: 0.01, damping: 0.1}
output: {times: [0.005]}
YAML
}

