//! What an integration refuses to start from, before its first evaluation:
//! a time that is NaN, a final time before the initial one, no steps, a
//! step, a tolerance or a first step that is zero, negative or NaN. Each is
//! a [`Failure::InvalidArgument`] at the initial state, never a panic, an
//! endless loop or the initial state returned as if `t_end` were reached.

use super::{Dynamics, Failure, IntegrationError, State};

/// Why the arguments are refused, at `initial`, if `refused`.
fn refuse<const NQ: usize, const NV: usize>(
    initial: &State<NQ, NV>,
    refused: bool,
    reason: &'static str,
) -> Result<(), IntegrationError<NQ>> {
    if refused {
        return Err(IntegrationError::at(
            initial,
            Failure::InvalidArgument { reason },
        ));
    }
    Ok(())
}

/// The span from `initial.t` to `t_end`: both times numbers, the final one
/// not before the initial one, and finite unless `open_ended` (an adaptive
/// integration may run to `+∞`, until a stopping event or its budget).
pub(crate) fn check_span<const NQ: usize, const NV: usize>(
    initial: &State<NQ, NV>,
    t_end: f64,
    open_ended: bool,
) -> Result<(), IntegrationError<NQ>> {
    refuse(
        initial,
        !initial.t.is_finite(),
        "the initial time is not finite",
    )?;
    refuse(initial, t_end.is_nan(), "the final time is NaN")?;
    refuse(
        initial,
        t_end < initial.t,
        "the final time is before the initial time",
    )?;
    refuse(
        initial,
        !open_ended && t_end.is_infinite(),
        "the final time is infinite for a fixed number of steps",
    )
}

/// How many of the `steps` fixed steps over the span from `initial.t` to
/// `t_end` ([`check_span`]) to take: all of them, or none when `t_end` is
/// the initial time (a step of length zero is no step).
pub(crate) fn fixed_steps_to_take<const NQ: usize, const NV: usize>(
    initial: &State<NQ, NV>,
    t_end: f64,
    steps: u64,
) -> Result<u64, IntegrationError<NQ>> {
    check_span(initial, t_end, false)?;
    refuse(initial, steps == 0, "no steps to take to the final time")?;
    Ok(if t_end == initial.t { 0 } else { steps })
}

/// Whether `dynamics` may start from `initial`
/// ([`Dynamics::check_start`]: a constrained start off the velocity form
/// without stabilisation is refused).
pub(crate) fn check_start<D, const NQ: usize, const NV: usize>(
    dynamics: &D,
    initial: &State<NQ, NV>,
) -> Result<(), IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV> + ?Sized,
{
    dynamics
        .check_start(initial)
        .map_err(|cause| IntegrationError::dynamics(initial.t, initial.q, cause))
}

/// A step or a tolerance `value` at `state`: a positive finite number,
/// else refused for `reason`.
pub(crate) fn check_positive<const NQ: usize, const NV: usize>(
    state: &State<NQ, NV>,
    value: f64,
    reason: &'static str,
) -> Result<(), IntegrationError<NQ>> {
    refuse(state, !(value > 0.0 && value.is_finite()), reason)
}

/// Why a step is refused.
pub(crate) const BAD_STEP: &str = "the step is not a positive finite length";

/// A relative and an absolute tolerance: finite, not negative, not both
/// zero.
pub(crate) fn check_tolerances<const NQ: usize, const NV: usize>(
    initial: &State<NQ, NV>,
    relative: f64,
    absolute: f64,
) -> Result<(), IntegrationError<NQ>> {
    let valid = |x: f64| x >= 0.0 && x.is_finite();
    refuse(
        initial,
        !(valid(relative) && valid(absolute) && relative + absolute > 0.0),
        "the tolerances are negative, not finite, or both zero",
    )
}
