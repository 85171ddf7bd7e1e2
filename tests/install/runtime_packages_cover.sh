#!/usr/bin/env bash
# The Docker image's run stage installs only `scripts/install_deps.sh --runtime`: every shared library the installed
# programs load must come from one of those packages or from a package they depend on.
# Usage: runtime_packages_cover.sh PREFIX SOURCE_DIR [PACKAGE_TO_LEAVE_OUT]  (the last: to see the check fail)
set -euo pipefail
prefix="$1"
src="$2"
leave_out="${3:-}"
runtime="$(sed -n '/^RUNTIME_PACKAGES=(/,/^)/p' "$src/scripts/install_deps.sh" | sed '1d;$d' | tr -s ' \n' '\n' |
  grep -v '^$' | grep -vx "${leave_out:-^$}")"
# What apt installs for that list: the packages and all their dependencies.
covered="$( (echo "$runtime"; apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts --no-breaks \
  --no-replaces --no-enhances $runtime 2> /dev/null | grep -v '^[ <]') | sed 's/:.*//' | sort -u)"
libs="$(for exe in "$prefix"/bin/*; do
  [ "$(head -c 4 "$exe" | od -An -c | tr -d ' ')" = '177ELF' ] && ldd "$exe" | awk '/=> \// {print $3}'
done | xargs -r readlink -f | sort -u)"
status=0
while read -r lib; do
  owner="$(dpkg -S "$lib" 2> /dev/null | head -1 | sed 's/:.*//')" ||
    owner="$(dpkg -S "${lib/#\/usr/}" 2> /dev/null | head -1 | sed 's/:.*//')" || true
  if [ -z "$owner" ]; then
    echo "$lib belongs to no Debian package"
    status=1
  elif ! grep -qx "$owner" <<< "$covered"; then
    echo "$lib comes from $owner, which install_deps.sh --runtime does not bring"
    status=1
  fi
done <<< "$libs"
echo "$(wc -l <<< "$libs") shared libraries of $prefix/bin; runtime packages: $(wc -w <<< "$runtime") listed," \
  "$(wc -l <<< "$covered") with their dependencies"
exit "$status"
