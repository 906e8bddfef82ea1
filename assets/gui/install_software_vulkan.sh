#!/usr/bin/env bash
# Xvfb and Mesa's software Vulkan driver (lavapipe) for running the explorer without a GPU.
# Mesa before 23 (Debian 12 ships 22.3.6) compiles a new shader for every draw whose uniforms
# it inlines and never frees it: the embedded Rerun viewer then grows by megabytes per frame
# (measured 2.5 MiB per frame, 17 MiB/s while a scene plays). On Debian 12 this installs
# Mesa from bookworm-backports (25.0 when written), which does not leak.
set -euo pipefail
apt_install() {
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@"
}
version() { dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true; }
if ! command -v Xvfb >/dev/null 2>&1; then
  apt-get update -qq
  apt_install xvfb
fi
current="$(version)"
if [ -n "$current" ] && dpkg --compare-versions "$current" ge 23; then
  echo "mesa-vulkan-drivers $current"
  exit 0
fi
codename="$(. /etc/os-release && echo "${VERSION_CODENAME:-}")"
if [ "$codename" = bookworm ]; then
  echo "deb http://deb.debian.org/debian bookworm-backports main" \
    > /etc/apt/sources.list.d/flexmodes-bookworm-backports.list
  apt-get update -qq
  apt_install -t bookworm-backports mesa-vulkan-drivers
else
  apt-get update -qq
  apt_install mesa-vulkan-drivers
fi
current="$(version)"
echo "mesa-vulkan-drivers $current"
if dpkg --compare-versions "$current" lt 23; then
  echo "warning: Mesa $current leaks a shader per draw; the explorer's memory will grow" >&2
fi
