#!/usr/bin/env bash
# PackageHeaders (docs/library.md): every public header, as installed, compiles on its own (it includes what
# it uses), with -Wall -Wextra -Werror, against the installed include folder alone plus the system's. Unity
# batches in the build would hide a header that leans on what an earlier file included; a program that
# includes one Sylva header first would not.
# Usage: headers-test.sh BUILD_DIR [JOBS]
set -euo pipefail
build="$(cd "$1" && pwd)"
jobs="${2:-2}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" --component dev >/dev/null
include="$work/prefix/include"
cd "$include"
mapfile -t headers < <(find sylva -name '*.hpp' | sort)
[ ${#headers[@]} -gt 100 ] || { echo "PackageHeaders: only ${#headers[@]} headers installed" >&2; exit 1; }
# Third-party include folders the headers may reach (OpenCV and ImGui install outside the default path).
export CHECK_FLAGS="-std=c++20 -fsyntax-only -Wall -Wextra -Wpedantic -Werror -I$include -I$include/sylva/shaders
  -I/usr/include/imgui -I/usr/include/opencv4"
printf '%s\n' "${headers[@]}" | xargs -P "$jobs" -I{} sh -c \
  'printf "#include <%s>\n" "{}" | ${CXX:-c++} $CHECK_FLAGS -x c++ - >"'"$work"'/$(echo {} | tr / _).log" 2>&1 ||
   echo "{}" >>"'"$work"'/failed"'
if [ -f "$work/failed" ]; then
  while read -r h; do
    echo "PackageHeaders: $h does not compile on its own:" >&2
    grep -m 3 -E "error|warning" "$work/$(echo "$h" | tr / _).log" >&2 || true
  done <"$work/failed"
  exit 1
fi
echo "PackageHeaders: all ${#headers[@]} installed headers compile on their own"
