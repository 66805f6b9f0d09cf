#!/usr/bin/env bash
# The Debian package: builds kew_<version>_<arch>.deb with dpkg-buildpackage
# from a copy of this tree, checks what it contains and runs lintian on it; then, only
# when the environment says CI=true and we are root (never on a user's machine), installs
# it with dpkg -i, checks the installed service, configuration, manual page and tools, and
# purges it, checking that nothing is left.
#   bash tests/package/test_deb.sh [WORK_DIR]
# WORK_DIR (default ${TMPDIR:-/tmp}/kew-deb-$UID) is emptied first; a fixed path lets
# ccache find the previous run's objects (dpkg-buildflags put the path in the flags).
set -euo pipefail

here=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:-${TMPDIR:-/tmp}/kew-deb-$(id -u)}
version=$(sed -n '1s/^kew (\([^)]*\)).*/\1/p' "$here/debian/changelog")
arch=$(dpkg --print-architecture)
deb=$work/kew_${version}_${arch}.deb

fail() { echo "test_deb: FAIL: $*" >&2; exit 1; }

# The tree as git sees it (tracked and new files, not the build trees), without .git, as
# a source package is built: kewd then names the package's own version as its revision.
rm -rf "$work"
mkdir -p "$work/kew"
(cd "$here" && git ls-files -z --cached --others --exclude-standard |
   while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
   tar --null -T - -cf -) | tar -C "$work/kew" -xf -
revision=debian-$version

# With warnings as errors: the package's build type (dpkg-buildflags: -O2, hardening) is
# the second one the test command builds. Through ccache (CMake finds it; dpkg-buildpackage
# and debhelper pass these through): paths below the copy hashed relative to it.
echo "test_deb: dpkg-buildpackage in $work/kew (no git: revision $revision expected)"
export CCACHE_DIR=${CCACHE_DIR:-$HOME/.cache/kew-ccache}
export CCACHE_BASEDIR=$work/kew
export CCACHE_NOHASHDIR=true
# Without the -dbgsym package (noautodbgsym): what is tested is the package installed.
(cd "$work/kew" && KEW_WERROR=ON DEB_BUILD_OPTIONS="parallel=$(nproc) noautodbgsym" \
   dpkg-buildpackage -b -us -uc >"$work/build.log" 2>&1) || { tail -40 "$work/build.log"; fail "dpkg-buildpackage"; }
! command -v ccache >/dev/null || grep -q "ccache .*-c .*\.cpp" "$work/build.log" ||
  fail "the package was not compiled through ccache (see $work/build.log)"
grep -Eq -- "-Werror( |$)" "$work/build.log" || fail "the package was not built with warnings as errors"
[ -f "$deb" ] || fail "$deb was not built (found: $(ls "$work"))"
echo "test_deb: built $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"

