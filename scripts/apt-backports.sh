# Sourced by scripts/setup.sh (and tests/scripts/test_apt_backports.sh): derives a
# bookworm-backports apt entry from the machine's own apt sources, so that the repository names no
# mirror. The entry whose suite is `bookworm` (the main Debian archive, not -security or -updates)
# gives the URIs, components and signed-by key; only the suite changes.
#
# Both source formats are read, in apt's order: the one-line sources.list, then
# sources.list.d/*.list and *.sources (deb822) in name order. The result keeps the format it came
# from: a deb822 stanza for rayster-backports.sources, or one line for rayster-backports.list.
#
# RAYSTER_APT_DIR (default /etc/apt) is the folder read; the tests point it at sample files.

apt_dir() { printf '%s\n' "${RAYSTER_APT_DIR:-/etc/apt}"; }

# The source files apt reads, in its order.
apt_source_files() {
  local dir
  dir=$(apt_dir)
  [ -f "$dir/sources.list" ] && printf '%s\n' "$dir/sources.list"
  local f
  for f in "$dir"/sources.list.d/*; do
    case "$f" in *.list | *.sources) [ -f "$f" ] && printf '%s\n' "$f" ;; esac
  done
  return 0
}

# One-line format: prints "OPTIONS<US>URI<US>COMPONENTS" (US: the ASCII unit separator, so that
# empty options survive `read`) of the first `deb` line whose suite is
# suite is exactly bookworm (OPTIONS without the brackets, possibly empty). Fails when there is none.
oneline_bookworm() {
  awk '
    { sub(/#.*/, "") }
    $1 != "deb" { next }
    {
      line = $0; sub(/^[ \t]*deb[ \t]+/, "", line)
      options = ""
      if (substr(line, 1, 1) == "[") {
        end = index(line, "]")
        if (end == 0) next
        options = substr(line, 2, end - 2)
        line = substr(line, end + 1)
      }
      n = split(line, f, /[ \t]+/)
      i = 1; while (i <= n && f[i] == "") i++
      uri = f[i]; suite = f[i + 1]
      if (suite != "bookworm") next
      components = ""
      for (j = i + 2; j <= n; j++) if (f[j] != "") components = components (components == "" ? "" : " ") f[j]
      gsub(/^[ \t]+|[ \t]+$/, "", options)
      printf "%s\037%s\037%s\n", options, uri, components
      found = 1; exit
    }
    END { exit found ? 0 : 1 }' "$1"
}

# deb822 format: prints the first enabled stanza with type deb and suite bookworm as the
# backports stanza (Types, URIs, Suites, Components, Architectures and Signed-By, the last possibly
# an embedded key on continuation lines). Fails when there is none.
deb822_bookworm() {
  awk '
    function flush() {
      if (types ~ /(^| )deb( |$)/ && suites ~ /(^| )bookworm( |$)/ && tolower(enabled) != "no" && uris != "") {
        print "Types: deb"
        print "URIs: " uris
        print "Suites: bookworm-backports"
        print "Components: " components
        if (arch != "") print "Architectures: " arch
        if (signed != "") print "Signed-By:" signed
        found = 1; exit
      }
      types = uris = suites = components = arch = signed = enabled = ""; field = ""
    }
    function trim(s) { gsub(/^[ \t]+|[ \t]+$/, "", s); return s }
    /^#/ { next }
    /^[ \t]*$/ { flush(); next }
    /^[ \t]/ { if (field == "signed-by") signed = signed "\n" $0; next }
    {
      colon = index($0, ":")
      if (colon == 0) next
      field = tolower(trim(substr($0, 1, colon - 1)))
      raw = substr($0, colon + 1)
      value = trim(raw)
      if (field == "types") types = value
      else if (field == "uris") uris = value
      else if (field == "suites") suites = value
      else if (field == "components") components = value
      else if (field == "architectures") arch = value
      else if (field == "enabled") enabled = value
      else if (field == "signed-by") signed = (value == "" ? "" : " " value)
    }
    END { if (!found) flush(); exit found ? 0 : 1 }' "$1"
}

# Whether an enabled entry of either format already names the bookworm-backports suite.
apt_has_backports() {
  local f
  while IFS= read -r f; do
    case "$f" in
      *.sources)
        awk 'BEGIN { s = 0 }
             /^#/ { next }
             /^[ \t]*$/ { if (hit && !off) { s = 1; exit } hit = off = 0; next }
             tolower($1) == "suites:" { for (i = 2; i <= NF; i++) if ($i == "bookworm-backports") hit = 1 }
             tolower($1) == "enabled:" && tolower($2) == "no" { off = 1 }
             END { exit (s || (hit && !off)) ? 0 : 1 }' "$f" && return 0 ;;
      *)
        awk '{ sub(/#.*/, "") } $1 == "deb" && / bookworm-backports([ \t]|$)/ { s = 1; exit } END { exit s ? 0 : 1 }' \
          "$f" && return 0 ;;
    esac
  done < <(apt_source_files)
  return 1
}

# Prints "FILE-NAME<NEWLINE>CONTENTS": the file to write under sources.list.d and what to write,
# derived from the first bookworm entry. Fails with a message on stderr when there is none.
backports_entry() {
  local f entry
  while IFS= read -r f; do
    case "$f" in
      *.sources)
        if entry=$(deb822_bookworm "$f"); then
          printf 'rayster-backports.sources\n%s\n' "$entry"
          return 0
        fi ;;
      *)
        if entry=$(oneline_bookworm "$f"); then
          local options uri components
          IFS=$'\037' read -r options uri components <<<"$entry"
          printf 'rayster-backports.list\ndeb %s%s bookworm-backports %s\n' "${options:+[$options] }" "$uri" \
            "$components"
          return 0
        fi ;;
    esac
  done < <(apt_source_files)
  local dir
  dir=$(apt_dir)
  echo "setup: error: no apt entry for Debian bookworm in $dir/sources.list or $dir/sources.list.d/;" \
    "add a bookworm-backports entry for your Debian mirror (the same URI and components as your bookworm" \
    "entry, suite bookworm-backports) and re-run" >&2
  return 1
}

# Adds the backports entry unless one exists. Prints what it did; returns 0 when it wrote a file
# (the caller then runs apt-get update), 1 when nothing was needed, 2 when no entry can be derived.
# $SUDO (empty or "sudo") writes the file.
add_backports() {
  apt_has_backports && return 1
  local entry name dir
  entry=$(backports_entry) || return 2
  name=${entry%%$'\n'*}
  dir="$(apt_dir)/sources.list.d"
  echo "setup: adding the bookworm-backports suite ($dir/$name, from the bookworm entry)"
  printf '# Added by Rayster scripts/setup.sh: bookworm-backports of the archive of your bookworm entry.\n%s\n' \
    "${entry#*$'\n'}" | ${SUDO:-} tee "$dir/$name" >/dev/null
  return 0
}
