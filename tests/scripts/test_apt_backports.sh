#!/usr/bin/env bash
# scripts/apt-backports.sh on sample apt folders: the backports entry is derived from the bookworm
# entry (deb822 and one-line, with [signed-by=...] options), an existing backports entry leaves
# everything alone, and a machine with no bookworm entry gets a clear error and no file.
# Run by ctest (apt_backports); never touches the machine's own /etc/apt.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../../scripts/apt-backports.sh"
SUDO=""

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT

# A fresh apt folder named $1; prints its path.
apt_folder() {
  mkdir -p "$root/$1/sources.list.d"
  printf '%s\n' "$root/$1"
}

# add_backports in folder $1; expects status $2 and prints nothing else.
run_add() {
  local status=0
  RAYSTER_APT_DIR=$1 add_backports >"$1/stdout" 2>"$1/stderr" || status=$?
  [ "$status" = "$2" ] || fail "$1: add_backports returned $status, expected $2 ($(cat "$1/stderr"))"
}

expect_file() { # folder, name, expected contents (without the header comment)
  local got
  if [ ! -f "$1/sources.list.d/$2" ]; then fail "$1: $2 was not written"; return; fi
  got=$(grep -v '^# Added by Rayster' "$1/sources.list.d/$2")
  [ "$got" = "$3" ] || fail "$1/$2: got
$got
expected
$3"
}

# deb822, like a stock Debian 12 image: security first, bookworm with -updates in one stanza.
d=$(apt_folder deb822)
cat >"$d/sources.list.d/debian.sources" <<'X'
Types: deb
# the security archive comes first here on purpose
URIs: http://security.mirror.example/debian-security
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb deb-src
# http://snapshot.example/archive/debian/20250520T000000Z
URIs: http://mirror.example/debian
Suites: bookworm bookworm-updates
Components: main contrib non-free-firmware
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
X
run_add "$d" 0
expect_file "$d" rayster-backports.sources "Types: deb
URIs: http://mirror.example/debian
Suites: bookworm-backports
Components: main contrib non-free-firmware
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg"
grep -q 'rayster-backports.sources' "$d/stdout" || fail "deb822: says nothing about the file it wrote"
# Idempotent: the entry it wrote counts as a backports entry.
cp "$d/sources.list.d/rayster-backports.sources" "$root/first"
run_add "$d" 1
cmp -s "$root/first" "$d/sources.list.d/rayster-backports.sources" || fail "deb822: second run changed the file"

# deb822 with a disabled bookworm stanza before the enabled one, and an embedded key.
d=$(apt_folder deb822-embedded)
cat >"$d/sources.list.d/a.sources" <<'X'
Types: deb
URIs: http://old.mirror.example/debian
Suites: bookworm
Components: main
Enabled: no
X
cat >"$d/sources.list.d/b.sources" <<'X'
Types: deb
URIs: https://mirror.example/debian
Suites: bookworm
Components: main
Architectures: amd64
Signed-By:
 -----BEGIN PGP PUBLIC KEY BLOCK-----
 .
 mQINBGPL0BUBEADmW5NdOOHwPIJlgPu6JDcKw/NZJPR8lsD3K87ZM18gzyQZJD+w
 -----END PGP PUBLIC KEY BLOCK-----
X
run_add "$d" 0
expect_file "$d" rayster-backports.sources "Types: deb
URIs: https://mirror.example/debian
Suites: bookworm-backports
Components: main
Architectures: amd64
Signed-By:
 -----BEGIN PGP PUBLIC KEY BLOCK-----
 .
 mQINBGPL0BUBEADmW5NdOOHwPIJlgPu6JDcKw/NZJPR8lsD3K87ZM18gzyQZJD+w
 -----END PGP PUBLIC KEY BLOCK-----"

# One-line sources.list with options; deb-src, security and a commented-out backports line first.
d=$(apt_folder oneline-options)
cat >"$d/sources.list" <<'X'
# deb http://mirror.example/debian bookworm-backports main
deb-src http://mirror.example/debian bookworm main
deb http://security.mirror.example/debian-security bookworm-security main
deb [arch=amd64 signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://mirror.example/debian bookworm main non-free-firmware # stock
X
run_add "$d" 0
expect_file "$d" rayster-backports.list \
  "deb [arch=amd64 signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://mirror.example/debian bookworm-backports main non-free-firmware"
run_add "$d" 1

# One-line *.list without options.
d=$(apt_folder oneline-plain)
echo 'deb http://mirror.example/debian/ bookworm main' >"$d/sources.list.d/mirror.list"
run_add "$d" 0
expect_file "$d" rayster-backports.list "deb http://mirror.example/debian/ bookworm-backports main"

# Already there, as today's setup.sh wrote it: nothing to do.
d=$(apt_folder existing)
cp "$root/deb822/sources.list.d/debian.sources" "$d/sources.list.d/"
echo 'deb http://mirror.example/debian bookworm-backports main' >"$d/sources.list.d/rayster-backports.list"
run_add "$d" 1
[ ! -e "$d/sources.list.d/rayster-backports.sources" ] || fail "existing: wrote a second backports entry"

# Nothing to derive from: only security and a third-party archive (and files apt ignores).
d=$(apt_folder nothing)
echo 'deb http://security.mirror.example/debian-security bookworm-security main' >"$d/sources.list"
printf 'Types: deb\nURIs: https://vendor.example/apt\nSuites: nodistro\nComponents: main\n' \
  >"$d/sources.list.d/vendor.sources"
echo 'deb http://mirror.example/debian bookworm main' >"$d/sources.list.d/old.list.disabled"
run_add "$d" 2
grep -q 'bookworm-backports' "$d/stderr" || fail "nothing: the error does not say what to add"
[ "$(wc -l <"$d/stderr")" = 1 ] || fail "nothing: the error is not one line"
ls "$d/sources.list.d" | grep -q rayster && fail "nothing: wrote a file"

# The repository names no host in its scripts.
if grep -rEn '[a-z0-9-]+\.(debian\.org|org|com|net)' "$here/../../scripts/"; then fail "scripts/ name a host"; fi

[ "$failures" = 0 ] && echo "apt-backports: all cases pass"
exit "$((failures > 0))"
