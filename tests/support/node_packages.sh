# Sourced by the ctest scripts that check uavmot's output with npm packages (tests/*_js/*.sh).
#   require_tools TEST_NAME TOOL...   exits 1 naming the first tool missing
#   install_node_packages DIR         `npm ci` in DIR when node_modules is missing or older than the lock

require_tools() {
  local test_name=$1 tool
  shift
  for tool in "$@"; do
    if ! command -v "$tool" >/dev/null; then
      echo "$test_name: $tool is required (bash tools/install_deps.sh)" >&2
      exit 1
    fi
  done
}

install_node_packages() {
  local dir=$1
  if [[ ! -f "$dir/node_modules/.package-lock.json" || "$dir/package-lock.json" -nt "$dir/node_modules/.package-lock.json" ]]; then
    (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error)
  fi
}
