#!/bin/sh
# Rebuilds the shipped models in resources/models from `archet new bowed-string`: the
# full-bandwidth strings at the paper's four pitches, homogeneous and harmonic, and the paper's
# own chaplets as *-paper. Each carries the stroke the builder found in its Helmholtz band.
# Usage: packaging/make-shipped-models.sh [path/to/archet]
set -eu
archet=${1:-build/bin/archet}
out=resources/models
for pitch in 110 220 440 880; do
    for tuning in homogeneous harmonic; do
        suffix=$([ "$tuning" = harmonic ] && echo -harmonic || true)
        "$archet" new bowed-string --pitch "$pitch" --tuning "$tuning" \
            -o "$out/bowed-string-$pitch$suffix.json"
        "$archet" new bowed-string --pitch "$pitch" --tuning "$tuning" --paper \
            -o "$out/bowed-string-$pitch$suffix-paper.json"
    done
done
