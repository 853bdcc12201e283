//! The three seed examples, exactly as the language reference writes them, for the unit
//! tests of every layer: the model files of `generated/models`, read at
//! compile time so that there is one copy of each.

/// Seed example 1: the double pendulum.
pub const DOUBLE_PENDULUM: &str = include_str!("../../generated/models/double_pendulum.dal");

/// Seed example 2: the bar on a rotating massless frame.
pub const ROTATING_BAR: &str = include_str!("../../generated/models/rotating_bar.dal");

/// Seed example 3: the pendulum in dependent coordinates.
pub const CONSTRAINED_PENDULUM: &str =
    include_str!("../../generated/models/constrained_pendulum.dal");
