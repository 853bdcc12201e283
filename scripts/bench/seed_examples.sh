#!/usr/bin/env bash
# Section "Seed examples": per-call cost of the generated `mass_matrix`,
# `forcing` and of the runtime's Cholesky solve on seed examples 1 and 2
# (benches/seed_examples.rs). Needs nothing outside this repository.
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

quietly cargo bench --bench seed_examples -- --warm-up-time 1 --measurement-time 3

cat <<'MD'
## Seed examples: the generated code per call

The generated `mass_matrix` and `forcing` of seed examples 1 and 2, and
the generic Cholesky solve `cholesky_accelerations` (`benches/seed_examples.rs`).

MD
table seed
echo
measured "criterion medians"
cat <<'MD'

    cargo bench --bench seed_examples -- --warm-up-time 1 --measurement-time 3
MD
