# Sourced by the scripts/bench-embree-*.sh side-by-side benchmarks: the Tandem binary ($T,
# or $TANDEM), Embree's tutorial $1 checked for (Debian embree-tools), and the built-in atrium
# exported as OBJ into a temporary folder ($SCENE_DIR/atrium.obj) removed on exit.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
T="${TANDEM:-$ROOT/build/release/apps/tandem/tandem}"
command -v "$1" >/dev/null || { echo "needs Embree's $1 (apt-get install embree-tools)"; exit 1; }
SCENE_DIR="$(mktemp -d)"
trap 'rm -rf "$SCENE_DIR"' EXIT
"$T" export --scene atrium --out "$SCENE_DIR/atrium.obj" >/dev/null
