#!/usr/bin/env bash
# The rules the code follows are written in the repository's own docs/, and
# every citation of them lands (docs/architecture.md, "Where the rules are
# written"). Over the tracked text files of a source tree this fails when
#   - a file outside docs/ names the outside brief (the word in capitals, as
#     a document) instead of a page of docs/;
#   - a cited docs/<page>.md does not exist;
#   - a section cited in the weathering model (model.md and a section sign
#     on one line, or any section sign inside docs/model.md) has no
#     "## §N " heading there;
#   - a relative Markdown link in README.md or docs/ points at a file that
#     does not exist, or at a heading that page does not have.
# Usage: citations_test.sh SOURCE_DIR      check the tree
#        citations_test.sh --self-test     plant each kind of bad citation in
#                                          a scratch tree and check that the
#                                          check catches it
set -uo pipefail
export LC_ALL=C.UTF-8

# The outside brief's name, assembled so that this file does not name it.
brief_word='S''PEC'

# Tracked files (or, outside a git checkout, every file but build output),
# relative to the tree, text only.
text_files() {
  local root=$1
  if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git -C "$root" ls-files -z
  else
    (cd "$root" && find . -type f -not -path './.git/*' -not -path './build*' -not -path '*/node_modules/*' \
      -printf '%P\0')
  fi | (cd "$root" && xargs -0 -r grep -IlZ '' --) | tr '\0' '\n'
}

# GitHub's anchor for a heading: lower case, punctuation and symbols dropped,
# spaces to hyphens.
slug() {
  tr 'A-Z' 'a-z' | LC_ALL=C sed -e 's/[^a-z0-9 _-]//g' -e 's/ /-/g'
}

