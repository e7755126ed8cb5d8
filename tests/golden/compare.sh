#!/usr/bin/env bash
# Compares two trees written by tests/golden/run.sh: every .h5 by its full-precision dump (h5dump
# -m %.17g, the build version replaced: it names the commit), every .json, .txt and .csv byte for byte
# except the timing lines of --compare's table. A file whose dump differs is classified by
# compare_h5.py: only attributes differ (ATTRIBUTES), or datasets do (DIFFERS, the first listed).
# usage: tests/golden/compare.sh DIR_A DIR_B
set -uo pipefail
a=$1 b=$2 status=0 count=0
version_of() { h5dump -a /h5md/creator/version "$1" 2>/dev/null | sed -n 's/.*(0): "\(.*\)".*/\1/p'; }
dump() { local v; v=$(version_of "$1"); h5dump -m %.17g "$1" | sed "1d; s/$v/VERSION/g"; }
for fa in "$a"/*.h5 "$a"/*/*.h5; do
  [ -e "$fa" ] || continue
  case $fa in *checkpoint*) continue ;; esac
  rel=${fa#"$a"/}; fb=$b/$rel; count=$((count + 1))
  if [ ! -e "$fb" ]; then echo "MISSING $rel"; status=1; continue; fi
  if ! cmp -s <(dump "$fa") <(dump "$fb"); then
    # which objects: datasets (values, shapes) or only attributes (compare_h5.py, with h5py)
    detail=$("$(dirname "$0")/compare_h5.py" "$fa" "$fb" 2>/dev/null); kind=$?
    case $kind in
      2) echo "ATTRIBUTES $rel: $(echo "$detail" | wc -l) attributes differ, every dataset the same" ;;
      *) echo "DIFFERS $rel: $(diff <(dump "$fa") <(dump "$fb") | grep -c '^[<>]') dump lines"
         echo "$detail" | grep -v "@" | head -5 | sed 's/^/    /' ;;
    esac
    status=1
  fi
done
for fa in "$a"/*.json "$a"/*.txt "$a"/*.csv; do
  [ -e "$fa" ] || continue
  rel=${fa#"$a"/}; fb=$b/$rel; count=$((count + 1))
  if [ ! -e "$fb" ]; then echo "MISSING $rel"; status=1; continue; fi
  if ! cmp -s <(grep -v 'coll/s\|wall\|seconds' "$fa") <(grep -v 'coll/s\|wall\|seconds' "$fb"); then echo "DIFFERS $rel"; status=1; fi
done
[ $status -eq 0 ] && echo "golden: $count files identical"
exit $status
