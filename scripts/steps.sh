# Sourced by .ci/run and scripts/test.sh: `step NAME` starts a timed step (and ends the one
# before), `steps_summary [LIMIT]` ends the last one and prints each step's seconds, the
# total and the slowest steps; with LIMIT, the total's share of LIMIT seconds too, and a
# warning past half of it.
# Seconds are bash's SECONDS, whole seconds since the sourcing script started.

STEP_NAMES=()
STEP_STARTS=()
STEP_PREFIX="${STEP_PREFIX:-==}"

step() {
    STEP_NAMES+=("$*")
    STEP_STARTS+=("$SECONDS")
    echo "$STEP_PREFIX [${SECONDS} s] $*"
}

steps_summary() {
    local limit="${1:-}" end="$SECONDS" count="${#STEP_NAMES[@]}" i next
    local table=""
    for ((i = 0; i < count; i++)); do
        if ((i + 1 < count)); then next="${STEP_STARTS[i + 1]}"; else next="$end"; fi
        table+="$((next - STEP_STARTS[i]))"$'\t'"${STEP_NAMES[i]}"$'\n'
    done
    echo "$STEP_PREFIX steps (seconds):"
    printf '%s' "$table" | awk -F'\t' '{ printf "   %6d  %s\n", $1, $2 }'
    echo "$STEP_PREFIX slowest:"
    printf '%s' "$table" | sort -t$'\t' -k1,1nr | head -n 3 | awk -F'\t' '{ printf "   %6d  %s\n", $1, $2 }'
    if [[ -z "$limit" ]]; then
        echo "$STEP_PREFIX total ${end} s"
        return
    fi
    local share=$((100 * end / limit))
    echo "$STEP_PREFIX total ${end} s: ${share} % of the ${limit} s limit"
    if ((2 * end > limit)); then
        echo "$STEP_PREFIX warning: past half of the ${limit} s limit; the margin is eroding" \
            "(cut the slowest steps above)"
    fi
}
