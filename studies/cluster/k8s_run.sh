#!/usr/bin/env bash
# A study on Kubernetes, start to end: the shared volume (k8s_volume.yaml), the shards
# (k8s_sweep.yaml), a wait that ends as soon as the shards' Job completes or fails, then the
# merge (k8s_merge.yaml) and its wait. Run from the repository root with kubectl set up:
#
#   STUDY=studies/monte_carlo.toml SHARDS=8 IMAGE=registry.example/wingman:latest \
#       studies/cluster/k8s_run.sh
#
# A Job that failed (a shard that could not run its cases, backoffLimitPerIndex times) ends the
# script with exit 1 and the failed indexes; running the script again starts the Jobs anew and
# each shard runs only what has no result yet. POLL_S (default 30) sets the seconds between
# looks at a Job.
set -euo pipefail

: "${STUDY:?set STUDY to the study file, e.g. studies/monte_carlo.toml}"
: "${SHARDS:?set SHARDS to the number of shards}"
IMAGE="${IMAGE:-wingman:latest}"
POLL_S="${POLL_S:-30}"
here="$(dirname "$0")"

# The manifest $1 with ${STUDY}, ${SHARDS} and ${IMAGE} filled in (and nothing else: the
# shell variables of its commands are the pod's).
render() {
    sed -e "s|\${STUDY}|$STUDY|g" -e "s|\${SHARDS}|$SHARDS|g" -e "s|\${IMAGE}|$IMAGE|g" \
        "$here/$1"
}

# Waits until job $1 has completed (return 0) or failed (exit 1, with its failed indexes).
wait_for() {
    while :; do
        conditions="$(kubectl get "job/$1" \
            -o 'jsonpath={.status.conditions[?(@.status=="True")].type}')"
        case " $conditions " in
        *" Failed "*)
            failed="$(kubectl get "job/$1" -o 'jsonpath={.status.failedIndexes}')"
            echo "k8s_run.sh: job $1 failed (failed indexes: ${failed:-none}); run again to retry" >&2
            exit 1
            ;;
        *" Complete "*) return 0 ;;
        esac
        sleep "$POLL_S"
    done
}

kubectl apply -f "$here/k8s_volume.yaml"
kubectl delete job wingman-sweep wingman-merge --ignore-not-found
render k8s_sweep.yaml | kubectl apply -f -
wait_for wingman-sweep
render k8s_merge.yaml | kubectl apply -f -
wait_for wingman-merge
echo "k8s_run.sh: $(basename "$STUDY" .toml) merged into runs/ on the volume wingman-runs"
