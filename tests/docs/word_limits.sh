#!/usr/bin/env bash
# The docs stay references a reader can take in: README.md at most 1,200 words, every other Markdown file
# of the project (third_party and build folders aside) at most 3,500, as `wc -w` counts words.
# Usage: word_limits.sh ROOT
# It first checks itself on a made-up tree with one file a word over each limit, so it is known to fire.
set -euo pipefail
root=$1

# Prints one line per file over its limit; returns 1 if there was one.
check() {
    local dir=$1 over=0 words limit f
    while IFS= read -r -d '' f; do
        words=$(wc -w < "$f")
        limit=3500
        [[ $f == "$dir/README.md" ]] && limit=1200
        if (( words > limit )); then
            echo "${f#"$dir"/}: $words words, over the limit of $limit"
            over=1
        fi
    done < <(find "$dir" -name '*.md' -not -path '*/third_party/*' -not -path '*/build*' -not -path '*/.git/*' -print0)
    return $over
}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/docs"
printf 'word\n%.0s' {1..1200} > "$tmp/README.md"
printf 'word\n%.0s' {1..3500} > "$tmp/docs/AT_LIMIT.md"
check "$tmp" > /dev/null || { echo "self-test: files at the limits were refused"; exit 1; }
echo word >> "$tmp/README.md"
echo word >> "$tmp/docs/AT_LIMIT.md"
said=$(check "$tmp" || true)
[[ $(grep -c "over the limit" <<< "$said") == 2 ]] || { echo "self-test: files a word over were not both refused: $said"; exit 1; }

if ! check "$root"; then
    echo "FAIL: shorten the files above (history goes into commit messages, detail into the doc that owns it)"
    exit 1
fi
echo "every Markdown file is within its word limit"
