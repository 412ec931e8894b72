#!/bin/sh
# make test's install step: the egg as a new user meets it.
#   1. a clean copy of this tree: the files git knows (tracked, or new and
#      not ignored), as a fresh clone holds them, with no build products;
#   2. an ordinary user (as root, this script makes one: downstroke-test)
#      and a private repository, CHICKEN's own repository after it;
#   3. chicken-install -test there: builds, installs and runs every suite,
#      the docs suite included, which then builds docs/guide.org's game with
#      csc -static and runs it from another directory with no CHICKEN
#      variable set;
#   4. chicken-status shows the egg with the version in downstroke.egg.
# Everything lives in one temporary directory, removed at the end.
set -e
if [ "$1" = --as-user ]; then
  work="$2"
  cd "$work/src"
  CHICKEN_INSTALL_REPOSITORY="$work/repo"
  CHICKEN_REPOSITORY_PATH="$work/repo:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository)"
  TMPDIR="$work/tmp"
  export CHICKEN_INSTALL_REPOSITORY CHICKEN_REPOSITORY_PATH TMPDIR
  mkdir -p "$work/repo" "$work/tmp"
  echo "install-test: chicken-install -test as $(id -un), into $work/repo"
  # the build's csc command lines go to a log; the suites' output is shown
  status=0
  chicken-install -test > "$work/install.log" 2>&1 || status=$?
  grep -v '^   /' "$work/install.log" || true
  if [ "$status" -ne 0 ]; then
    echo "install-test: chicken-install -test failed (exit $status); its last lines:"
    tail -40 "$work/install.log"
    exit 1
  fi
  version="$(sed -n 's/^ *(version "\([^"]*\)").*/\1/p' downstroke.egg)"
  listed="$(chicken-status downstroke)"
  echo "install-test: chicken-status says: $listed"
  case "$listed" in
    *downstroke*"$version"*) ;;
    *) echo "install-test: chicken-status does not list downstroke $version"; exit 1 ;;
  esac
  exit 0
fi

here="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d "${TMPDIR:-/tmp}/downstroke-install.XXXXXX")"
trap 'rm -rf "$work"' EXIT
mkdir "$work/src"
if git -C "$here" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  (cd "$here" && git ls-files -z --cached --others --exclude-standard |
     tar --null -T - -cf - 2>/dev/null) | tar -xf - -C "$work/src"
else
  # not a git checkout (a release tarball): everything but build products
  (cd "$here" && tar --exclude=./build --exclude=./build2 --exclude='./downstroke.*.so' \
     --exclude='./downstroke.*.o' --exclude='./downstroke.*.link' -cf - .) | tar -xf - -C "$work/src"
fi
chmod 755 "$work"

if [ "$(id -u)" -eq 0 ]; then
  user=downstroke-test
  id "$user" >/dev/null 2>&1 || useradd --create-home --shell /bin/sh "$user"
  chown -R "$user" "$work"
  su "$user" -s /bin/sh -c "sh '$work/src/tools/install-test.sh' --as-user '$work'"
else
  sh "$work/src/tools/install-test.sh" --as-user "$work"
fi
