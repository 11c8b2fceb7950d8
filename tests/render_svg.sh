#!/usr/bin/env bash
# Renders SVG diagrams (`sitlogc graph`) to PNG with headless Chromium, at
# the size the SVG declares, so that a person can look at them.
#
#   tests/render_svg.sh IN.svg OUT.png      one file
#   tests/render_svg.sh                     docs/graph/*.png from the examples
#
# Skips cleanly (exit 0, a message) when Chromium is not installed
# (Debian: apt-get install chromium fonts-dejavu-core).
set -euo pipefail
cd "$(dirname "$0")/.."
CHROMIUM="$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)"
if [ -z "$CHROMIUM" ]; then
    echo "render_svg.sh: no chromium found; skipped"
    exit 0
fi
render() {
    local svg="$1" png="$2" w h
    w=$(grep -o 'width="[0-9.]*"' "$svg" | head -1 | grep -o '[0-9.]*')
    h=$(grep -o 'height="[0-9.]*"' "$svg" | head -1 | grep -o '[0-9.]*')
    "$CHROMIUM" --headless --no-sandbox --disable-gpu --hide-scrollbars \
        --window-size="${w%.*},${h%.*}" --screenshot="$png" "file://$(realpath "$svg")" >/dev/null 2>&1
    echo "wrote $png (${w%.*}x${h%.*})"
}
if [ $# -eq 2 ]; then
    render "$1" "$2"
    exit 0
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cargo run -q --bin sitlogc -- graph dms/examples/appendix_a -o "$tmp/appendix_a.svg"
render "$tmp/appendix_a.svg" docs/graph/appendix_a.png
cargo run -q --bin sitlogc -- graph cli/tests/graph/shapes -o "$tmp/shapes.svg"
render "$tmp/shapes.svg" docs/graph/shapes.png
cargo run -q --bin sitlogc -- graph dms/apps/home --dm main -o "$tmp/home_main.svg"
render "$tmp/home_main.svg" docs/graph/home_main.png
cargo run -q --bin sitlogc -- graph dms/apps/home --overview -o "$tmp/home_overview.svg"
render "$tmp/home_overview.svg" docs/graph/home_overview.png
