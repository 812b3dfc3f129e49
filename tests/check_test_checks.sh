#!/bin/bash
# The shell tests' check DESCRIPTION STATUS takes the condition's status; a command
# substitution in DESCRIPTION runs first and sets $? itself, so `cond; check "... $(x)" $?`
# passes whatever cond said. Such a check must keep the status first:
# `cond; ok=$?; check "... $(x)" $ok`. Lists every check written the unsafe way.
# Usage: check_test_checks.sh TESTS_DIR
bad=$(grep -n 'check ".*\$(.*" \$?[[:space:]]*$' "$1"/*.sh "$1"/support/*.sh)
[ -z "$bad" ] && exit 0
echo "$bad"
echo "check_test_checks: these checks take \$? after a substitution in their description"
exit 1
