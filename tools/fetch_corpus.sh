#!/usr/bin/env bash
# Fetch the corpus of LaTeX written by others that tools/corpus.py audits (issues 65, 66): each
# source of tools/corpus-sources.md (`## owner/repo`, then its `commit:`) cloned from GitHub and
# checked out at that commit into CORPUS/owner__repo, with only its LaTeX and Markdown files kept
# (.tex .md .sty .cls .bib .bst .clo .cfg, README and LICENSE). Needs the network; the corpus is
# never committed (the sources' licences vary).
#
#   bash tools/fetch_corpus.sh /work/corpus
#   python3 tools/corpus.py /work/corpus --sources /work/corpus/SOURCES.md --out reports/corpus.md
set -euo pipefail
out=${1:?usage: fetch_corpus.sh CORPUS_DIR}
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out"
cp "$here/corpus-sources.md" "$out/SOURCES.md"
repo=""
while IFS= read -r line; do
  case "$line" in
    "## "*) repo="${line#\#\# }"; repo="${repo//\`/}" ;;
    *"commit:"*)
      commit=$(grep -oE '[0-9a-f]{40}' <<<"$line" | head -1)
      [ -n "$repo" ] && [ -n "$commit" ] || continue
      dest="$out/${repo/\//__}"
      if [ -d "$dest" ]; then echo "have $repo"; continue; fi
      echo "fetching $repo at $commit"
      tmp=$(mktemp -d)
      git clone -q --filter=blob:none "https://github.com/$repo.git" "$tmp/src"
      git -C "$tmp/src" checkout -q "$commit"
      mkdir -p "$dest"
      (cd "$tmp/src" && find . -type f \( -name '*.tex' -o -name '*.md' -o -name '*.sty' -o -name '*.cls' \
          -o -name '*.bib' -o -name '*.bst' -o -name '*.clo' -o -name '*.cfg' -o -iname 'README*' \
          -o -iname 'LICENSE*' -o -iname 'COPYING*' \) -not -path './.git/*' -print0 \
        | xargs -0 -I{} cp --parents {} "$dest/")
      rm -rf "$tmp"
      repo="" ;;
  esac
done < "$here/corpus-sources.md"
