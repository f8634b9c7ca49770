#!/usr/bin/env bash
# The link graph is the architecture: modeling/ and input/ must never include a Vulkan, GLFW or
# ImGui header. This test fails naming the offending file and line.
set -u
root="${PLANESKETCH_SOURCE_DIR:-$(cd "$(dirname "$0")/.." && pwd)}"
bad=$(grep -rnE '#\s*include\s*[<"](vulkan/|GLFW/|imgui|glm/|volk)' "$root/modeling" "$root/input" 2>/dev/null || true)
if [ -n "$bad" ]; then
  echo "layering violation: modeling/ and input/ must not include GPU/window headers:"
  echo "$bad"
  exit 1
fi
# engine may not include libinput, and modeling may not include input/ or engine/ headers.
bad2=$(grep -rnE '#\s*include\s*[<"](input/|engine/|app/|libinput)' "$root/modeling" 2>/dev/null || true)
if [ -n "$bad2" ]; then
  echo "layering violation: modeling/ includes a higher layer:"; echo "$bad2"; exit 1
fi
bad3=$(grep -rnE '#\s*include\s*[<"](engine/|app/)' "$root/input" 2>/dev/null || true)
if [ -n "$bad3" ]; then
  echo "layering violation: input/ includes engine/ or app/:"; echo "$bad3"; exit 1
fi
echo "layering ok"
