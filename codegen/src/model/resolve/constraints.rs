//! The `constraint` and `closure` statements: rows of `A v̇ = b`, written
//! out or made from the points and frames a loop closure joins.

use super::Resolver;
use super::evaluate::{CONSTRAINT, GEOMETRY};
use super::scope::Binding;
use crate::expr::SymKinds;
use crate::language::ast::{Expr, Field, SpanRange};
use crate::language::keyword::Symbol;
use crate::language::keyword::field::{ALONG, AT, AXIS, FRAME, TO, WELDED};
use crate::model::closure::{ClosureKind, closure_rows};
use crate::model::{Constraint, PointId};
use proc_macro2::Ident;

impl Resolver {
    pub(super) fn constraint(&mut self, keyword: &Ident, lhs: &Expr, rhs: &Expr) {
        let (Some(l), Some(r)) = (self.scalar(lhs, CONSTRAINT), self.scalar(rhs, CONSTRAINT))
        else {
            return;
        };
        let residual = self.pool.sub(l, r);
        let span = SpanRange::new(keyword.span(), rhs.range().end);
        if !self.check_constrains_something(span, residual) {
            return;
        }
        let nonholonomic = self.pool.kinds(residual).intersects(SymKinds::SPEED);
        if nonholonomic && !self.check_linear_in_speeds(span, residual) {
            return;
        }
        self.model.constraints.push(Constraint {
            residual,
            nonholonomic,
            vanishes: false,
        });
    }

    /// `closure NAME { at: P, to: Q };` (spherical), with `axis: F.z,
    /// along: G.z` (revolute) or `frame: F, welded: G` (welded): ordinary
    /// holonomic rows, those that vanish identically dropped (see
    /// [`closure_rows`]).
    pub(super) fn closure(&mut self, name: &Ident, fields: &[Field]) {
        self.define(name, Binding::Closure);
        let Some((at, to, kind)) = self.closure_fields(name, fields) else {
            return;
        };
        let at = at.and_then(|e| self.point(e, GEOMETRY));
        let to = to.and_then(|e| self.point(e, GEOMETRY));
        if let (Some(at), Some(to), Some(kind)) = (at, to, kind) {
            self.add_closure_rows(name, at, to, kind);
        }
    }

    /// A closure's points `at` and `to` and its kind, from which pair of
    /// fields it has (revolute: `axis`, `along`; welded: `frame`,
    /// `welded`; spherical: neither); `None` if it mixes the two.
    fn closure_fields<'a>(
        &mut self,
        name: &Ident,
        fields: &'a [Field],
    ) -> Option<(Option<&'a Expr>, Option<&'a Expr>, Option<ClosureKind>)> {
        let has = |pair: [Symbol; 2]| fields.iter().any(|f| pair.iter().any(|n| f.name == *n));
        let (revolute, welded) = (has([AXIS, ALONG]), has([FRAME, WELDED]));
        if revolute && welded {
            self.errors.push(
                name.span(),
                format!(
                    "closure `{name}` mixes the fields of a revolute closure (`axis`, `along`) \
                     and of a welded one (`frame`, `welded`); give one pair, or neither for a \
                     spherical closure"
                ),
            );
            return None;
        }
        Some(if revolute {
            let [at, to, axis, along] =
                self.fields(name, "revolute closure", fields, [AT, TO, AXIS, ALONG]);
            let axis = axis.and_then(|e| self.frame_axis(e));
            let along = along.and_then(|e| self.frame_axis(e));
            let kind = axis
                .zip(along)
                .map(|(axis, along)| ClosureKind::Revolute { axis, along });
            (at, to, kind)
        } else if welded {
            let [at, to, frame, welded] =
                self.fields(name, "welded closure", fields, [AT, TO, FRAME, WELDED]);
            let frame = frame.and_then(|e| self.frame(e));
            let welded = welded.and_then(|e| self.frame(e));
            let kind = frame
                .zip(welded)
                .map(|(frame, welded)| ClosureKind::Welded { frame, welded });
            (at, to, kind)
        } else {
            let [at, to] = self.fields(name, "closure", fields, [AT, TO]);
            (at, to, Some(ClosureKind::Spherical))
        })
    }

    /// The rows of closure `name` that do not vanish identically, each
    /// checked to involve a coordinate; an error if none is left.
    fn add_closure_rows(&mut self, name: &Ident, at: PointId, to: PointId, kind: ClosureKind) {
        let (mut added, mut rejected) = (0, 0);
        for row in closure_rows(&self.model, &mut self.pool, at, to, kind) {
            if self.pool.is_zero(row.residual) {
                continue;
            }
            if !self.pool.kinds(row.residual).intersects(SymKinds::COORD) {
                self.errors.push(
                    name.span(),
                    format!(
                        "closure `{name}` can never hold: {} involves no coordinate and is \
                         not identically zero; join points (and frames) that the coordinates move",
                        row.what
                    ),
                );
                rejected += 1;
                continue;
            }
            self.model.constraints.push(Constraint {
                residual: row.residual,
                nonholonomic: false,
                vanishes: false,
            });
            added += 1;
        }
        if added + rejected == 0 {
            self.errors.push(
                name.span(),
                format!(
                    "closure `{name}` constrains nothing: what it joins coincides in every \
                     configuration"
                ),
            );
        }
    }
}