# Prints one line per problem in the tree at $1; returns the count (capped).
check_tree() {
  local root=$1 problems=0 files file
  files=$(text_files "$root")

  # 1. The outside brief, named outside docs/.
  while IFS= read -r file; do
    [[ $file == docs/* ]] && continue
    while IFS= read -r hit; do
      echo "$file:$hit: names the outside brief; cite a page of docs/ instead"
      problems=$((problems + 1))
    done < <(grep -nE "(^|[^A-Za-z0-9_])${brief_word}([^A-Za-z0-9_]|$)|(^|[^A-Za-z0-9_])[Ss]pec(\.md)? ?§" "$root/$file" |
      cut -d: -f1)
  done <<<"$files"

  # 2. Every cited docs/<page>.md exists.
  while IFS= read -r file; do
    while IFS=: read -r line cited; do
      cited=${cited#"${cited%%docs/*}"}
      if [[ ! -f $root/$cited ]]; then
        echo "$file:$line: cites $cited, which does not exist"
        problems=$((problems + 1))
      fi
    done < <(grep -noE '(^|[^A-Za-z0-9_./-])docs/[A-Za-z0-9_-]+\.md' "$root/$file")
  done <<<"$files"

  # 3. Every section of the model that is cited has its heading.
  local sections=" "
  if [[ -f $root/docs/model.md ]]; then
    sections+=$(sed -nE 's/^## §([0-9]+) .*/\1/p' "$root/docs/model.md" | tr '\n' ' ')
  fi
  while IFS= read -r file; do
    local pattern='model\.md'
    [[ $file == docs/model.md ]] && pattern='§'
    while IFS=: read -r line text; do
      while IFS= read -r ref; do
        local part
        for part in $(sed -E 's/(–|-)/ /g; s/§//g' <<<"$ref"); do
          if [[ ! $part =~ ^[0-9]+$ || $sections != *" $part "* ]]; then
            echo "$file:$line: cites docs/model.md §$part, which has no '## §$part ' heading"
            problems=$((problems + 1))
          fi
        done
      done < <(grep -oE '§[0-9][0-9.]*((–|-)§?[0-9][0-9.]*)?' <<<"$text")
    done < <(grep -nE "$pattern" "$root/$file" | grep '§')
  done <<<"$files"

  # 4. Relative links in README.md and docs/ land on a file, and on a heading of it.
  while IFS= read -r file; do
    [[ $file == README.md || $file == docs/*.md ]] || continue
    local dir
    dir=$(dirname "$file")
    while IFS=: read -r line target; do
      target=${target#](}
      target=${target%)}
      [[ $target =~ ^[a-z]+: ]] && continue  # http:, https:, mailto:
      local path=${target%%#*} anchor=""
      [[ $target == *'#'* ]] && anchor=${target#*#}
      local resolved=$file
      [[ -n $path && $dir == . ]] && resolved=$path
      [[ -n $path && $dir != . ]] && resolved=$dir/$path
      if [[ ! -e $root/$resolved ]]; then
        echo "$file:$line: links to $target, which does not exist"
        problems=$((problems + 1))
      elif [[ -n $anchor && $resolved == *.md ]] &&
        ! sed -nE 's/^#+ +//p' "$root/$resolved" | slug | grep -qxF -- "$anchor"; then
        echo "$file:$line: links to $target, but $resolved has no such heading"
        problems=$((problems + 1))
      fi
    done < <(grep -noE '\]\([^) ]+\)' "$root/$file")
  done <<<"$files"

  return $((problems > 100 ? 100 : problems))
}

# A small tree that passes, then each kind of bad citation planted in a copy
# of it: the check must pass the first and fail every other.
self_test() {
  local scratch failures=0
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' RETURN
  make_tree() {
    rm -rf "$1" && mkdir -p "$1/docs" "$1/src"
    printf '# Model\n\n## §1 Grid\n\nAs §2 says.\n\n## §2 Exposure\n' >"$1/docs/model.md"
    printf '# Formats\n\n## `rock.vdb`\n\nSee [the model](model.md) and [grids](#rockvdb).\n' >"$1/docs/formats.md"
    printf '# Tool\n\n[model](docs/model.md), [vdb](docs/formats.md#rockvdb).\n' >"$1/README.md"
    printf '// Grids (docs/model.md §1, §2; docs/formats.md).\nint BubbleSpec;\n' >"$1/src/grid.h"
    git -C "$1" init -q && git -C "$1" add -A
  }
  expect() {  # expect pass|fail DESCRIPTION: checks the tree in $scratch/t
    local want=$1 what=$2 out
    out=$(check_tree "$scratch/t")
    local status=$?
    if [[ $want == pass && $status -ne 0 ]] || [[ $want == fail && $status -eq 0 ]]; then
      echo "FAIL: $what: the check should $want here"
      [[ -n $out ]] && echo "$out"
      failures=$((failures + 1))
    else
      echo "ok: $what${out:+ → ${out%%$'\n'*}}"
    fi
  }
  plant() {  # plant FILE TEXT: a fresh tree with TEXT appended to FILE
    make_tree "$scratch/t"
    printf '%s\n' "$2" >>"$scratch/t/$1"
    git -C "$scratch/t" add -A
  }

  make_tree "$scratch/t"
  expect pass "a clean tree"
  plant src/grid.h "// See ${brief_word} §2.3."
  expect fail "the outside brief named in code"
  plant src/grid.h "// See ${brief_word}.md."
  expect fail "the outside brief's file named in code"
  plant src/grid.h "// As the sp""ec §2.3 says."
  expect fail "the outside brief cited by section in lower case"
  plant docs/""notes.md "The ${brief_word} says so."
  expect pass "the outside brief named inside docs/"
  plant src/grid.h "// See docs/""dependencies.md."
  expect fail "a docs page that does not exist"
  plant src/grid.h "// (docs/model.md §""3)"
  expect fail "a model section without a heading"
  plant src/grid.h "// (docs/model.md §""2.8)"
  expect fail "a model section numbered the outside brief's way"
  plant src/grid.h "// (docs/model.md §1–""2.9)"
  expect fail "a range of model sections ending at one without a heading"
  plant src/grid.h "// (docs/model.md §1–§2)"
  expect pass "a range of model sections that all exist"
  plant docs/model.md "As §""7 says."
  expect fail "a section the model cites in itself without a heading"
  plant docs/formats.md "[gone](missing.md)"
  expect fail "a relative link to a missing page"
  plant README.md "[vdb](docs/formats.md#no-such-heading)"
  expect fail "a link to a heading that does not exist"
  plant README.md "[site](https://example.org/x.md)"
  expect pass "an outside link"

  ((failures == 0)) || return 1
  echo "ok: every planted bad citation is caught"
}

if [[ ${1:-} == --self-test ]]; then
  self_test
  exit $?
fi
[[ $# -eq 1 && -d $1 ]] || {
  echo "usage: citations_test.sh SOURCE_DIR | --self-test" >&2
  exit 2
}
check_tree "$1"
status=$?
if ((status > 0)); then
  echo "FAIL: $status citation problem(s) above (100 or more are counted as 100)"
  exit 1
fi
echo "ok: every citation lands in docs/"