# Contents: binaries, the unit, the conffile, manual pages, the map, the aerodrome table,
# the alerting rules.
contents=$(dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./|/|')
for path in /usr/bin/kewd /usr/bin/kew-watch /usr/bin/kew-replay /usr/bin/kew-gen /usr/bin/kew-eval \
            /usr/bin/kew-decode /lib/systemd/system/kewd.service /etc/kew/kew.toml \
            /usr/share/man/man8/kewd.8.gz /usr/share/man/man5/kew.toml.5.gz /usr/share/man/man5/kewd.toml.5.gz \
            /usr/share/man/man1/kew-replay.1.gz \
            /usr/share/man/man1/kew-gen.1.gz /usr/share/man/man1/kew-watch.1.gz /usr/share/man/man1/kew-decode.1.gz \
            /usr/share/man/man1/kew-eval.1.gz /usr/share/kew/web/index.html /usr/share/kew/aerodromes.csv \
            /usr/share/kew/prometheus/kew-rules.yml \
            /usr/share/doc/kew/copyright \
            /usr/share/doc/kew/examples/nats/nats-server.conf \
            /usr/share/doc/kew/examples/nats/nats-server.service.d/kew.conf \
            /usr/share/doc/kew/examples/nats/nats-server@.service \
            /usr/share/doc/kew/examples/nats/cluster/kew-bus-1.conf; do
  grep -qx "$path" <<<"$contents" || fail "$path is not in the package"
done
dpkg-deb -f "$deb" Depends | grep -q libjs-leaflet || fail "Depends lacks libjs-leaflet"
dpkg-deb -f "$deb" Depends | grep -q libmodbus || fail "Depends lacks the shared libraries (\${shlibs:Depends})"
dpkg-deb -f "$deb" Depends | grep -q libnats || fail "Depends lacks the NATS C client library"
control=$work/control
dpkg-deb -e "$deb" "$control"
grep -qx /etc/kew/kew.toml "$control/conffiles" || fail "/etc/kew/kew.toml is not a conffile"
grep -q 'deb-systemd-helper' "$control/postinst" || fail "postinst does not enable the unit"
grep -q 'purge' "$control/postrm" || fail "postrm does not clean up on purge"
# The package's version is the release the binaries report (debian/changelog and
# project(VERSION) in CMakeLists.txt move together), and, built without git, its revision.
dpkg-deb -x "$deb" "$work/root"
# The package builds without tests, so its kewd carries no test hook (docs/testing.md).
! grep -q KEWD_TEST_STALL_FILE "$work/root/usr/bin/kewd" || fail "the packaged kewd contains a test hook"
reported=$("$work/root/usr/bin/kewd" --version)
[ "$reported" = "kewd $version ($revision)" ] || fail "kewd --version says '$reported', the package is $version of $revision"
echo "test_deb: contents, conffile, maintainer scripts and version ($reported) as expected"

# lintian, pedantic tags included: any finding fails unless debian/kew.lintian-overrides
# justifies it (docs/operations.md "Install as a service").
lintian --info --pedantic --fail-on error,warning,info,pedantic "$deb" 2>&1 |
  grep -v 'running with root privileges' >"$work/lintian.log" || true
if [ -s "$work/lintian.log" ]; then cat "$work/lintian.log"; fail "lintian has findings"; fi
echo "test_deb: lintian: no finding (overrides: debian/kew.lintian-overrides)"

if [ "${CI:-}" != true ] || [ "$(id -u)" -ne 0 ]; then
  echo "test_deb: install test skipped (it runs only with CI=true as root: it installs and purges the package)"
  exit 0
fi
if dpkg-query -W -f='${Status}' kew 2>/dev/null | grep -q "ok installed"; then
  fail "a kew package is already installed here; the install test will not replace it"
fi

echo "test_deb: dpkg -i $(basename "$deb")"
dpkg -i "$deb" >"$work/install.log" 2>&1 || { cat "$work/install.log"; dpkg --purge kew >/dev/null 2>&1 || true; fail "dpkg -i"; }
trap 'dpkg --purge kew >/dev/null 2>&1 || true' EXIT
if [ -d /run/systemd/system ]; then
  [ "$(systemctl is-enabled kewd)" = enabled ] || fail "systemctl is-enabled kewd: $(systemctl is-enabled kewd)"
  systemctl is-active --quiet kewd || fail "kewd is not running after installation"
else
  # No systemd as PID 1 (a container): the unit is present and enabled for the next boot.
  [ -f /lib/systemd/system/kewd.service ] || fail "the unit is not installed"
  [ -L /etc/systemd/system/multi-user.target.wants/kewd.service ] || fail "the unit is not enabled"
  [ "$(systemctl is-enabled kewd 2>/dev/null || true)" = enabled ] || fail "systemctl is-enabled kewd"
fi
[ "$(dpkg-query -W -f='${Conffiles}' kew | awk '{print $1}')" = /etc/kew/kew.toml ] ||
  fail "dpkg-query Conffiles: $(dpkg-query -W -f='${Conffiles}' kew)"
# The configuration's alert log and state live in the unit's LogsDirectory and
# StateDirectory, which systemd creates at the first start. Without systemd as PID 1 the
# service never started: the check passes before them, saying so; then they are made here
# as systemd would (and must go on purge).
if [ ! -d /run/systemd/system ]; then
  checked=$(kewd --check-config -c /etc/kew/kew.toml) || fail "kewd --check-config before the first start"
  grep -q "^note: .*/var/log/kew does not exist yet; systemd creates it" <<<"$checked" ||
    fail "kewd --check-config before the first start does not say systemd creates /var/log/kew: $checked"
  mkdir -p /var/log/kew /var/lib/kew
fi
checked=$(kewd --check-config -c /etc/kew/kew.toml) || fail "kewd --check-config -c /etc/kew/kew.toml"
# The installed kewd reads the installed aerodrome table by default.
grep -q "^aerodromes file: /usr/share/kew/aerodromes.csv " <<<"$checked" ||
  fail "kewd --check-config does not read /usr/share/kew/aerodromes.csv: $checked"
[ "$(man -w kewd)" = /usr/share/man/man8/kewd.8.gz ] || fail "man -w kewd: $(man -w kewd 2>&1)"
kewd --version | grep -q "($revision)" || fail "kewd --version: $(kewd --version) (built from $revision)"
echo "test_deb: installed: unit enabled, conffile registered, configuration valid, man kewd found"

# Purge: as if the service had run (its log and state), then nothing of kew may remain.
[ -d /run/systemd/system ] || { echo '{}' >/var/log/kew/alerts.jsonl; echo '{}' >/var/lib/kew/kewd.state; }
dpkg --purge kew >"$work/purge.log" 2>&1 || { cat "$work/purge.log"; fail "dpkg --purge"; }
trap - EXIT
for path in /usr/bin/kewd /etc/kew /var/log/kew /var/lib/kew /lib/systemd/system/kewd.service \
            /etc/systemd/system/multi-user.target.wants/kewd.service /usr/share/man/man8/kewd.8.gz; do
  [ ! -e "$path" ] && [ ! -L "$path" ] || fail "$path is left after purge"
done
echo "test_deb: purged: nothing left"
