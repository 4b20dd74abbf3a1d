# The firmware check's verdict on one performance target (sourced by
# scripts/firmware-check.sh; tests/test_fw_target.py runs it alone).
#
#   target NAME VALUE LIMIT
#
# Prints "met" when VALUE <= LIMIT. Otherwise, and when VALUE is empty (not
# measured), prints "MISSED" and appends to FAILURES, so the check fails.
target() {
    if [ -z "$2" ]; then
        echo "  MISSED  $1: not measured"
        FAILURES+=("$1: not measured")
    elif awk -v v="$2" -v l="$3" 'BEGIN { exit !(v <= l) }'; then
        echo "  met     $1: $2 <= $3"
    else
        echo "  MISSED  $1: $2 > $3"
        FAILURES+=("missed $1: $2 > $3")
    fi
}
