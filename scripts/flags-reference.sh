#!/bin/bash
# Writes docs/flags.md to stdout: every command's `--help`, as the binary given prints it. The flags'
# help lives once, in the code (apps/ and src/requests/integrator_parameters.cpp); this page is made
# from it, and the test Docs.FlagReferenceIsTheHelp fails when the page and the binary disagree.
#   bash scripts/flags-reference.sh build/tripath > docs/flags.md
set -euo pipefail
tripath=${1:?usage: flags-reference.sh path/to/tripath}
echo "# Every flag"
echo
echo "What \`tripath --help\` and \`tripath <command> --help\` print, made by"
echo "\`bash scripts/flags-reference.sh build/tripath > docs/flags.md\` (a test checks that it is current)."
echo "What the flags mean together: [command-line.md](command-line.md), [compare.md](compare.md)."
for command in "" render scenes reference compare benchmark export montage; do
    echo
    echo "## tripath${command:+ $command}"
    echo
    echo '```'
    # shellcheck disable=SC2086
    "$tripath" $command --help
    echo '```'
done
