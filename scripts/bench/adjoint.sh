#!/usr/bin/env bash
# Section "Adjoints": λᵀ ∂v̇/∂(q, v, u) by one solve with M and the generated
# reverse sweep, against forming accelerations_jacobian and its product,
# on the spatial chains of 6, 12, 30 and 60 links (generated/benches/adjoint.rs).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"
# Absolute: criterion writes under it from the bench's own directory.
CARGO_TARGET_DIR="$(realpath -m "$CARGO_TARGET_DIR")"
export CARGO_TARGET_DIR

quietly cargo bench -p dalembert-generated --bench adjoint --features large -- --warm-up-time 1 --measurement-time 3

cat <<'MD'
## Adjoints: the reverse sweep against forming the jacobian

`accelerations_adjoint` (`dalembert::control`: `accelerations`, one solve
`μ = M⁻¹ λ`, then `inverse_dynamics_adjoint`, one reverse sweep over the
Newton–Euler recursion) against `accelerations_jacobian` and the product
`λᵀ J`, on the spatial chains (the sweep alone: columns two and three).

MD
python3 - "$CARGO_TARGET_DIR" "$STAMP" "$(dirname "${BASH_SOURCE[0]}")/lib" <<'PY'
import sys
target, stamp, lib = sys.argv[1:4]
sys.path.insert(0, lib)
from criterion_table import medians
found = {k: v for k, v in medians(target, stamp).items() if k.startswith("adjoint/")}
if not found:
    sys.exit("no adjoint results found: did the bench run?")
ns = sorted({int(k.split("/")[1]) for k in found})
def cell(x):
    return "–" if x is None else (f"{x:.1f}" if x < 100 else f"{x:.0f}")
print("| n | `inverse_dynamics_adjoint` (ns) | per link | `accelerations_adjoint` (ns) "
      "| `accelerations_jacobian` + `λᵀ J` (ns) | jacobian / adjoint |")
print("|---|---|---|---|---|---|")
for n in ns:
    sweep = found.get(f"adjoint/{n}/inverse_dynamics_adjoint")
    adjoint = found.get(f"adjoint/{n}/accelerations_adjoint")
    jacobian = found.get(f"adjoint/{n}/accelerations_jacobian_product")
    per_link = None if sweep is None else sweep / n
    ratio = f"{jacobian / adjoint:.2f}" if jacobian and adjoint else "–"
    print(f"| {n} | {cell(sweep)} | {cell(per_link)} | {cell(adjoint)} | {cell(jacobian)} | {ratio} |")
PY
echo
measured "criterion medians of thread CPU time, 1000 states"
cat <<'MD'

    cargo bench -p dalembert-generated --bench adjoint --features large -- --warm-up-time 1 --measurement-time 3
MD
