//! Cheap per-node summaries of which symbols an expression may contain:
//! the exact set of symbol *kinds* ([`SymKinds`]) and a 128-bit signature of
//! the symbols themselves ([`Signature`]), both computed once at interning.

use std::ops::BitOr;

use super::Sym;

/// Bit set of symbol kinds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct SymKinds(u8);

impl SymKinds {
    /// No symbols at all (a constant).
    pub const EMPTY: SymKinds = SymKinds(0);
    /// Time `t`.
    pub const TIME: SymKinds = SymKinds(1);
    /// Parameters.
    pub const PARAM: SymKinds = SymKinds(1 << 1);
    /// Generalized coordinates.
    pub const COORD: SymKinds = SymKinds(1 << 2);
    /// Generalized speeds.
    pub const SPEED: SymKinds = SymKinds(1 << 3);
    /// Generalized accelerations.
    pub const ACCEL: SymKinds = SymKinds(1 << 4);
    /// Inputs.
    pub const INPUT: SymKinds = SymKinds(1 << 5);
    /// Lagrange multipliers.
    pub const MULTIPLIER: SymKinds = SymKinds(1 << 6);

    /// Whether every kind in `other` is in `self`.
    pub const fn contains(self, other: SymKinds) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether `self` and `other` share a kind.
    pub const fn intersects(self, other: SymKinds) -> bool {
        self.0 & other.0 != 0
    }

    /// The kinds in either set.
    pub const fn union(self, other: SymKinds) -> SymKinds {
        SymKinds(self.0 | other.0)
    }

    /// The kinds in both sets.
    pub const fn intersection(self, other: SymKinds) -> SymKinds {
        SymKinds(self.0 & other.0)
    }

    /// Whether the set is empty.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }
}

impl BitOr for SymKinds {
    type Output = SymKinds;
    fn bitor(self, other: SymKinds) -> SymKinds {
        self.union(other)
    }
}

impl Sym {
    /// The kind of this symbol, as a one-element [`SymKinds`].
    pub fn kind(self) -> SymKinds {
        match self {
            Sym::Time => SymKinds::TIME,
            Sym::Param(_) => SymKinds::PARAM,
            Sym::Coord(_) => SymKinds::COORD,
            Sym::Speed(_) => SymKinds::SPEED,
            Sym::Accel(_) => SymKinds::ACCEL,
            Sym::Input(_) => SymKinds::INPUT,
            Sym::Multiplier(_) => SymKinds::MULTIPLIER,
        }
    }
}

/// A Bloom-style summary of the symbols in an expression: each symbol sets
/// one bit, an expression the union of its children's. A clear bit proves
/// the symbol absent. Coordinates, speeds and accelerations get 32 bits each,
/// so the test is exact for systems of up to 32 coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(super) struct Signature(u128);

impl Signature {
    /// The signature of one symbol.
    pub(super) fn of(sym: Sym) -> Signature {
        let bit = match sym {
            Sym::Time => 0,
            Sym::Param(i) => 1 + i % 15,
            Sym::Input(i) => 16 + i % 8,
            Sym::Multiplier(i) => 24 + i % 8,
            Sym::Coord(i) => 32 + i % 32,
            Sym::Speed(i) => 64 + i % 32,
            Sym::Accel(i) => 96 + i % 32,
        };
        Signature(1 << bit)
    }

    /// The signature of an expression with both sets of symbols.
    pub(super) fn union(self, other: Signature) -> Signature {
        Signature(self.0 | other.0)
    }

    /// Whether an expression with this signature may contain `sym`.
    pub(super) fn may_contain(self, sym: Sym) -> bool {
        self.0 & Signature::of(sym).0 != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kind_set_operations() {
        let k = SymKinds::COORD | SymKinds::SPEED;
        assert!(k.contains(SymKinds::COORD) && k.contains(SymKinds::EMPTY));
        assert!(!k.contains(SymKinds::COORD | SymKinds::TIME));
        assert!(k.intersects(SymKinds::SPEED | SymKinds::TIME));
        assert!(!k.intersects(SymKinds::PARAM));
        assert!(SymKinds::EMPTY.is_empty() && !k.is_empty());
        assert_eq!(Sym::Multiplier(3).kind(), SymKinds::MULTIPLIER);
    }

    #[test]
    fn signature_is_exact_for_small_indices() {
        let s = Signature::of(Sym::Coord(3)).union(Signature::of(Sym::Speed(31)));
        assert!(s.may_contain(Sym::Coord(3)) && s.may_contain(Sym::Speed(31)));
        for i in (0..32).filter(|&i| i != 3) {
            assert!(!s.may_contain(Sym::Coord(i)));
            assert!(!s.may_contain(Sym::Accel(i)));
        }
        assert!(!s.may_contain(Sym::Time));
        // Beyond 32 coordinates it is a superset, never a false negative.
        assert!(s.may_contain(Sym::Coord(35)));
    }
}
